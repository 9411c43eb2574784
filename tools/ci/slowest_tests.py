#!/usr/bin/env python3
"""Prints the slowest tests of one or more ctest JUnit files (ctest --output-junit), slowest first.

    tools/ci/slowest_tests.py [--most N] [--cost-data OUT] FILE.xml [FILE.xml ...]

Each row: seconds, the file's label (its name without .xml) and the test's name; the tests that
failed are listed after them, by name, so the end of CI's log says which. ctest writes a
test's wall time as the testcase's `time` attribute; a missing or empty file is said, not fatal,
so a CI run that failed before its tests still prints its stage table.

--cost-data OUT also writes the tests' times as ctest's cost data (CTestCostData.txt: a line
`NAME RUNS SECONDS` a test, then `---`), from which ctest -j starts the longest tests first; the
Makefile seeds a fresh build's with tests/ctest_costs/ (BENCHMARKS.md, "CI's time").
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--most", type=int, default=10)
    ap.add_argument("--cost-data")
    ap.add_argument("files", nargs="+")
    args = ap.parse_args()
    rows = []
    failed = []
    for path in args.files:
        label = os.path.splitext(os.path.basename(path))[0]
        try:
            root = ET.parse(path).getroot()
        except (OSError, ET.ParseError) as e:
            print(f"  ({path}: {e})")
            continue
        for case in root.iter("testcase"):
            try:
                seconds = float(case.get("time", "0"))
            except ValueError:
                continue
            rows.append((seconds, label, case.get("name", "?")))
            if case.get("status") == "fail" or case.find("failure") is not None:
                failed.append((label, case.get("name", "?")))
    rows.sort(key=lambda r: -r[0])
    if args.cost_data:
        with open(args.cost_data, "w") as out:
            for seconds, _, name in rows:
                if " " not in name:  # ctest splits a cost line at spaces
                    out.write(f"{name} 1 {seconds:.3f}\n")
            out.write("---\n")
    total = sum(r[0] for r in rows)
    print(f"{len(rows)} tests, {total:.0f} s of test time; the {min(args.most, len(rows))} slowest:")
    for seconds, label, name in rows[: args.most]:
        print(f"  {seconds:8.1f} s  {label:<10} {name}")
    if failed:
        print(f"{len(failed)} failed:")
        for label, name in failed:
            print(f"  {label:<10} {name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
