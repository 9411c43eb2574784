#!/usr/bin/env bash
# Regenerates docs/gallery.md and its images (`make gallery`): every shipped scene and every
# tree family in both styles at 640x360, issue 13's Corot look beside the thesis's, and issue
# 27's families and pond beside their images before it, each image with the command that
# paints it. JPEG at quality 85 keeps each under 200 KB (checked).
set -euo pipefail

BIN=${1:-build/pleinair}
OUT=docs/gallery
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$OUT"
rm -f "$OUT"/*.jpg
W=640 H=360
SIZE="--set /camera/width=$W --set /camera/height=$H"
MD="$TMP/gallery.md"

# jpg PNG NAME: the image as docs/gallery/NAME.jpg, refused over 200 KB.
jpg() {
    oiiotool "$1" --compression jpeg:85 -o "$OUT/$2.jpg"
    local bytes
    bytes=$(stat -c %s "$OUT/$2.jpg")
    if [ "$bytes" -gt 204800 ]; then
        echo "docs/gallery.sh: $OUT/$2.jpg is $bytes bytes, over 200 KB" >&2
        exit 1
    fi
}

# The first frame a second into an animated scene (its own file or one it extends names a
# track, or it takes its camera from a glTF file), or the still.
frame_of() {
    if grep -q '"track"\|"gltf"' "presets/scenes/$1.json"; then echo "--frame 25"; fi
}

cat > "$MD" <<'EOF'
# Gallery

Every shipped scene and tree family, painted by the commands beside them (from the repository's
root, after `make build`), at 640x360 and saved as JPEG. `make gallery` paints them again and
rewrites this page; it refuses an image over 200 KB.

## The Corot look against the thesis's (issue 13)

`mortefontaine-thesis` is the default scene painted as pleinair painted before issue 13 (the
background's gradient for a sky, water that mirrors nothing, crowns lit leaf by leaf);
`mortefontaine` is it now. Left the thesis's, right the Corot look.

EOF

# Full size, once each, for the crops.
"$BIN" render mortefontaine-thesis -o "$TMP/thesis.png" > /dev/null
"$BIN" render mortefontaine -o "$TMP/corot.png" > /dev/null
"$BIN" render mortefontaine-paint -o "$TMP/paint.png" > /dev/null
"$BIN" render mortefontaine-paint --set /render/canvas_weave=0 -o "$TMP/pigment.png" > /dev/null

# pair NAME CROP RESIZE A B: A and B cut to CROP (WxH+X+Y), each resized, side by side.
pair() {
    oiiotool "$4" --cut "$2" --resize "$3" "$5" --cut "$2" --resize "$3" --mosaic 2x1 \
        -o "$TMP/$1.png"
    jpg "$TMP/$1.png" "$1"
}
pair whole 1920x1080+0+0 320x180 "$TMP/thesis.png" "$TMP/corot.png"
pair sky 960x540+480+0 320x180 "$TMP/thesis.png" "$TMP/corot.png"
pair water 960x160+240+620 480x80 "$TMP/thesis.png" "$TMP/corot.png"
pair crown 560x700+1360+0 256x320 "$TMP/thesis.png" "$TMP/corot.png"
pair pigment 480x360+1240+140 320x240 "$TMP/corot.png" "$TMP/pigment.png"
pair canvas 320x240+1300+640 320x240 "$TMP/corot.png" "$TMP/paint.png"

cat >> "$MD" <<'EOF'
| | |
|---|---|
| The whole scene. `pleinair render mortefontaine-thesis -o thesis.png`, `pleinair render mortefontaine -o corot.png` | ![](gallery/whole.jpg) |
| The sky (§1): the gradient under slow noise, and `corot-sky`'s strokes at infinity, lit from the sun's side, thinning into the horizon's haze. | ![](gallery/sky.jpg) |
| The pond (§2): grey ticks, and strokes mirroring the far bank's trees, trunks and sky, darker towards the viewer. | ![](gallery/water.jpg) |
| The great oak up close (§4): light blots everywhere, and lights gathered on the sunlit (left) side, smaller broken strokes and holes at the crown's edge. | ![](gallery/crown.jpg) |
| Alpha blending in linear RGB, and pigment mixing (§3, `pleinair render mortefontaine-paint --set /render/canvas_weave=0 -o pigment.png`): thin greens over the sky's blue-greys and creams mix towards yellow-olive as paint does. | ![](gallery/pigment.jpg) |
| No canvas, and `/render/canvas_weave` 0.35 (§3, `pleinair render mortefontaine-paint -o paint.png`): the weave shows where the grass strokes are thin and catches their edges. | ![](gallery/canvas.jpg) |

## Scenes

| scene | command | image |
|---|---|---|
EOF

for f in presets/scenes/*.json; do
    name=$(basename "$f" .json)
    frame=$(frame_of "$name")
    # shellcheck disable=SC2086
    "$BIN" render "$name" -o "$TMP/$name.png" $SIZE $frame > /dev/null
    jpg "$TMP/$name.png" "scene-$name"
    desc=$(grep -m1 '"description"' "$f" | sed 's/.*"description": *"\(.*\)",*/\1/')
    echo "| \`$name\`: $desc | \`pleinair render $name -o $name.png $SIZE${frame:+ $frame}\` | ![](gallery/scene-$name.jpg) |" >> "$MD"
