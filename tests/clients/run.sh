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
echo "== Blender lays out a scene, pleinair paints it"
scene="$work/out/blender-scene"
mkdir -p "$scene"
blender -b --factory-startup --python-exit-code 1 -P "$here/blender_scene.py" -- \
    "$scene/valley.glb" "$scene/points.json" 2>&1 | grep -E "^exported|Error|Traceback"
test "${PIPESTATUS[0]}" -eq 0
cp "$here/blender_scene.json" "$scene/scene.json"
(cd "$work" && node validate.mjs "$scene/valley.glb")
points=()
while read -r p; do points+=(--point "$p"); done < <(/usr/bin/python3 -c "
import json
for p in json.load(open('$scene/points.json'))['points']: print(','.join(map(repr, p)))")
"$pleinair" camera "$scene/scene.json" "${points[@]}" >"$scene/camera.jsonl"
/usr/bin/python3 "$here/match_camera.py" "$scene/points.json" "$scene/camera.jsonl"
"$pleinair" animate "$scene/scene.json" --frames 1-48x47 -o "$scene/f_####.png" --progress log \
    >/dev/null
test -s "$scene/f_0001.png" && test -s "$scene/f_0048.png"
echo "  painted frames 1 and 48 of the Blender scene: $scene"
echo "== pleinair exports scenes; Blender imports one and sees what pleinair's camera sees"
"$pleinair" render "$scene/scene.json" --export "$scene/back.glb" >/dev/null
"$pleinair" render forest-edge --export "$work/out/forest-edge.glb" --export-low-detail >/dev/null
size="--set /camera/width=320 --set /camera/height=180"
# shellcheck disable=SC2086
"$pleinair" render grove-orbit --export "$work/out/grove.glb" --export-low-detail \
    --export-instancing nodes $size >/dev/null
(cd "$work" && node validate.mjs "$scene/back.glb" "$work/out/forest-edge.glb" \
    "$work/out/grove.glb" | grep -v "^  info")
blender -b --factory-startup --python-exit-code 1 -P "$here/blender_import_scene.py" -- \
    "$work/out/grove.glb" 9 "$here/grove_points.json" "$work/out/grove_points.json" 2>&1 |
    grep -E "^(ok|FAIL)|Error|Traceback"
test "${PIPESTATUS[0]}" -eq 0
points=()
while read -r p; do points+=(--point "$p"); done < <(/usr/bin/python3 -c "
import json
for p in json.load(open('$here/grove_points.json'))['points']: print(','.join(map(repr, p)))")
# shellcheck disable=SC2086
"$pleinair" camera grove-orbit $size "${points[@]}" >"$work/out/grove_camera.jsonl"
/usr/bin/python3 "$here/match_camera.py" "$work/out/grove_points.json" "$work/out/grove_camera.jsonl"
echo "test-clients: all passed"
