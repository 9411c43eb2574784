# Lays out the shipped `valley` scene's world in Blender 3.4, as a user would: a valley between
# two hillsides with a pond on its floor, five rocks on the near ground and a camera walking down
# the valley for six seconds. It writes what presets/scenes/valley.json reads:
#   valley/heights.png  the ground as a 16-bit height map (257 x 257 samples over x -160..160,
#                       z -260..60 in pleinair's frame; 0 is -12 m and 65535 is 36 m)
#   valley/valley.glb   the rocks and the animated camera, through Blender's glTF exporter
#
#   blender -b --factory-startup -P tools/blender/make_valley.py -- presets/scenes/valley
import math
import os
import struct
import sys
import zlib

import bpy
from mathutils import Vector

out = sys.argv[sys.argv.index("--") + 1]
os.makedirs(out, exist_ok=True)

X0, X1, Z0, Z1, N = -160.0, 160.0, -260.0, 60.0, 257
LOW, HIGH = -12.0, 36.0


def floor_x(z):
    """Where the valley's floor runs, winding."""
    return 12.0 * math.sin(z / 70.0)


def height(x, z):
    """The ground's height at pleinair's (x, z): y up, z towards the viewer."""
    across = (x - floor_x(z)) / 55.0
    h = 22.0 * (1.0 - math.exp(-across * across))  # the two hillsides
    h += 0.015 * z  # the floor falls away down the valley
    h -= 2.5 * math.exp(-((x - floor_x(-90.0)) ** 2 + (z + 90.0) ** 2) / 625.0)  # the pond
    h += 25.0 * math.exp(-((z + 250.0) / 40.0) ** 2)  # the far ridge closing the valley
    h += 1.5 * math.sin(x / 23.0) * math.cos(z / 31.0)
    return h


def write_png16(path, width, height_px, rows):
    """A greyscale 16-bit PNG: rows of values 0..65535, the first row on top."""
    raw = b"".join(b"\0" + struct.pack(">%dH" % width, *row) for row in rows)

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height_px, 16, 0, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


# The height map: row 0 at the least z, as /terrain/height_map reads it.
rows = []
for j in range(N):
    z = Z0 + (Z1 - Z0) * j / (N - 1)
    row = []
    for i in range(N):
        x = X0 + (X1 - X0) * i / (N - 1)
        v = (height(x, z) - LOW) / (HIGH - LOW)
        row.append(int(round(65535 * min(max(v, 0.0), 1.0))))
    rows.append(row)
write_png16(os.path.join(out, "heights.png"), N, N, rows)


def blender(x, y, z):
    """pleinair's (x, y up, z) in Blender's (x, y, z up)."""
    return Vector((x, -z, y))


bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.resolution_x, scene.render.resolution_y = 1920, 1080
scene.render.fps = 24
scene.frame_start, scene.frame_end = 1, 145

# Rocks on the near ground, half sunk, squashed and turned.
objects = []
for i, (x, z, r) in enumerate([(-7.0, 22.0, 1.3), (8.0, 12.0, 1.8), (-12.0, 2.0, 2.4),
                               (5.0, -14.0, 1.0), (15.0, -30.0, 2.8)]):
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=r,
                                          location=blender(x, height(x, z) + 0.2 * r, z))
    rock = bpy.context.active_object
    rock.name = f"Rock{i + 1}"
    rock.scale = (1.4, 1.1, 0.65)
    rock.rotation_euler = (0.1 * i, 0.0, 0.7 * i)
    objects.append(rock)

# The camera walks down the valley's floor at eye height, looking down it.
cam_data = bpy.data.cameras.new("Camera")
cam_data.lens = 32
camera = bpy.data.objects.new("Camera", cam_data)
scene.collection.objects.link(camera)
scene.camera = camera
for frame, (x, z), (tx, ty, tz) in [(1, (3.0, 44.0), (floor_x(-120.0), -1.0, -120.0)),
                                    (49, (1.0, 30.0), (floor_x(-120.0) - 3.0, -1.0, -120.0)),
                                    (97, (-1.0, 16.0), (floor_x(-120.0) - 5.0, -1.5, -120.0)),
                                    (145, (-2.0, 2.0), (floor_x(-120.0) - 6.0, -2.0, -120.0))]:
    eye = blender(x, height(x, z) + 2.6, z)
    camera.location = eye
    camera.rotation_euler = (blender(tx, ty, tz) - eye).to_track_quat("-Z", "Y").to_euler()
    camera.keyframe_insert("location", frame=frame)
    camera.keyframe_insert("rotation_euler", frame=frame)
objects.append(camera)

bpy.ops.object.select_all(action="DESELECT")
for o in objects:
    o.select_set(True)
bpy.ops.export_scene.gltf(filepath=os.path.join(out, "valley.glb"), export_format="GLB",
                          use_selection=True, export_cameras=True, export_animations=True,
                          export_yup=True, export_apply=True)
print(f"wrote {out}/heights.png and {out}/valley.glb")