done

cat >> "$MD" <<'EOF'

## Tree families

Four members of each family on a contact sheet, their crowns painted as strokes and as graftals
(the graftal style of issue 11: `corot-leaf` dabs, and for the truffula its own tufts).

| family | strokes | graftals |
|---|---|---|
EOF

for f in presets/trees/*.json; do
    name=$(basename "$f" .json)
    style=corot-leaf
    [ "$name" = truffula ] && style=truffula-tuft
    "$BIN" family --preset "$name" --count 4 --width $W --height $H -o "$TMP/$name.png" > /dev/null
    "$BIN" family --preset "$name" --count 4 --width $W --height $H --style $style \
        -o "$TMP/$name-graftal.png" > /dev/null
    jpg "$TMP/$name.png" "family-$name"
    jpg "$TMP/$name-graftal.png" "family-$name-graftals"
    echo "| \`$name\`: \`pleinair family --preset $name --count 4 --width $W --height $H -o $name.png\`, the same with \`--style $style\` | ![](gallery/family-$name.jpg) | ![](gallery/family-$name-graftals.jpg) |" >> "$MD"
done

cat >> "$MD" <<'EOF'

## Species and the pond (issue 27): before and after

Left, as pleinair painted them before issue 27 (b2e9d7e's binary, the same command; kept in
`gallery/before/`, which `make gallery` does not repaint); right, as it paints them now. The
families' measures against their species' targets are in BENCHMARKS.md, "Trees from the side
(issue 27)"; the pond's in "Corot's crowns, palette and pond".

| what changed | before | now |
|---|---|---|
EOF

# family NAME WHAT: three members before and now, with the command.
family() {
    "$BIN" family --preset "$1" --count 3 --width 720 --height 400 -o "$TMP/$1-3.png" > /dev/null
    jpg "$TMP/$1-3.png" "now-family-$1"
    echo "| \`$1\`: $2 \`pleinair family --preset $1 --count 3 --width 720 --height 400 -o $1.png\` | ![](gallery/before/family-$1.jpg) | ![](gallery/now-family-$1.jpg) |" >> "$MD"
}
family willow "a dark haystack before; now as wide as tall, its branchlets falling in a curtain nearly to the ground."
family poplar "a column three to four times as tall as wide, branched nearly to the ground."
family oak "a round bush hiding its trunk before; now a short bole bare to half its height under a few limbs spreading nearly level, each carrying its own mass of leaves, the sky between them; every member broader than tall."
family birch "a narrow, airy crown on a white trunk that shows, its branchlets drooping."
family pine "the umbrella on a tall bare trunk (the stone pine read as its species before too)."
family shrub "a garden shrub, branched from the ground (no species; unchanged)."
family truffula "Dr. Seuss's tufts on bare stems (no species; unchanged)."
echo "| \`mortefontaine\`: recomposed after the painting: the great oak screening the right with its limbs over the water, a thin leaning birch on the open left with wild flowers at its foot (the warm accent), the far bank in a blue haze merging with the sky, mirrored as pale by the still water, the meadow in greyed sage. \`pleinair render mortefontaine -o mortefontaine.png $SIZE\` | ![](gallery/before/scene-mortefontaine.jpg) | ![](gallery/scene-mortefontaine.jpg) |" >> "$MD"

mv "$MD" docs/gallery.md
echo "docs/gallery.md: $(ls "$OUT"/*.jpg | wc -l) images, $(du -ck "$OUT"/*.jpg | tail -1 | cut -f1) KB"
