#!/usr/bin/env bash
# Runs each libFuzzer program of the sanitized build for SECONDS, JOBS of them at once (each is
# one process on one core, so two cores fuzz two targets in the time of one), from the committed
# seed corpus and regressions; new inputs go to BUILD/corpus/TARGET, not the repository. Prints
# each target's final statistics in the targets' order once all have run, and exits 1 when one
# found something (its input is BUILD/finding-TARGET-*). FUZZ_SEED, when set and not 0, fixes
# libFuzzer's seed: CI's run then tries the same inputs in the same order each time (how many,
# the machine's speed decides), so a finding there is found again
# here by the same command and a pass is not a draw (run without it to explore further).
#   [FUZZ_SEED=N] tools/ci/fuzz.sh BUILD SECONDS JOBS TARGET...
set -uo pipefail
build=$1 seconds=$2 jobs=$3
shift 3
root=$(cd "$(dirname "$0")/../.." && pwd)
logs=$build/fuzz-logs
mkdir -p "$logs"

fuzz_one() {
    local t=$1
    mkdir -p "$build/corpus/$t"
    local extra=()
    [ -d "$root/tests/fuzz/regressions/$t" ] && extra+=("$root/tests/fuzz/regressions/$t")
    # A fresh scratch corpus each run, so a fixed seed replays the same run.
    [ "${FUZZ_SEED:-0}" != 0 ] && rm -rf "$build/corpus/$t" && mkdir -p "$build/corpus/$t"
    local seed=()
    [ "${FUZZ_SEED:-0}" != 0 ] && seed=(-seed="$FUZZ_SEED")
    PLEINAIR_PRESETS="$root/presets" "$build/tests/fuzz/fuzz_$t" -max_total_time="$seconds" \
        "${seed[@]}" -max_len=65536 -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
        -artifact_prefix="$build/finding-$t-" \
        "$build/corpus/$t" "$root/tests/fuzz/corpus/$t" "${extra[@]}" >"$logs/$t.log" 2>&1
    echo $? >"$logs/$t.rc"
}
export -f fuzz_one
export build seconds root logs FUZZ_SEED

printf '%s\n' "$@" | xargs -P "$jobs" -I{} bash -c 'fuzz_one {}'
# The findings come last, after every target's statistics, and are also kept in
# BUILD/fuzz-findings.txt, which .ci/run prints again at its very end: the tail of CI's log is
# often all that is kept of it.
failed=()
rm -f "$build/fuzz-findings.txt"
for t in "$@"; do
    rc=$(cat "$logs/$t.rc" 2>/dev/null || echo 1)
    echo "fuzz $t: $seconds s, exit $rc"
    grep -E "^(stat::|==|SUMMARY|Done|#[0-9]+ *DONE)" "$logs/$t.log" | sed 's/^/  /'
    [ "$rc" != 0 ] && failed+=("$t")
done
for t in "${failed[@]}"; do
  {
    echo "fuzz $t found something (exit $(cat "$logs/$t.rc" 2>/dev/null)); the end of its log:"
    grep -v -E "^(#[0-9]+|INFO:|MS:)" "$logs/$t.log" | tail -40 | sed 's/^/  | /'
    for f in "$build"/finding-"$t"-*; do
        [ -f "$f" ] || continue
        echo "  input $f ($(stat -c %s "$f") bytes), base64:"
        head -c 4096 "$f" | base64 -w 100 | sed 's/^/  | /'
    done
  } | tee -a "$build/fuzz-findings.txt"
done
[ ${#failed[@]} -eq 0 ]
