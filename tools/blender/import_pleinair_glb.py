# Imports a pleinair tree.glb into Blender 3.4 or later, keeping what Blender's own importer
# drops: the leaf cards' custom vertex attributes (_BRANCH_DISTANCE, _LABEL, _PIVOT, ...), which
# become point attributes of the same names (without the underscore) that geometry nodes and
# shaders read through an Attribute node.
#
#   blender -P tools/blender/import_pleinair_glb.py -- tree.glb [more.glb ...]
#
# or, from Blender's Python console or another script: import_pleinair_glb.import_glb(path).
# Blender 3.4's importer (io_scene_gltf2 3.4.50, gltf2_blender_mesh.py) reads POSITION, NORMAL,
# TEXCOORD_n, COLOR_n, JOINTS_n and WEIGHTS_n only; this reads the file's own accessors for the
# rest and matches Blender's vertex order (each primitive's used vertices in index order, the
# primitives one after another, with "merge vertices" off as it is by default).
import json
import struct
import sys

import numpy

# Debian 12 pairs Blender 3.4 with numpy 1.24, which removed the alias `numpy.bool` that the
# 3.4 importer still uses (gltf2_blender_mesh.py); restore it before the importer runs.
if "bool" not in numpy.__dict__:
    numpy.bool = bool

_COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
_DTYPES = {5120: numpy.int8, 5121: numpy.uint8, 5122: numpy.int16, 5123: numpy.uint16,
           5125: numpy.uint32, 5126: numpy.float32}


def read_glb(path):
    """The JSON and binary chunks of a GLB file."""
    with open(path, "rb") as f:
        data = f.read()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    if magic != b"glTF" or version != 2 or length > len(data):
        raise ValueError(f"{path}: not a glTF 2.0 binary")
    offset, doc, binary = 12, None, b""
    while offset + 8 <= length:
        size, kind = struct.unpack_from("<II", data, offset)
        chunk = data[offset + 8: offset + 8 + size]
        if kind == 0x4E4F534A:
            doc = json.loads(chunk)
        elif kind == 0x004E4942:
            binary = chunk
        offset += 8 + size
    return doc, binary


def accessor(doc, binary, index):
    """An accessor's values as a numpy array of shape (count, components)."""
    a = doc["accessors"][index]
    view = doc["bufferViews"][a["bufferView"]]
    n = _COMPONENTS[a["type"]]
    dtype = numpy.dtype(_DTYPES[a["componentType"]])
    start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    stride = view.get("byteStride", 0) or n * dtype.itemsize
    rows = [numpy.frombuffer(binary, dtype, n, start + i * stride) for i in range(a["count"])] \
        if stride != n * dtype.itemsize else \
        [numpy.frombuffer(binary, dtype, a["count"] * n, start)]
    return numpy.concatenate(rows).reshape(a["count"], n)


def custom_attributes(doc, binary, mesh):
    """Per Blender vertex of `mesh` (a glTF mesh), every custom attribute's values; vertices of
    a primitive without an attribute read 0."""
    pieces, names = [], set()
    for prim in mesh["primitives"]:
        count = doc["accessors"][prim["attributes"]["POSITION"]]["count"]
        used = numpy.unique(accessor(doc, binary, prim["indices"]).ravel()) \
            if "indices" in prim else numpy.arange(count)
        values = {k: accessor(doc, binary, v)[used] for k, v in prim["attributes"].items()
                  if k.startswith("_")}
        names.update(values)
        pieces.append((len(used), values))
    out = {}
    for name in sorted(names):
        width = next(v[name].shape[1] for _, v in pieces if name in v)
        out[name] = numpy.concatenate([v[name] if name in v else numpy.zeros((n, width), numpy.float32)
                                       for n, v in pieces])
    return out


def import_glb(path):
    """Imports `path` with Blender's glTF importer, then adds the custom attributes to each
    mesh object made from a glTF node. Returns the new objects."""
    import bpy
    before = set(bpy.data.objects)
    bpy.ops.import_scene.gltf(filepath=path)
    new = [o for o in bpy.data.objects if o not in before]
    doc, binary = read_glb(path)
    by_name = {o.name: o for o in new if o.type == "MESH"}
    for node in doc.get("nodes", []):
        obj = by_name.get(node.get("name"))
        if obj is None or "mesh" not in node:
            continue
        mesh = obj.data
        for name, values in custom_attributes(doc, binary, doc["meshes"][node["mesh"]]).items():
            if len(values) != len(mesh.vertices):
                raise ValueError(f"{path}: {name} has {len(values)} values for "
                                 f"{len(mesh.vertices)} vertices of {obj.name}")
            attr_name = name.lstrip("_").lower()
            if values.shape[1] == 1:
                attr = mesh.attributes.new(attr_name, "FLOAT", "POINT")
                attr.data.foreach_set("value", values.ravel().astype(numpy.float32))
            else:
                # glTF's Y-up vectors in Blender's Z-up frame, as the importer turns positions.
                v = values[:, :3].astype(numpy.float32)
                v = numpy.stack([v[:, 0], -v[:, 2], v[:, 1]], axis=1)
                attr = mesh.attributes.new(attr_name, "FLOAT_VECTOR", "POINT")
                attr.data.foreach_set("vector", v.ravel())
    return new


if __name__ == "__main__":
    for glb in sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []:
        for o in import_glb(glb):
            print(f"imported {o.name}")
