# Blender 3.4 imports a scene pleinair exported (render --export --export-instancing nodes): the
# test checks one object per tree and the camera, and writes where Blender's camera (animated
# by the file) sees test points at some frames, for match_camera.py to hold against
# `pleinair camera`. Exit code 1 when the objects are not all there.
#
#   blender -b --factory-startup --python-exit-code 1 -P tests/clients/blender_import_scene.py \
#       -- SCENE.glb TREES POINTS_IN.json POINTS_OUT.json
import json
import sys

import bpy
import numpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

if "bool" not in numpy.__dict__:  # Debian 12: Blender 3.4's importer and numpy 1.24
    numpy.bool = bool

glb, trees, points_in, points_out = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb)
scene = bpy.context.scene
objects = list(scene.objects)
tree_objects = [o for o in objects if o.name.startswith("tree-") and o.name.endswith("_LOD0")]
cameras = [o for o in objects if o.type == "CAMERA"]
lights = [o for o in objects if o.type == "LIGHT"]
print(f"ok   {len(tree_objects)} tree objects (want {trees}), {len(cameras)} camera, "
      f"{len(lights)} light")
if len(tree_objects) != int(trees) or len(cameras) != 1 or len(lights) != 1:
    print("FAIL objects")
    sys.exit(1)
camera = cameras[0]
scene.camera = camera
# The file's aspect ratio at a size pleinair's test uses.
scene.render.resolution_x, scene.render.resolution_y = 320, 180
scene.render.resolution_percentage = 100
spec = json.load(open(points_in))
# Points given in glTF's / pleinair's frame (x, y up, z), turned into Blender's (x, -z, y).
world = [Vector((p[0], -p[2], p[1])) for p in spec["points"]]
# Blender's importer starts the animation at frame 1 for time 0, at the scene's fps.
scene.render.fps = int(spec.get("fps", 24))
out = {"points": spec["points"], "frames": {}}
for frame in spec["frames"]:
    scene.frame_set(frame)
    out["frames"][str(frame)] = [
        [c.x * 320, (1.0 - c.y) * 180, c.z]
        for c in (world_to_camera_view(scene, camera, p) for p in world)]
json.dump(out, open(points_out, "w"), indent=1)
print(f"ok   projected {len(world)} points at {len(spec['frames'])} frames")
