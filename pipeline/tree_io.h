// Tree files: meshes as OBJ and PLY through OpenMesh's writers, leaf particles as a binary PLY
// point cloud whose vertex properties are every particle attribute by name, and tree.json.
#pragma once

#include <filesystem>
#include <string>

#include "generators/tree.h"

namespace pleinair {

// The files of one tree, as bytes; world space = tree.origin + tree-local, summed in double.
std::string mesh_obj(const QuadMesh& mesh, const glm::dvec3& origin);
std::string mesh_ply(const QuadMesh& mesh, const glm::dvec3& origin);
std::string leaves_ply(const LeafParticles& leaves, const glm::dvec3& origin);
std::string tree_json(const Tree& tree, const std::string& preset_name);

// Writes control.{obj,ply}, render.{obj,ply}, lod.{obj,ply} (when built), leaves.ply and
// tree.json into `dir` (created), each file atomically. Throws std::runtime_error on failure.
void write_tree(const Tree& tree, const std::string& preset_name, const std::filesystem::path& dir);

}  // namespace pleinair
