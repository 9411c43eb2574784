#!/usr/bin/env bash
# submit.sh -- submit a pleinair shot to Slurm: a job array whose tasks each paint a chunk of
# frames, then (with --video) an encode job that runs only if every task succeeded.
#
#   pipeline/farm/submit.sh SCENE FIRST LAST CHUNK OUTPATTERN [--video F.mp4] [--wait] [animate args...]
#   pipeline/farm/submit.sh tree-dolly 1 193 12 out/dolly/frame_####.png --video out/dolly.mp4
#
# Task ID (0 .. N-1, N = ceil((LAST - FIRST + 1) / CHUNK)) paints frames FIRST + ID*CHUNK ..
# min(LAST, FIRST + (ID+1)*CHUNK - 1) with `pleinair animate --resume --progress log`; its log is
# DIR/render_ARRAYID_ID.log beside the frames. Other arguments (--set, --preview, --threads ...)
# go to every `pleinair animate`. Prints the job ids, and the sbatch command that runs some tasks
# again; the last line is "array=ID encode=ID" (encode=none without --video).
# --wait: wait for the jobs, print each task's state and exit 1 unless every job COMPLETED.
# Submitting the same command again repaints only the frames that are missing.
#
# Environment: PLEINAIR (the binary; default `pleinair` on PATH, else build/pleinair of this
# repository; made absolute, so it must be visible at that path on the compute nodes),
# PLEINAIR_CPUS (CPUs per task, default 1), PLEINAIR_SBATCH_ARGS (more sbatch options for both
# jobs, split on spaces, e.g. "--partition=render --time=2:00:00").
# Jobs run in the current folder, so relative paths mean the same thing on the nodes (a shared
# file system is assumed).
set -euo pipefail

die() { echo "submit.sh: $*" >&2; exit 2; }
is_uint() { case "$1" in '' | *[!0-9]*) return 1 ;; *) return 0 ;; esac; }
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
job_script=$here/pleinair-slurm.sh

[ $# -ge 5 ] || die "usage: submit.sh SCENE FIRST LAST CHUNK OUTPATTERN [--video F.mp4] [--wait] [animate args...]"
scene=$1 first=$2 last=$3 chunk=$4 out=$5
shift 5
is_uint "$first" && is_uint "$last" && is_uint "$chunk" || die "FIRST, LAST and CHUNK must be whole numbers"
[ "$first" -ge 1 ] && [ "$first" -le "$last" ] && [ "$chunk" -ge 1 ] ||
    die "need 1 <= FIRST <= LAST and CHUNK >= 1 (got $first $last $chunk)"

video="" wait=0 extra=()
while [ $# -gt 0 ]; do
    case "$1" in
        --video) [ $# -ge 2 ] || die "--video needs a file"; video=$2; shift 2 ;;
        --video=*) video=${1#--video=}; shift ;;
        --wait) wait=1; shift ;;
        --frames | --frames=* | -o | --out | --out=* | --resume | --progress | --progress=*)
            die "$1 is set by submit.sh" ;;
        *) extra+=("$1"); shift ;;
    esac
done
case "$video" in '' | *.mp4) ;; *) die "--video: expected a file ending in .mp4, got \"$video\"" ;; esac

# The binary, as an absolute path the jobs can run.
bin=${PLEINAIR:-}
if [ -z "$bin" ]; then
    if command -v pleinair >/dev/null 2>&1; then bin=$(command -v pleinair)
    elif [ -x "$here/../../build/pleinair" ]; then bin=$here/../../build/pleinair
    else die "no pleinair on PATH nor in $(cd "$here/../.." && pwd)/build: set PLEINAIR=/path/to/pleinair"
    fi
