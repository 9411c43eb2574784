// Tree files: meshes as OBJ and PLY through OpenMesh's writers, leaf particles as a binary PLY
// point cloud whose vertex properties are every particle attribute by name, and tree.json.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "generators/tree.h"
#include "pipeline/output/gltf_tree.h"

namespace pleinair {

// The files of one tree, as bytes; world space = tree.origin + tree-local, summed in double.
std::string mesh_obj(const QuadMesh& mesh, const glm::dvec3& origin);
std::string mesh_ply(const QuadMesh& mesh, const glm::dvec3& origin);
// Besides the thesis's attributes, each particle's wind rig (generators/wind.h) for a Blender
// or Houdini user to drive the same motion: `limb` (tree.json's branch id it hangs on),
// `limb_level` (0 trunk, 1 branch, 2 twig: Pivot Painter's hierarchy depth), `pivot_x/y/z` (its
// limb's base, world: Pivot Painter's per-element pivot) and `stiffness` (its limb's, the
// preset's /stiffness/trunk or /stiffness/limbs). Limbs' parents, ends and ring centres are in
// tree.json.
std::string leaves_ply(const LeafParticles& leaves, const glm::dvec3& origin,
                       const std::vector<BranchInfo>& limbs = {},
                       const WindStiffness& stiffness = {});
std::string leaves_ply(const Tree& tree, const WindStiffness& stiffness = {});
std::string tree_json(const Tree& tree, const std::string& preset_name,
                      const WindStiffness& stiffness = {});

// Which files a tree folder holds besides tree.json: `all` the OBJ and PLY meshes, leaves.ply
// and tree.glb; `glb` tree.glb alone; `obj-ply` all but tree.glb.
enum class TreeFormat { kAll, kGlb, kObjPly };
// The names `--format` takes, and the format of one (nullptr-like false for an unknown name).
bool parse_tree_format(const std::string& name, TreeFormat& format);

struct TreeOutput {
    WindStiffness stiffness;  // the preset's, carried into leaves.ply, tree.json and tree.glb
    TreeLook look;            // tree.glb's leaf cards and materials
    TreeFormat format = TreeFormat::kAll;
};

// Writes control.{obj,ply}, render.{obj,ply}, lod.{obj,ply} (when built), leaves.ply, tree.glb
// and tree.json (as `out.format` selects) into a temporary folder beside `dir`, renamed to
// `dir` once every file is written, replacing an earlier tree folder there
// (PartialOutput::commit): the folder is complete or absent. Throws InputError if `dir` may not
// be replaced (check_output_folder) and std::runtime_error naming the file that failed; the
// temporary folder is removed then.
void write_tree(const Tree& tree, const std::string& preset_name, const std::filesystem::path& dir,
                const TreeOutput& out = {});

// A family's folder: per member a tree folder `PRESET-III-seed-SEED` and family.json listing
// them, written into a temporary folder renamed to `dir` when complete, like write_tree.
void write_family(const std::vector<Tree>& trees, const std::string& preset_name,
                  uint64_t base_seed, const std::filesystem::path& dir, const TreeOutput& out = {});

// Throws InputError unless `dir` is absent or a folder that a tree or family output may replace
// as a whole: an empty one, or one holding `marker` ("tree.json", "family.json"). Anything else
// is someone's folder, never deleted to make room.
void check_output_folder(const std::filesystem::path& dir, const std::string& marker);

}  // namespace pleinair
