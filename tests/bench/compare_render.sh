#!/bin/bash
# One frame painted by `render --frame` with pleinair binaries in turn, twice: the sprites
# stage's ms (from --explain) and the command's wall time, for the shots and sizes where
# selection is the cost (BENCHMARKS.md, "Occlusion maps"):
#   tests/bench/compare_render.sh BINARY...
set -euo pipefail
cd "$(dirname "$0")/../.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for rep in 1 2; do
    for case in "forest-walk 193 112 64" "forest-walk 193 480 270" "forest-edge-walk 24 480 270" \
        "mortefontaine-walk 48 480 270"; do
        read -r shot frame w h <<<"$case"
        for bin in "$@"; do
            t0=$(date +%s.%N)
            sprites=$("$bin" render "$shot" --frame "$frame" --set /camera/width="$w" \
                --set /camera/height="$h" -o "$out/f.png" --explain 2>&1 |
                awk '$1 == "sprites" {print $2}')
            t1=$(date +%s.%N)
            echo "run $rep $shot ${w}x$h $bin sprites ${sprites} ms, $(echo "$t1 - $t0" | bc) s"
        done
    done
done
