#!/bin/bash
# Frame times of pleinair binaries, interleaved (each binary in turn, twice), as BENCHMARKS.md's
# "Frames that cost what they show" measures them:
#   tests/bench/compare_frames.sh BINARY...
# Median ms a frame over frames 20-27 of each walk at 480x270, at the walks' preview size
# (640x360) and at 1920x1080, for each binary; the last one again as a draft (--draft) at the
# two small sizes.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() { # binary shot width height [extra arguments]
    "$1" animate "presets/scenes/$2.json" --set /camera/width="$3" --set /camera/height="$4" \
        "${@:5}" --frames 20-27 --progress log -o "$out/f_####.png" 2>&1 |
        tail -1 | sed -E 's/.*median ([0-9]+) ms.*/\1/'
}
last=${*: -1}
for shot in forest-edge-walk mortefontaine-walk; do
    for size in "480 270" "640 360" "1920 1080"; do
        read -r w h <<<"$size"
        for rep in 1 2; do
            line="$shot ${w}x${h} run $rep:"
            for bin in "$@"; do line="$line $(run "$bin" "$shot" "$w" "$h")"; done
            if [ "$w" != 1920 ]; then
                line="$line draft $(run "$last" "$shot" "$w" "$h" --draft)"
            fi
            echo "$line"
        done
    done
done
