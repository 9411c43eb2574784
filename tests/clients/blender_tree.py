# Blender 3.4 (headless) imports a pleinair tree.glb: the test checks the objects and their
# triangle counts per material, that the tree stands upright in Blender's Z-up world at the
# height pleinair reports, that the leaf cards' custom attributes survive (through
# tools/blender/import_pleinair_glb.py) with one label per leaf, and that the preset and seed
# arrive as custom properties. Exit code 1 with the failed checks listed.
#
#   blender -b --factory-startup --python-exit-code 1 -P tests/clients/blender_tree.py -- tree.glb stats.json PRESET SEED
import json
import os
import sys

import bpy
import numpy

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tools", "blender"))
import import_pleinair_glb  # noqa: E402

glb, stats_path, preset, seed = sys.argv[sys.argv.index("--") + 1:]
stats = json.load(open(stats_path))
tree = json.load(open(os.path.join(os.path.dirname(glb), "tree.json")))
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


bpy.ops.wm.read_factory_settings(use_empty=True)
objects = import_pleinair_glb.import_glb(glb)
name = f"{preset}-seed-{seed}"
by_name = {o.name: o for o in objects}
check(set(by_name) >= {name, name + "_LOD0", name + "_LOD1"},
      f"objects {sorted(by_name)} hold {name}, _LOD0 and _LOD1")
if failures:
    sys.exit(1)
root, lod0, lod1 = by_name[name], by_name[name + "_LOD0"], by_name[name + "_LOD1"]

# Extras become the root's custom properties.
check(root.get("preset") == preset and int(root.get("seed")) == int(seed),
      f"root properties preset={root.get('preset')} seed={root.get('seed')}")


def triangles_per_material(obj):
    names = [m.name for m in obj.data.materials]
    counts = dict.fromkeys(names, 0)
    for p in obj.data.polygons:
        counts[names[p.material_index]] += 1
    check(all(len(p.vertices) == 3 for p in obj.data.polygons), f"{obj.name}: triangles only")
    return counts


counts = tree["counts"]
got0 = triangles_per_material(lod0)
check(got0 == {"bark": 2 * counts["render_faces"], "leaves": 4 * counts["leaves"]},
      f"LOD0 triangles {got0}: 2 per render face ({counts['render_faces']}), 4 per leaf "
      f"({counts['leaves']})")
got1 = triangles_per_material(lod1)
check(got1["bark"] == 2 * counts["lod_faces"] and 0 < got1["leaves"] < 4 * counts["leaves"],
      f"LOD1 triangles {got1}: 2 per low-detail face ({counts['lod_faces']}), fewer leaves")


def attribute(obj, attr):
    a = obj.data.attributes.get(attr)
    if a is None:
        return None
    n = len(obj.data.vertices)
    if a.data_type == "FLOAT_VECTOR":
        v = numpy.zeros(3 * n, numpy.float32)
        a.data.foreach_get("vector", v)
        return v.reshape(n, 3)
    v = numpy.zeros(n, numpy.float32)
    a.data.foreach_get("value", v)
    return v


names = ["branch_distance", "center_distance", "label", "tree_id", "fade_begin", "fade_end",
         "limb", "limb_level", "stiffness", "pivot", "particle_position", "particle_normal"]
missing = [n for n in names if lod0.data.attributes.get(n) is None]
check(not missing, f"custom attributes survive (missing: {missing})")

# Leaf vertices: those of polygons with the leaves material.
leaf_material = [m.name for m in lod0.data.materials].index("leaves")
leaf_vertices = numpy.unique([v for p in lod0.data.polygons if p.material_index == leaf_material
                              for v in p.vertices])
labels = attribute(lod0, "label")[leaf_vertices]
check(len(numpy.unique(labels)) == counts["leaves"],
      f"{len(numpy.unique(labels))} distinct labels for {counts['leaves']} leaves")
cd = attribute(lod0, "center_distance")[leaf_vertices]
check(cd.min() >= 0 and cd.max() <= 1, f"centre distances in [0, 1] ({cd.min()}..{cd.max()})")

# Upright at the right height: the bark's vertices and the leaf particles (Blender's Z-up world)
# span the box `pleinair tree --stats` reports in pleinair's Y-up world.
world = numpy.array([list(lod0.matrix_world @ v.co) for v in lod0.data.vertices], numpy.float64)
bark_vertices = numpy.setdiff1d(numpy.arange(len(world)), leaf_vertices)
offset = numpy.array(list(root.matrix_world.translation))
particles = attribute(lod0, "particle_position")[leaf_vertices].astype(numpy.float64) + offset
points = numpy.concatenate([world[bark_vertices], particles])
lo, hi = points.min(axis=0), points.max(axis=0)
smin, smax = stats["bbox"]["min"], stats["bbox"]["max"]
want_lo = numpy.array([smin[0], -smax[2], smin[1]])
want_hi = numpy.array([smax[0], -smin[2], smax[1]])
check(numpy.abs(lo - want_lo).max() < 1e-3 and numpy.abs(hi - want_hi).max() < 1e-3,
      f"Blender box {lo.round(4)}..{hi.round(4)} is pleinair's Y-up box turned Z-up "
      f"{want_lo.round(4)}..{want_hi.round(4)}")
check(hi[2] - lo[2] > 0.5 * (smax[1] - smin[1]) and lo[2] < hi[2],
      f"the tree stands along +Z, {hi[2] - lo[2]:.3f} tall")

print(f"{len(failures)} failed")
sys.exit(1 if failures else 0)
