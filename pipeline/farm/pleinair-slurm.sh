#!/usr/bin/env bash
# pleinair-slurm.sh -- the Slurm batch script of a pleinair shot: one array task paints one chunk
# of frames, or the encode job turns the finished frames into a video.
#
#   sbatch --array=0-(N-1) pleinair-slurm.sh render SCENE FIRST LAST CHUNK OUTPATTERN [animate args...]
#   sbatch --dependency=afterok:ARRAYID pleinair-slurm.sh encode SCENE FIRST LAST OUTPATTERN VIDEO [animate args...]
#
# Array task ID paints frames FIRST + ID*CHUNK .. min(LAST, FIRST + (ID+1)*CHUNK - 1) with
# `pleinair animate --resume --progress log`, so a task run again keeps the frames that are
# already complete. The encode job runs `animate --frames FIRST-LAST --resume --video VIDEO`: every
# frame exists, so it only encodes. submit.sh submits both; see the README, "Rendering on a Slurm
# cluster".
#
# The binary: $PLEINAIR if set (submit.sh sets it to an absolute path), else `pleinair` on PATH.
# Sbatch runs a copy of this file from its spool folder, so nothing here is found beside it.
# --threads is the task's CPUs (SLURM_CPUS_PER_TASK) unless the animate args name --threads.
#SBATCH --job-name=pleinair
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
set -euo pipefail

die() { echo "pleinair-slurm.sh: $*" >&2; exit 2; }
is_uint() { case "$1" in '' | *[!0-9]*) return 1 ;; *) return 0 ;; esac; }

PLEINAIR=${PLEINAIR:-pleinair}
command -v "$PLEINAIR" >/dev/null 2>&1 || die "cannot run '$PLEINAIR' (set PLEINAIR=/path/to/pleinair)"

threads=()
if [ -n "${SLURM_CPUS_PER_TASK:-}" ]; then threads=(--threads "$SLURM_CPUS_PER_TASK"); fi

mode=${1:-}
case "$mode" in
    render)
        [ $# -ge 6 ] || die "usage: render SCENE FIRST LAST CHUNK OUTPATTERN [animate args...]"
        scene=$2 first=$3 last=$4 chunk=$5 out=$6
        shift 6
        is_uint "$first" && is_uint "$last" && is_uint "$chunk" && [ "$chunk" -ge 1 ] ||
            die "FIRST, LAST and CHUNK must be whole numbers, CHUNK >= 1 (got $first $last $chunk)"
        id=${SLURM_ARRAY_TASK_ID:-}
        is_uint "$id" || die "SLURM_ARRAY_TASK_ID is not set: submit with sbatch --array"
        a=$((first + id * chunk))
        b=$((a + chunk - 1))
        [ "$b" -le "$last" ] || b=$last
        [ "$a" -le "$b" ] || die "task $id: no frame left (frames $first-$last in chunks of $chunk)"
        ;;
    encode)
        [ $# -ge 6 ] || die "usage: encode SCENE FIRST LAST OUTPATTERN VIDEO [animate args...]"
        scene=$2 a=$3 b=$4 out=$5 video=$6
        shift 6
        ;;
    *) die "first argument: render or encode (got '$mode')" ;;
esac
for arg in "$@"; do
    case "$arg" in --threads | --threads=*) threads=() ;; esac
done

echo "pleinair-slurm.sh: $mode frames $a-$b of $scene on $(hostname -s)," \
    "job ${SLURM_JOB_ID:-?} task ${SLURM_ARRAY_TASK_ID:--}"
cmd=("$PLEINAIR" "${threads[@]}" animate "$scene" --frames "$a-$b" -o "$out" --resume --progress log)
[ "$mode" = encode ] && cmd+=(--video "$video")
cmd+=("$@")
echo "+ ${cmd[*]}"
exec "${cmd[@]}"
