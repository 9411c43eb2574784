#!/usr/bin/env bash
# Runs each libFuzzer program of the sanitized build for SECONDS, JOBS of them at once (each is
# one process on one core, so two cores fuzz two targets in the time of one), from the committed
# seed corpus and regressions; new inputs go to BUILD/corpus/TARGET, not the repository. Prints
# each target's final statistics in the targets' order once all have run, and exits 1 when one
# found something (its input is BUILD/finding-TARGET-*).
#   tools/ci/fuzz.sh BUILD SECONDS JOBS TARGET...
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
    PLEINAIR_PRESETS="$root/presets" "$build/tests/fuzz/fuzz_$t" -max_total_time="$seconds" \
        -max_len=65536 -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
        -artifact_prefix="$build/finding-$t-" \
        "$build/corpus/$t" "$root/tests/fuzz/corpus/$t" "${extra[@]}" >"$logs/$t.log" 2>&1
    echo $? >"$logs/$t.rc"
}
export -f fuzz_one
export build seconds root logs

printf '%s\n' "$@" | xargs -P "$jobs" -I{} bash -c 'fuzz_one {}'
failed=0
for t in "$@"; do
    rc=$(cat "$logs/$t.rc" 2>/dev/null || echo 1)
    echo "fuzz $t: $seconds s, exit $rc"
    grep -E "^(stat::|==|SUMMARY|Done|#[0-9]+ *DONE)" "$logs/$t.log" | sed 's/^/  /'
    if [ "$rc" != 0 ]; then
        failed=1
        tail -40 "$logs/$t.log" | sed 's/^/  | /'
    fi
done
exit $failed
