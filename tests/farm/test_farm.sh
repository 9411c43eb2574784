#!/usr/bin/env bash
# test_farm.sh -- `make test-farm`: starts a real one-node Slurm cluster on this machine, submits a
# small shot with pipeline/farm/submit.sh and checks what comes back against a local run.
#
# Checks: every array task COMPLETED with exit 0 (scontrol and the jobcomp log); frames
# byte-identical to one local `pleinair animate` of the same range; the video's frame count;
# submitting again repaints nothing; `sbatch --array=ID` repaints a lost chunk; a shot whose tasks
# fail (a bad --set value; a range past the end of the track) cancels its encode job and
# submit.sh says so. The cluster is stopped at the end, whatever happens.
#
# Needs root (it installs and starts slurmctld, slurmd and munged: tests/farm/slurm-local.sh).
# PLEINAIR: the binary (default build/pleinair of this repository). The last line is
# "N passed, M failed"; the exit code is non-zero when a check failed.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
here=$root/tests/farm
submit=$root/pipeline/farm/submit.sh
PLEINAIR=${PLEINAIR:-$root/build/pleinair}
export PLEINAIR PLEINAIR_PRESETS=$root/presets

passed=0 failed=0 finished=0 cluster=0 work=""
declare -A daemon_pids=()
say() { echo "[test-farm +${SECONDS}s] $*"; }
pass() { echo "PASS: $*"; passed=$((passed + 1)); }
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }
check() {  # check DESCRIPTION COMMAND...
    local what=$1; shift
    if "$@"; then pass "$what"; else fail "$what"; fi
}

stop_cluster() {
    [ "$cluster" = 1 ] || return 0
    cluster=0
    say "stopping the cluster"
    "$here/slurm-stop.sh" || fail "slurm-stop.sh failed"
    local name pid alive=""
    for name in "${!daemon_pids[@]}"; do
        pid=${daemon_pids[$name]}
        if kill -0 "$pid" 2>/dev/null; then alive+=" $name($pid)"; fi
    done
    if [ -z "$alive" ]; then pass "cluster stopped: no Slurm or munge daemon left running"
    else fail "still running after slurm-stop.sh:$alive"; fi
}

finish() {
    local rc=$?
    [ "$finished" = 1 ] && return
    finished=1
    set +e
    if [ "$rc" != 0 ] && [ "$failed" = 0 ]; then fail "the test stopped early (exit $rc, see above)"; fi
    stop_cluster
    if [ -n "$work" ]; then
        if [ "$failed" = 0 ]; then rm -rf "$work"; else echo "files kept for a look: $work"; fi
    fi
    say "done"
    echo "$passed passed, $failed failed"
    [ "$failed" = 0 ] || exit 1
    exit 0
}
trap finish EXIT
trap 'exit 130' INT TERM

fatal() { fail "$*"; exit 1; }

# ------------------------------------------------------------------ set-up
[ "$(id -u)" -eq 0 ] || fatal "test-farm must run as root: it installs and starts a Slurm cluster (CI runs as root)"
[ -x "$PLEINAIR" ] || fatal "no binary at $PLEINAIR (run make build, or set PLEINAIR)"
for tool in ffmpeg ffprobe cmp; do
    command -v "$tool" >/dev/null 2>&1 || fatal "$tool is missing (make deps installs ffmpeg)"
done

say "starting a one-node Slurm cluster"
cluster=1  # from here on, stop whatever part of it was started
"$here/slurm-local.sh" || fatal "the Slurm cluster did not start (see above and /var/log/slurm)"
for f in slurmctld:/run/slurm/slurmctld.pid slurmd:/run/slurm/slurmd.pid munged:/run/munge/munged.pid; do
    [ -s "${f#*:}" ] && daemon_pids[${f%%:*}]=$(head -n1 "${f#*:}" | tr -dc '0-9')
done
pass "cluster up (${SECONDS}s)"

work=$(mktemp -d "${TMPDIR:-/tmp}/pleinair-farm.XXXXXX")
chmod 755 "$work"
cd "$work"

SCENE=tree-dolly
SIZE=(--set /camera/width=160 --set /camera/height=90)
FIRST=1 LAST=12 CHUNK=4 TASKS=3

