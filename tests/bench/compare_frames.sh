#!/bin/bash
# Frame times of two pleinair binaries, interleaved (old, new, new with thinning; twice), as
# BENCHMARKS.md's "Frames that cost what they show" measures them:
#   tests/bench/compare_frames.sh OLD_BINARY NEW_BINARY
# Median ms a frame over frames 20-27 of each walk at 480x270 and 1920x1080.
set -euo pipefail
OLD=$1
NEW=$2
cd "$(dirname "$0")/../.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() { # binary shot width height [extra arguments]
    "$1" animate "presets/scenes/$2.json" --set /camera/width="$3" --set /camera/height="$4" \
        "${@:5}" --frames 20-27 --progress log -o "$out/f_####.png" 2>&1 |
        tail -1 | sed -E 's/.*median ([0-9]+) ms.*/\1/'
}
for shot in forest-edge-walk mortefontaine-walk; do
    for size in "480 270" "1920 1080"; do
        read -r w h <<<"$size"
        for rep in 1 2; do
            o=$(run "$OLD" "$shot" "$w" "$h")
            n=$(run "$NEW" "$shot" "$w" "$h")
            t=""
            if [ "$w" = 480 ]; then t=$(run "$NEW" "$shot" "$w" "$h" --set /render/thin_below_px=6); fi
            echo "$shot ${w}x${h} run $rep: old $o new $n new-thinned $t"
        done
    done
done
