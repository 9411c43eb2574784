// glTF 2.0 files read into a scene (through tinygltf): the triangles of named mesh nodes as
// surfaces that grow strokes, and a camera node with its animation as the camera track.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "generators/quad_mesh.h"
#include "pipeline/input/camera_track.h"

namespace pleinair {

// A glTF document, parsed and checked: every accessor pleinair reads lies inside its buffer.
// Throws InputError naming `source` and `pointer`: a file that is missing, not glTF, truncated,
// or over the particle_file_mb limit.
struct GltfDocument;
std::shared_ptr<const GltfDocument> load_gltf(const std::filesystem::path& path,
                                              const std::string& source,
                                              const std::string& pointer);
// The same from bytes in memory, named `name` in errors. Buffers a .gltf names by a relative
// URI are read from `base` (as load_gltf reads them beside the file); with `base` empty no
// file is read, and such a buffer is refused (the fuzz target).
std::shared_ptr<const GltfDocument> parse_gltf(const std::string& bytes, const std::string& name,
                                               const std::filesystem::path& base,
                                               const std::string& source,
                                               const std::string& pointer);

// The triangles of the mesh nodes named in `nodes` (all mesh nodes of the default scene when
// empty), in world space: each node's transform down the hierarchy, then `scale` and
// `position`. Triangles are quads whose last corner repeats the third (Embree reads them so).
// Throws InputError for a node name not in the file, a primitive that is not triangles, an
// index past its vertices, a vertex that is not finite, or an accessor of the wrong type, each
// named by its mesh and primitive.
QuadMesh gltf_triangles(const GltfDocument& doc, const std::vector<std::string>& nodes,
                        const glm::dvec3& position, double scale, const std::string& source,
                        const std::string& pointer);

// A camera node as a camera track: one key per time its animation samples (translation and
// rotation channels of the node and its parents, linear between them as Blender bakes them),
// looking down the node's -z with its +y up, focused `focus_distance` ahead; fov from the
// camera's yfov (kept at any image shape: the file's aspect ratio is not enforced). `name`
// picks the node (empty: the first node with a camera). A camera without animation gives one
// key. Times start at 0 where the file's first sample is, and
// samples within a thousandth of a frame of the `fps` grid are put on it (Blender's float
// times), so frame N of the scene is the file's N-th baked frame.
CameraTrack gltf_camera_track(const GltfDocument& doc, const std::string& name,
                              double focus_distance, double fps, const std::string& source,
                              const std::string& pointer);

}  // namespace pleinair
