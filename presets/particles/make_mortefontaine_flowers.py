#!/usr/bin/env python3
"""Writes mortefontaine-flowers.ply: the wild flowers on Mortefontaine's near bank.

Corot's Souvenir de Mortefontaine keeps one warm accent, the rose and cream of the figures under
the small tree on the left; pleinair paints no figures, so a drift of flowers on the bank by the
leaning birch carries it: cream and pale yellow heads, one in two rose or madder red.
Laid out on flat ground (y up, y = height above it): the scene places them with `on_terrain`.
Binary little endian, with Houdini's attributes: pscale (a radius), id, and the colour (red,
green, blue as uchar sRGB). Pure Python, seeded: running it again writes the same bytes.
"""
import math
import random
import struct
import sys

rng = random.Random(1864)
points = []  # (x, y, z, pscale, id, r, g, b)

# Three drifts, denser at their middle (a gaussian), in the scene's world (x, z).
drifts = [((-12.0, 20.0), 1.8, 70), ((-8.5, 23.5), 1.2, 40), ((-15.0, 17.5), 1.2, 30)]
for (cx, cz), spread, count in drifts:
    for _ in range(count):
        x, z = rng.gauss(cx, spread), rng.gauss(cz, spread * 0.6)
        warm = rng.random() < 0.5
        if warm:
            r, g, b = rng.choice([(196, 112, 100), (184, 84, 64), (206, 132, 116)])
        else:
            r, g, b = rng.choice([(222, 216, 184), (214, 204, 150), (232, 226, 204)])
        points.append((x, rng.uniform(0.15, 0.4), z, rng.uniform(0.12, 0.2), len(points), r, g, b))

header = (
    "ply\nformat binary_little_endian 1.0\ncomment pleinair: wild flowers for mortefontaine, y up\n"
    f"element vertex {len(points)}\n"
    "property float x\nproperty float y\nproperty float z\nproperty float pscale\n"
    "property int id\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n")
out = sys.argv[1] if len(sys.argv) > 1 else "mortefontaine-flowers.ply"
with open(out, "wb") as f:
    f.write(header.encode("ascii"))
    for p in points:
        f.write(struct.pack("<4fi3B", *p))
