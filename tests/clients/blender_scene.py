# Builds a small scene in Blender 3.4 by script (a hilly ground, three rocks, a camera that
# walks and turns over 48 frames), exports it with Blender's own glTF exporter, and writes where
# Blender's camera sees test points at a few frames, for pleinair to match
# (tests/clients/run.sh compares them with `pleinair camera`).
#
#   blender -b --factory-startup --python-exit-code 1 -P tests/clients/blender_scene.py -- \
#       OUT.glb POINTS.json
import json
import math
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

glb, points_path = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.resolution_x, scene.render.resolution_y = 320, 180
scene.render.resolution_percentage = 100
scene.render.fps = 24
scene.frame_start, scene.frame_end = 1, 48


def height(x, y):
    return 3.0 * math.sin(x / 9.0) * math.cos(y / 11.0) + 0.04 * x + 0.5 * math.sin(y / 3.0)


# The ground: a 60 m grid, 48 x 48 cells, lifted into hills.
bpy.ops.mesh.primitive_grid_add(x_subdivisions=48, y_subdivisions=48, size=60)
ground = bpy.context.active_object
ground.name = "Valley"
for v in ground.data.vertices:
    v.co.z = height(v.co.x, v.co.y)

# Rocks: subdivided icospheres, squashed and half sunk in the ground.
rocks = []
for i, (x, y, r) in enumerate([(-4.0, 6.0, 1.6), (3.0, 12.0, 2.2), (8.0, 2.0, 1.1)]):
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=r, location=(x, y, height(x, y)))
    rock = bpy.context.active_object
    rock.name = f"Rock{i + 1}"
    rock.scale = (1.3, 1.0, 0.7)
    rock.rotation_euler = (0.0, 0.0, 0.5 * i)
    rocks.append(rock)

# The camera walks up the valley, turning to keep the rocks in view.
cam_data = bpy.data.cameras.new("Camera")
cam_data.lens = 30
camera = bpy.data.objects.new("Camera", cam_data)
scene.collection.objects.link(camera)
scene.camera = camera
for frame, loc, rot in [(1, (-2.0, -20.0, 4.0), (80.0, 0.0, -10.0)),
                        (24, (3.0, -12.0, 4.5), (78.0, 0.0, 5.0)),
                        (48, (9.0, -6.0, 5.5), (75.0, 0.0, 25.0))]:
    camera.location = loc
    camera.rotation_euler = tuple(math.radians(a) for a in rot)
    camera.keyframe_insert("location", frame=frame)
    camera.keyframe_insert("rotation_euler", frame=frame)

bpy.ops.export_scene.gltf(filepath=glb, export_format="GLB", export_cameras=True,
                          export_animations=True, export_yup=True, export_apply=True)

# Test points: each rock's centre and nine points of the ground, in Blender's world; written in
# glTF's (x, z, -y), where pleinair reads them.
world = [r.matrix_world.translation.copy() for r in rocks]
for x in (-6.0, 0.0, 6.0):
    for y in (0.0, 8.0, 16.0):
        world.append(Vector((x, y, height(x, y))))
out = {"points": [[p.x, p.z, -p.y] for p in world], "frames": {}}
for frame in (1, 12, 24, 36, 48):
    scene.frame_set(frame)
    seen = []
    for p in world:
        c = world_to_camera_view(scene, camera, p)
        seen.append([c.x * scene.render.resolution_x, (1.0 - c.y) * scene.render.resolution_y,
                     c.z])
    out["frames"][str(frame)] = seen
with open(points_path, "w") as f:
    json.dump(out, f, indent=1)
print(f"exported {glb} and {len(world)} test points at {len(out['frames'])} frames")