# jobs_done IDS: wait (at most 120 s) until none of the jobs is pending or running
jobs_done() {
    local i
    for ((i = 0; i < 600; i++)); do
        [ -z "$(squeue -h -j "$1" -t PD,R,CG,CF,S 2>/dev/null)" ] && return 0
        sleep 0.2
    done
    echo "jobs $1 still queued after 120 s" >&2
    return 1
}
# task_states ARRAYID: "TASK STATE EXITCODE" per task, sorted by task
task_states() {
    scontrol -o show job "$1" | sed -n 's/.* ArrayTaskId=\([0-9]*\) .* JobState=\([A-Z_]*\) .* ExitCode=\([0-9:]*\) .*/\1 \2 \3/p' | sort -n
}
job_state() { scontrol -o show job "$1" | sed -n 's/.* JobState=\([A-Z_]*\) .* ExitCode=\([0-9:]*\) .*/\1 \2/p'; }
# jobcomp_states ARRAYID: the same from the completion log (the last line of each task)
jobcomp_states() {
    sed -n "s/.* JobState=\([A-Z_]*\) .* ArrayJobId=$1 ArrayTaskId=\([0-9]*\) .* ExitCode=\([0-9:]*\) .*/\2 \1 \3/p" \
        /var/log/slurm/jobcomp.log | sort -n -s -k1,1 | awk '{last[$1] = $0} END {for (t in last) print last[t]}' | sort -n
}
expect_states() {  # expect_states WHAT ACTUAL EXPECTED
    if [ "$2" = "$3" ]; then pass "$1"
    else fail "$1: got [$(tr '\n' ';' <<<"$2")], expected [$(tr '\n' ';' <<<"$3")]"; fi
}
all_completed() {  # the expected task_states of N tasks all COMPLETED with exit 0
    local t
    for ((t = 0; t < $1; t++)); do echo "$t COMPLETED 0:0"; done
}
ids_of() { sed -n 's/^array=\([0-9]*\) encode=\([0-9a-z]*\)$/\1 \2/p' "$1" | tail -n1; }
same_frames() {  # same_frames DIR A B: frames A..B in DIR equal those of local/
    local f name ok=0
    for ((f = $2; f <= $3; f++)); do
        name=$(printf 'frame_%04d.png' "$f")
        cmp -s "local/$name" "$1/$name" || { echo "  $1/$name differs from local/$name (or is missing)"; ok=1; }
    done
    return $ok
}
count() { find "$1" -maxdepth 1 -name "$2" | wc -l; }

# ------------------------------------------------------------------ a local run, one process
t0=$SECONDS
"$PLEINAIR" animate "$SCENE" --frames "$FIRST-$LAST" "${SIZE[@]}" -o local/frame_####.png --progress log >local.log 2>&1 ||
    { cat local.log; fatal "local pleinair animate failed"; }
pass "local animate of frames $FIRST-$LAST ($((SECONDS - t0))s)"

# ------------------------------------------------------------------ the shot on the farm
say "submitting $SCENE frames $FIRST-$LAST in chunks of $CHUNK, with a video"
t0=$SECONDS
rc=0
timeout 150 "$submit" "$SCENE" "$FIRST" "$LAST" "$CHUNK" farm/frame_####.png --video farm/shot.mp4 --wait \
    "${SIZE[@]}" >submit.out 2>&1 || rc=$?
sed 's/^/  | /' submit.out
check "submit.sh --wait exits 0 for a good shot ($((SECONDS - t0))s)" [ "$rc" = 0 ]
read -r A E <<<"$(ids_of submit.out)" || true
[ -n "${A:-}" ] && [ -n "${E:-}" ] && [ "$E" != none ] || fatal "submit.sh printed no job ids"
expect_states "every array task COMPLETED with exit 0 (scontrol)" "$(task_states "$A")" "$(all_completed $TASKS)"
expect_states "every array task COMPLETED with exit 0 (jobcomp.log)" "$(jobcomp_states "$A")" "$(all_completed $TASKS)"
expect_states "the encode job COMPLETED with exit 0" "$(job_state "$E")" "COMPLETED 0:0"
check "$LAST frames on disk" [ "$(count farm 'frame_*.png')" = "$LAST" ]
check "each task's log ends its chunk at Progress: 100%" \
    [ "$(grep -l '^Progress: 100%$' farm/render_"$A"_*.log | wc -l)" = "$TASKS" ]
check "no temporary left beside the frames" [ "$(count farm '.*partial*')" = 0 ]
check "farm frames byte-identical to the local run" same_frames farm "$FIRST" "$LAST"
nb=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 farm/shot.mp4 2>&1 || true)
check "the video holds $LAST frames (ffprobe: $nb)" [ "$nb" = "$LAST" ]
size=$(ffprobe -v error -select_streams v:0 -show_entries stream=width,height,pix_fmt -of csv=p=0 farm/shot.mp4 2>&1 || true)
check "the video is 160x90 yuv420p (ffprobe: $size)" [ "$size" = "160,90,yuv420p" ]

# ------------------------------------------------------------------ resume
say "submitting the same shot again: nothing to repaint"
touch -d '-1 second' marker
t0=$SECONDS
rc=0
timeout 150 "$submit" "$SCENE" "$FIRST" "$LAST" "$CHUNK" farm/frame_####.png --video farm/shot.mp4 --wait \
    "${SIZE[@]}" >resubmit.out 2>&1 || rc=$?
