#!/usr/bin/env python3
"""Writes hedgerow.ply: what a Houdini scatter exports for pleinair's particle example.

A hedge along x (a rounded, lumpy mass of foliage points) and poppies in the grass before it,
z up as Blender and this script write it, binary little endian, with Houdini's attributes:
pscale (a radius), id, the normal (nx, ny, nz) and the colour (red, green, blue as uchar sRGB).
Pure Python, seeded: running it again writes the same bytes.
"""
import math
import random
import struct
import sys

rng = random.Random(7)
points = []  # (x, y, z, pscale, id, nx, ny, nz, r, g, b)

# The hedge: points on a lumpy half-ellipsoid 24 long, 2.2 deep, 3 high, its normal outwards.
for i in range(9000):
    u = rng.uniform(-1.0, 1.0)
    a = rng.uniform(0.0, math.pi)
    lump = 1.0 + 0.18 * math.sin(7.0 * u + 1.3) * math.sin(3.0 * a)
    nx, ny, nz = u * 0.35, math.cos(a), math.sin(a)
    norm = math.sqrt(nx * nx + ny * ny + nz * nz)
    nx, ny, nz = nx / norm, ny / norm, nz / norm
    depth = rng.uniform(0.75, 1.0)
    x = 12.0 * u
    y = 1.1 * math.cos(a) * lump * depth
    z = 3.0 * math.sin(a) * lump * depth * (1.0 - 0.25 * u * u)
    shade = rng.uniform(0.0, 1.0)
    r, g, b = (int(52 + 34 * shade), int(70 + 38 * shade), int(40 + 14 * shade))
    points.append((x, y, z, rng.uniform(0.16, 0.24), i, nx, ny, nz, r, g, b))

# Poppies and grass heads in front of it: small, facing up, red among olive.
for i in range(3000):
    x, y = rng.uniform(-13.0, 13.0), rng.uniform(-7.0, -1.4)
    poppy = rng.random() < 0.18
    r, g, b = (196, 58, 40) if poppy else (128, 126, 70)
    points.append((x, y, rng.uniform(0.05, 0.35), 0.13 if poppy else 0.1, 9000 + i,
                   0.0, 0.0, 1.0, r, g, b))

header = (
    "ply\nformat binary_little_endian 1.0\ncomment pleinair example: a hedgerow, z up\n"
    f"element vertex {len(points)}\n"
    "property float x\nproperty float y\nproperty float z\nproperty float pscale\n"
    "property int id\nproperty float nx\nproperty float ny\nproperty float nz\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n")
out = sys.argv[1] if len(sys.argv) > 1 else "hedgerow.ply"
with open(out, "wb") as f:
    f.write(header.encode("ascii"))
    for p in points:
        f.write(struct.pack("<4fi3f3B", *p))
