// Ray queries against the scene's opaque surfaces (terrain, rocks, trunks) through Embree 3.
// Geometry is stored relative to an anchor point chosen by the caller (the terrain's centre,
// say), so a landscape 1e5 units from the origin keeps full float precision in Embree. Ray
// origins carry the error of whoever computed them in world space, so they are pushed off
// their surface (along its normal when given, and along the ray) by an epsilon scaled to the
// magnitude of their world coordinates. Embree stays inside rays.cpp.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <limits>
#include <memory>

#include "generators/quad_mesh.h"

namespace pleinair {

// The offset that lifts a ray origin off the surface it starts on: 32 float ulps of its
// largest world coordinate, never less than those of 1.
float ray_epsilon(const glm::dvec3& world_point);

struct RayHit {
    bool hit = false;
    float t = 0;  // along the unit direction, from the (un-offset) origin
    uint32_t geometry = 0;
    uint32_t primitive = 0;
    glm::vec3 normal{0.0f};  // unit, geometric, facing the ray's origin side as built
};

class RayScene {
  public:
    explicit RayScene(const glm::dvec3& anchor = glm::dvec3(0.0));
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    // Copies the mesh (world positions, placed by `offset`) into Embree; returns its id.
    uint32_t add_mesh(const QuadMesh& mesh, const glm::dvec3& offset = glm::dvec3(0.0));
    // Builds the acceleration structure; call once after the last add_mesh.
    void commit();
    uint32_t mesh_count() const;

    // Nearest hit along a unit direction, within tmax. `surface_normal`, if the origin lies
    // on a surface, is the direction it is lifted along (flipped to the ray's side).
    RayHit intersect(const glm::dvec3& origin, const glm::vec3& direction,
                     float tmax = std::numeric_limits<float>::infinity(),
                     const glm::vec3* surface_normal = nullptr) const;
    // Whether anything lies along the direction within tmax (a shadow ray).
    bool occluded(const glm::dvec3& origin, const glm::vec3& direction,
                  float tmax = std::numeric_limits<float>::infinity(),
                  const glm::vec3* surface_normal = nullptr) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace pleinair
