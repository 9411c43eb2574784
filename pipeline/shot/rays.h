// Ray queries against the scene's surfaces (terrain, water, rocks, trunks) and its brush-stroke
// shadow casters, through Embree 3. Geometry is stored relative to an anchor point chosen by the
// caller (the terrain's centre, say), so a landscape 1e5 units from the origin keeps full float
// precision in Embree. Ray origins carry the error of whoever computed them in world space, so
// they are pushed off their surface (along its normal when given, and along the ray) by an
// epsilon scaled to the magnitude of their world coordinates. Embree stays inside rays.cpp.
#pragma once

#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "generators/quad_mesh.h"
#include "pipeline/input/settings.h"
#include "shading/portable_math.h"
#include "shading/stroke_shader.h"

namespace pleinair {

// Embree's device configuration (rtcNewDevice's argument). Left to itself Embree picks the
// widest instruction set the CPU has, and its BVH and hit tests differ with it (4- or 8-wide
// nodes, FMA or not), so the same scene would paint other bytes on another CPU. pleinair pins
// SSE2, which every x86-64 CPU runs, at a cost in speed measured by tests/bench/bench_rays.cpp
// (BENCHMARKS.md); `--fast-rays` gives the choice back to Embree.
inline constexpr const char* kPortableRayDevice = "isa=sse2";

// The configuration given to every device created after this call (empty: Embree's defaults).
// For tests and benchmarks; not thread-safe, so set it before building shots.
void set_ray_device_config(const std::string& config);

// The offset that lifts a ray origin off the surface it starts on: 32 float ulps of its
// largest coordinate (relative to the ray scene's anchor, as Embree sees it), never less than
// those of 1.
float ray_epsilon(const glm::dvec3& world_point);

// Flush-to-zero and denormals-are-zero for the current thread while in scope (Embree asks for
// both in every thread that traces); the previous modes come back on exit, so code that runs
// later on the same worker computes as it would have.
class FlushDenormals {
  public:
    FlushDenormals();
    ~FlushDenormals();
    FlushDenormals(const FlushDenormals&) = delete;
    FlushDenormals& operator=(const FlushDenormals&) = delete;

  private:
    unsigned saved_;
};

struct RayHit {
    bool hit = false;
    float t = 0;  // along the unit direction, from the (un-offset) origin
    uint32_t geometry = 0;
    uint32_t primitive = 0;
    glm::vec3 normal{0.0f};  // unit, geometric, facing the ray's origin side as built
};

// A leaf stroke as a shadow caster: a square-ish card facing the sun whose opacity is the same
// stroke mask the painter draws (IV.4.2: shadows fall as brush strokes, never as squares).
struct StrokeCaster {
    glm::dvec3 center{0.0};              // world
    glm::vec3 axis_s{1, 0, 0};           // unit, across the stroke
    glm::vec3 axis_t{0, 1, 0};           // unit, along it; both perpendicular to the sun
    float half_w = 0.5f, half_l = 0.5f;  // world units
    StrokeNoise noise;                   // noise frequencies and offsets of the stroke
};

// The frame a caster card facing the sun (unit) is turned in: a0 across, b0 along, both
// perpendicular to it. a0 lies in the horizontal plane, so a tree turned about the vertical
// sees its cards turned with it (what lets members' cards serve every tree); only a sun
// straight overhead takes the x axis instead.
inline void sun_card_frame(const glm::vec3& sun, glm::vec3& a0, glm::vec3& b0) {
    const bool overhead = sun.x * sun.x + sun.z * sun.z < 1e-12f;
    const glm::vec3 ref = overhead ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    a0 = glm::normalize(glm::cross(ref, sun));
    b0 = glm::cross(sun, a0);
}

// The axes of a caster card in that frame, turned in its plane by its stroke's angle jitter
// (leaf and imported strokes' cards in the world, a member's in the sun scene's filter).
// The same from the angle's cosine and sine (kept per card by whoever turns many).
inline void sun_card_turn(float ca, float sa, const glm::vec3& a0, const glm::vec3& b0,
                          glm::vec3& axis_s, glm::vec3& axis_t) {
    axis_s = ca * a0 + sa * b0;
    axis_t = -sa * a0 + ca * b0;
}
inline void sun_card_axes(const StrokeShaderParams& p, float label, const glm::vec3& a0,
                          const glm::vec3& b0, glm::vec3& axis_s, glm::vec3& axis_t) {
    const double ang = stroke_angle_jitter(p, label);
    sun_card_turn(static_cast<float>(pmath::cos(ang)), static_cast<float>(pmath::sin(ang)), a0, b0,
                  axis_s, axis_t);
}

// A grown tree's leaf strokes as shadow casters in its own space (IV.4.2), for the sun's scenes
// to place by instances: each card faces the sun as the ray crossing it sees it (in the tree's
// space, so a turned tree's cards face the sun too) and is turned by its stroke's angle
// jitter, so one set serves every tree drawn from the member and any sun direction. The arrays
// are the member's leaf particles and must outlive the scenes, as must the shader and edge.
struct MemberCasters {
    size_t count = 0;
    const glm::vec3* position = nullptr;  // card centres
    const glm::vec3* normal = nullptr;    // unit: the stroke's lightness against the sun
    const float* label = nullptr;
    const float* center_distance = nullptr;
    const float* branch_distance = nullptr;
    float stroke_width = 0;  // before the size jitter, in the member's units
    const StrokeShaderParams* shader = nullptr;
    const EdgeTable* edge = nullptr;
};

// Meshes several RayScenes share (each tree's limbs, in the camera's scene and the sun's),
// each kept in its own space and built once; scenes place them as instances. A scene holds
// its own reference to the device and the meshes, so either may be destroyed first.
class RayMeshes {
  public:
    RayMeshes();
    ~RayMeshes();
    RayMeshes(const RayMeshes&) = delete;
    RayMeshes& operator=(const RayMeshes&) = delete;

