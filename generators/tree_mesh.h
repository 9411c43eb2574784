// The growing tree's control mesh: an OpenMesh polygon mesh grown only by extruding quad faces,
// with every limb's rings and side faces recorded so later generators can walk them in a
// stable order. Included by the generators' .cpp files only; OpenMesh stays out of public headers.
#pragma once

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <array>
#include <glm/vec3.hpp>
#include <vector>

#include "generators/quad_mesh.h"
#include "generators/tree_params.h"

namespace pleinair {

struct TreeMeshTraits : public OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
    HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};
using ControlMesh = OpenMesh::PolyMesh_ArrayKernelT<TreeMeshTraits>;

// Four vertices counter-clockwise about the limb's growth direction.
using Ring = std::array<OpenMesh::VertexHandle, 4>;

// The trunk (level 0) or one branch. Ring 0 of a branch is the parent face it grew from.
struct Limb {
    uint64_t key = 0;  // structural key: (parent key, segment, side), never an index
    int level = 0;     // 0 trunk, 1 branch, 2 twig
    int parent = -1;   // index of the parent limb
    int parent_segment = -1;
    std::vector<Ring> rings;
    std::vector<OpenMesh::FaceHandle> sides;  // sides[4 * s + j]: segment s (rings s, s+1), side j;
                                              // invalid once a branch has grown from it
    OpenMesh::FaceHandle top;                 // the cap the next extrusion moves
    std::vector<glm::dvec3> centers;          // ring centroids: the limb's skeleton
    std::vector<double> radii;                // mean distance of a ring's vertices to its centroid
    glm::dvec3 direction{0, 1, 0};            // direction of the last extrusion
    glm::dvec3 heading{0, 1, 0};              // where growth is steering (before turn limits)
    double length = 0;                        // sum of extrusion lengths
};

struct TreeMesh {
    ControlMesh mesh;
    std::vector<Limb> limbs;
    double unit = 1;
    double min_radius = 0;  // no ring is ever smaller: keeps faces non-degenerate (taper 0)

    TreeMesh();
    glm::dvec3 point(OpenMesh::VertexHandle v) const;
};

// Per-step growth parameters of a limb.
struct StepParams {
    const Param* extrude_length;
    const Param* twist;
    const Param* taper;
    const Param* wobble;
    glm::dvec3 tropism_direction{0, -1, 0};
    double tropism_strength = 0;  // drawn once per limb
    double tropism_increase = 0;  // per unit of the limb's length
};

// When a limb stops growing; checked before each step.
struct StopRule {
    int max_steps = 0;          // extrusions by this call
    double max_length = 1e300;  // limb length (branches)
    double max_height = 1e300;  // height of the last ring's centre (trunk)
};

// Extrudes the top ring of `limb` step by step. Every step draws the same numbers from `rng`
// whatever happens, so a stopped limb never shifts another's stream (each limb has its own).
void grow_limb(TreeMesh& tm, int limb, const StepParams& sp, const StopRule& stop, Rng& rng);

// Extrudes quad `face` (vertices `old_ring` in face order, counter-clockwise from outside): the
// face moves to the new vertices `pos` and four side quads join old vertex j to new vertex j.
Ring extrude_face(TreeMesh& tm, OpenMesh::FaceHandle face, const Ring& old_ring,
                  const std::array<glm::dvec3, 4>& pos, std::array<OpenMesh::FaceHandle, 4>& sides);

// The mesh as it stands; vertex i is OpenMesh vertex i, positions tree-local.
QuadMesh to_quad_mesh(const TreeMesh& tm);

// Small vector helpers shared by the generators (double precision, tree-local frame).
glm::dvec3 rotate(const glm::dvec3& v, const glm::dvec3& unit_axis, double radians);
glm::dvec3 any_perpendicular(const glm::dvec3& unit_v);
// Two unit vectors (u, w) with (u, w, n) a right-handed orthonormal frame, for unit n.
std::pair<glm::dvec3, glm::dvec3> orthonormal_basis(const glm::dvec3& unit_n);
glm::dvec3 safe_normalize(const glm::dvec3& v, const glm::dvec3& fallback);
// Turns unit vector `v` by `degrees` about an axis perpendicular to it at azimuth `turns` (0..1).
glm::dvec3 wobble_direction(const glm::dvec3& v, double degrees, double turns);
// The same turn given by the cosine and sine of its angle.
glm::dvec3 turn_direction(const glm::dvec3& v, double cos_t, double sin_t, double turns);
glm::dvec3 apply_tropism(const glm::dvec3& heading, const glm::dvec3& direction, double strength);
// A tropism's pull once `length` has grown (in world units, `unit` a tree unit): its strength
// plus its increase per tree unit, never below none (limbs and leaf strands alike).
double tropism_pull(double strength, double increase, double length, double unit);
double radians(double degrees);

}  // namespace pleinair