check "the same submit again exits 0 ($((SECONDS - t0))s)" [ "$rc" = 0 ]
read -r A2 E2 <<<"$(ids_of resubmit.out)" || true
expect_states "its tasks COMPLETED with exit 0" "$(task_states "${A2:-0}")" "$(all_completed $TASKS)"
expect_states "its encode job COMPLETED with exit 0" "$(job_state "${E2:-0}")" "COMPLETED 0:0"
check "its tasks repainted nothing (every frame was already complete)" \
    [ "$(grep -l '^every frame was already complete$' farm/render_"${A2:-0}"_*.log 2>/dev/null | wc -l)" = "$TASKS" ]
check "no frame file was rewritten" [ -z "$(find farm -name 'frame_*.png' -newer marker)" ]

say "losing frames 6 and 7, then sbatch --array=1 with the command submit.sh printed"
rm farm/frame_0006.png farm/frame_0007.png
rerun=$(sed -n 's/^submit.sh: to paint some tasks again: //p' submit.out)
rc=0
out=$(eval "${rerun/sbatch --array=IDS/sbatch --parsable --array=1}") || rc=$?
A3=${out%%;*}
check "sbatch --array=1 accepted the printed command" [ "$rc/${A3:-none}" = "0/${A3//[!0-9]/x}" ]
jobs_done "${A3:-0}" || true
expect_states "task 1 COMPLETED with exit 0" "$(task_states "${A3:-0}")" "1 COMPLETED 0:0"
check "frames 5-8 byte-identical to the local run again" same_frames farm 5 8
check "only frames 6 and 7 were painted again" \
    [ "$(cd farm && find . -name 'frame_*.png' -newer ../marker | sort | tr '\n' ' ')" = "./frame_0006.png ./frame_0007.png " ]

# ------------------------------------------------------------------ failures
say "a shot with a bad --set value: every task fails, the encode job is cancelled"
rc=0
timeout 150 "$submit" "$SCENE" 1 8 "$CHUNK" bad/frame_####.png --video bad/shot.mp4 --wait \
    --set /camera/width=wide >bad.out 2>&1 || rc=$?
sed 's/^/  | /' bad.out
check "submit.sh --wait exits 1" [ "$rc" = 1 ]
read -r A4 E4 <<<"$(ids_of bad.out)" || true
expect_states "both tasks FAILED with exit 2" "$(task_states "${A4:-0}")" "$(printf '0 FAILED 2:0\n1 FAILED 2:0')"
check "the encode job was CANCELLED, never run" \
    sh -c "scontrol -o show job ${E4:-0} | grep -q 'JobState=CANCELLED .*Reason=DependencyNeverSatisfied'"
check "submit.sh says the shot failed and the encode job did not run" \
    sh -c "grep -q '^submit.sh: shot FAILED' bad.out && grep -q '^submit.sh: encode job ${E4:-0} did not run' bad.out"
check "a task's log names the bad key" grep -q '/camera/width' "bad/render_${A4:-0}_0.log"
check "no frame and no video written" [ "$(count bad 'frame_*')/$(count bad 'shot.mp4')" = 0/0 ]

say "a shot running past the track's last frame (193): the last tasks fail"
rc=0
timeout 150 "$submit" "$SCENE" 185 197 "$CHUNK" past/frame_####.png --video past/shot.mp4 --wait \
    "${SIZE[@]}" >past.out 2>&1 || rc=$?
sed 's/^/  | /' past.out
check "submit.sh --wait exits 1" [ "$rc" = 1 ]
read -r A5 E5 <<<"$(ids_of past.out)" || true
expect_states "tasks 0-1 COMPLETED, tasks 2-3 FAILED with exit 2" "$(task_states "${A5:-0}")" \
    "$(printf '0 COMPLETED 0:0\n1 COMPLETED 0:0\n2 FAILED 2:0\n3 FAILED 2:0')"
expect_states "the same in jobcomp.log" "$(jobcomp_states "${A5:-0}")" \
    "$(printf '0 COMPLETED 0:0\n1 COMPLETED 0:0\n2 FAILED 2:0\n3 FAILED 2:0')"
check "the encode job was CANCELLED" sh -c "scontrol -o show job ${E5:-0} | grep -q 'JobState=CANCELLED'"
check "submit.sh names the failed tasks" grep -q '^submit.sh: failed tasks: 2,3 ' past.out
check "frames 185-192 written, no video" [ "$(count past 'frame_*.png')/$(count past 'shot.mp4')" = 8/0 ]

check "nothing left in the queue" [ -z "$(squeue -h 2>/dev/null)" ]