    // Copies the mesh into Embree, in its own coordinates; returns its index.
    uint32_t add(const QuadMesh& mesh);
    // A member's leaf casters (cards in its own space), built into their own scene; returns
    // its index for RayScene::add_caster_instance.
    uint32_t add_casters(const MemberCasters& casters);
    // Builds every mesh's and caster set's acceleration structure, in parallel; call once
    // after the last add.
    void commit();
    uint32_t size() const;
    uint32_t caster_sets() const;

    struct Impl;

  private:
    std::shared_ptr<Impl> impl_;
    friend class RayScene;
};

class RayScene {
  public:
    // With `shared`, the scene lives on its device and can place its meshes by add_instance.
    explicit RayScene(const glm::dvec3& anchor = glm::dvec3(0.0),
                      const RayMeshes* shared = nullptr);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    // Copies the mesh (world positions, placed by `offset`) into Embree; returns its id.
    uint32_t add_mesh(const QuadMesh& mesh, const glm::dvec3& offset = glm::dvec3(0.0));
    // Places shared mesh `mesh` (committed) at world = offset + linear * p; returns the
    // geometry id, which hits on it report. `linear` must be invertible.
    uint32_t add_instance(uint32_t mesh, const glm::dmat3& linear, const glm::dvec3& offset);
    // Adds stroke casters, evaluated by an occlusion filter with the given stroke parameters
    // (which must outlive the scene). Returns the geometry id; primitive i is casters[i].
    uint32_t add_casters(const std::vector<StrokeCaster>& casters, const StrokeShaderParams& shader,
                         const EdgeTable& edge);
    // Places shared caster set `set` (committed) at world = offset + linear * p, for a linear
    // part that is a turn about the vertical times a uniform scale (a tree's placement): the
    // cards face the sun in the set's space, which is the world's turned about the vertical.
    // Returns the instance's id among the caster geometries.
    uint32_t add_caster_instance(uint32_t set, const glm::dmat3& linear, const glm::dvec3& offset);
    // Builds the acceleration structure; call once after the last add.
    void commit();
    uint32_t mesh_count() const;           // meshes and instances
    uint32_t caster_count() const;         // cards, counting each instance's
    uint32_t caster_cards_stored() const;  // cards this scene holds itself (not instanced)

    // Nearest hit along a unit direction, within tmax. `surface_normal`, if the origin lies
    // on a surface, is the direction it is lifted along (flipped to the ray's side). Stroke
    // casters are invisible to this query.
    RayHit intersect(const glm::dvec3& origin, const glm::vec3& direction,
                     float tmax = std::numeric_limits<float>::infinity(),
                     const glm::vec3* surface_normal = nullptr) const;
    // Whether anything opaque lies along the direction within tmax; casters count as their
    // stroke mask thresholded at one half.
    bool occluded(const glm::dvec3& origin, const glm::vec3& direction,
                  float tmax = std::numeric_limits<float>::infinity(),
                  const glm::vec3* surface_normal = nullptr) const;
    // The light that gets through along the direction: 0 behind an opaque surface, else the
    // product of (1 - stroke opacity) over the casters crossed (kTransmissive) or 0/1 by the
    // threshold (kThreshold).
    float transmittance(const glm::dvec3& origin, const glm::vec3& direction, ShadowMode mode,
                        float tmax = std::numeric_limits<float>::infinity(),
                        const glm::vec3* surface_normal = nullptr) const;
    // transmittance (kTransmissive) that walks through every card, none blocking, and gives in
    // `distance` the cards' mean distance along the ray weighed by the light each takes (0
    // when none): where a mirror's ray meets the leaves it mirrors, for their haze. Light under
    // a thousandth counts as none, as transmittance's.
    float transmittance_depth(const glm::dvec3& origin, const glm::vec3& direction, float tmax,
                              const glm::vec3* surface_normal, float& distance) const;

  private:
    // transmittance, or with `distance` transmittance_depth's walk through every card.
    float through_casters(const glm::dvec3& origin, const glm::vec3& direction, ShadowMode mode,
                          float tmax, const glm::vec3* surface_normal, float* distance) const;
    uint32_t attach(void* geometry, const glm::mat3& normal_to_world);  // an RTCGeometry
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace pleinair
