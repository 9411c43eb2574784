#!/bin/bash
# Issue 26's forest test: forest-edge's groups replaced by one wood of about 622 trees (radius
# 140 m about (-5, -140), min_distance 8; the terrain widened to hold ten times as many), each
# family grown per tree or drawn from 8 members, and the wood of ten times the area (radius 443).
# One 1280x720 still each: peak memory and wall time (/usr/bin/time -v).
#   tests/bench/forest_memory.sh [PLEINAIR_BINARY]
set -euo pipefail
BIN=${1:-build/pleinair}
cd "$(dirname "$0")/../.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for spec in "140 0" "140 8" "443 8"; do
    read -r radius members <<<"$spec"
    sets=(--set '/terrain/min=[-460,-600]' --set '/terrain/max=[460,320]' --set '/trees=[]'
          --set "/groups=[{\"seed\":3,\"center\":[-5,-140],\"radius\":$radius,\"min_distance\":8,\"families\":{\"oak\":3,\"birch\":2,\"poplar\":1,\"shrub\":2},\"max_slope\":25}]")
    for f in oak birch poplar shrub; do sets+=(--set "/families/$f/members=$members"); done
    /usr/bin/time -v "$BIN" render forest-edge "${sets[@]}" --explain -o "$out/f.png" >"$out/log" 2>&1
    trees=$(grep -oE '\(([0-9]+) trees\)' "$out/log" | head -1)
    rss=$(awk '/Maximum resident/ {printf "%.0f MB", $6 / 1024}' "$out/log")
    wall=$(awk '/Elapsed/ {print $8}' "$out/log")
    echo "radius $radius members $members $trees: peak $rss, wall $wall"
done
