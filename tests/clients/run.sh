#!/usr/bin/env bash
# pleinair's glTF files against real clients: every exported .glb through the Khronos validator
# (no errors allowed), and Blender 3.4 importing a tree (tests/clients/blender_tree.py).
#   tests/clients/run.sh PLEINAIR WORK_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
pleinair="$1"
work="$2"
rm -rf "$work/out"
mkdir -p "$work/out"

# The validator from npm, pinned (package.json), installed beside the work files.
cp "$here/package.json" "$work/package.json"
(cd "$work" && npm install --no-audit --no-fund --loglevel=error >/dev/null)
cp "$here/validate.mjs" "$work/validate.mjs"

glbs=()
for preset in birch oak pine poplar shrub truffula willow; do
    "$pleinair" tree --preset "$preset" --seed 1 --format glb -o "$work/out/$preset" \
        --stats >"$work/out/$preset.stats"
    glbs+=("$work/out/$preset/tree.glb")
done
"$pleinair" family --preset willow --count 2 --seed 5 --format glb -o "$work/out/family" >/dev/null
glbs+=("$work/out/family"/*/tree.glb)
echo "== gltf-validator: ${#glbs[@]} files"
(cd "$work" && node validate.mjs "${glbs[@]}")

echo "== Blender imports tree.glb"
for preset in oak willow; do
    blender -b --factory-startup --python-exit-code 1 -P "$here/blender_tree.py" -- \
        "$work/out/$preset/tree.glb" "$work/out/$preset.stats" "$preset" 1 2>&1 |
        grep -E "^(ok|FAIL|[0-9]+ failed)|Error|Traceback" | sed "s/^/  $preset: /"
    test "${PIPESTATUS[0]}" -eq 0
done
echo "test-clients: all passed"