elif [[ "$bin" != */* ]]; then
    bin=$(command -v "$bin") || die "PLEINAIR=$PLEINAIR: not found on PATH"
fi
[ -x "$bin" ] || die "PLEINAIR: $bin is not an executable file"
bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
command -v sbatch >/dev/null 2>&1 || die "sbatch not found: is this a Slurm submit host?"

n=$(((last - first) / chunk + 1))
dir=$(dirname "$out")
mkdir -p "$dir"
[ -z "$video" ] || mkdir -p "$(dirname "$video")"
read -r -a site_args <<<"${PLEINAIR_SBATCH_ARGS:-}"
common=(--chdir="$PWD" --export="ALL,PLEINAIR=$bin" --ntasks=1 --cpus-per-task="${PLEINAIR_CPUS:-1}"
        ${site_args[@]+"${site_args[@]}"})
name=pleinair-$(basename "$scene" .json)
render_args=(--job-name="$name" -o "$dir/render_%A_%a.log" "${common[@]}"
             "$job_script" render "$scene" "$first" "$last" "$chunk" "$out" ${extra[@]+"${extra[@]}"})

array_id=$(sbatch --parsable --array="0-$((n - 1))" "${render_args[@]}")
array_id=${array_id%%;*}
echo "submit.sh: array job $array_id: $n tasks paint frames $first-$last of $scene in chunks of $chunk into $out"
echo "submit.sh: task logs: $dir/render_${array_id}_<task>.log"
encode_id=none
if [ -n "$video" ]; then
    encode_id=$(sbatch --parsable --dependency="afterok:$array_id" --kill-on-invalid-dep=yes \
        --job-name="$name-encode" -o "$dir/encode_%j.log" "${common[@]}" \
        "$job_script" encode "$scene" "$first" "$last" "$out" "$video" ${extra[@]+"${extra[@]}"})
    encode_id=${encode_id%%;*}
    echo "submit.sh: encode job $encode_id: $video once every task of $array_id succeeded (log $dir/encode_$encode_id.log)"
fi
quote() {  # words a shell reads back as they are
    local w out=""
    for w in "$@"; do
        if [[ "$w" =~ ^[A-Za-z0-9_./=:,%#@+-]+$ ]]; then out+=" $w"; else out+=" '${w//\'/\'\\\'\'}'"; fi
    done
    echo "${out# }"
}
rerun=$(quote sbatch --array=IDS "${render_args[@]}")
echo "submit.sh: to paint some tasks again: $rerun"

if [ "$wait" = 1 ]; then
    ids=$array_id
    [ "$encode_id" = none ] || ids="$ids,$encode_id"
    while [ -n "$(squeue -h -j "$ids" -t PD,R,CG,CF,S 2>/dev/null)" ]; do sleep 0.5; done
    field() { sed -n "s/.* $1=\([^ ]*\).*/\1/p" <<<"$2"; }
    failed=() ok=1
    while read -r t state code; do
        a=$((first + t * chunk)) b=$((first + (t + 1) * chunk - 1))
        [ "$b" -le "$last" ] || b=$last
        frames="frames $a-$b"
        [ "$a" != "$b" ] || frames="frame $a"
        echo "submit.sh: task $t ($frames): $state exit $code"
        if [ "$state" != COMPLETED ] || [ "$code" != 0:0 ]; then failed+=("$t"); ok=0; fi
    done < <(scontrol -o show job "$array_id" | while IFS= read -r line; do
                 echo "$(field ArrayTaskId "$line") $(field JobState "$line") $(field ExitCode "$line")"
             done | sort -n)
    if [ "$encode_id" != none ]; then
        line=$(scontrol -o show job "$encode_id")
        state=$(field JobState "$line") code=$(field ExitCode "$line") why=$(field Reason "$line")
        [ "$why" != None ] || why=""
        echo "submit.sh: encode job $encode_id: $state exit $code${why:+ ($why)}"
        [ "$state" = COMPLETED ] && [ "$code" = 0:0 ] || ok=0
    fi
    if [ "$ok" = 1 ]; then
        echo "submit.sh: shot complete: array=$array_id encode=$encode_id"
    else
        [ ${#failed[@]} -eq 0 ] || echo "submit.sh: failed tasks: $(IFS=,; echo "${failed[*]}")" \
            "(see their logs); submit the same command again, or: ${rerun/IDS/$(IFS=,; echo "${failed[*]}")}"
        [ "$encode_id" = none ] || [ ${#failed[@]} -eq 0 ] ||
            echo "submit.sh: encode job $encode_id did not run: a task it waited for failed"
        echo "submit.sh: shot FAILED: array=$array_id encode=$encode_id"
        echo "array=$array_id encode=$encode_id"
        exit 1
    fi
fi
echo "array=$array_id encode=$encode_id"
