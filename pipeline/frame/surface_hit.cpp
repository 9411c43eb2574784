// surface_hit: what a camera or mirror ray that meets a surface sees of it, flat.
#include "pipeline/frame/surface_hit.h"

#include <glm/geometric.hpp>

#include "pipeline/frame/distance_mass.h"
#include "pipeline/shot/shot.h"

namespace pleinair {

MaterialId surface_material(const Shot& shot, const RayHit& h, const glm::dvec3& world,
                            bool& water) {
    const ViewSurface& vs = shot.view_surfaces[h.geometry];
    const MaterialId mat =
        vs.terrain ? shot.materials.surface(terrain_material_at(shot.scene, world)) : vs.material;
    water = !vs.terrain && mat == shot.materials.surface(shot.scene.water.material);
    return mat;
}

SurfaceHit surface_hit(const Shot& shot, const FrameView& view, const FramePlan& plan,
                       const RenderSettings& rs, const RayScene* sun_rays, const RayHit& h,
                       const glm::dvec3& world, glm::vec3 n, const glm::dvec3& dir, float depth) {
    const SceneDesc& scene = shot.scene;
    if (glm::dot(glm::dvec3(n), dir) > 0) n = -n;
    SurfaceHit out;
    const MaterialId mat = surface_material(shot, h, world, out.water);
    const SpriteMaterial& m = shot.materials[mat];
    const glm::vec3 sun(view.sun_direction);
    const float n_dot_l = glm::dot(n, sun);
    // A middle-depth stroke's lightness, a little darker: paint under paint.
    float l = m.surface ? surface_lightness(*m.surface, n_dot_l, 0.5f) : clamp01(n_dot_l);
    l *= 0.9f;
    float sh = 1.0f;
    if (plan.shadows && sun_rays)
        sh = sun_light_at(*sun_rays, RayOrigin{world, n, true, 0.01f}, sun, rs.shadows);
    sh *= cloud_light(scene.clouds, world.x, world.z);
    if (sh < 1.0f) l *= shadow_remap(sh, m.shader->shadow_bias);
    const Camera& cam = view.camera;
    if (depth < 0.0f) depth = static_cast<float>(glm::dot(world - cam.eye, cam.forward));
    float d = 0;
    if (plan.atmosphere)
        d = distance_value(depth, scene.atmosphere.near_distance, scene.atmosphere.far_distance,
                           m.shader->dist_curve_bias);
    out.k = stroke_constants(*m.shader, n_dot_l, 0.5f, 0.5f, 0.5f, 0, 1.0f, d, 0.0f, false,
                             plan.atmosphere && has_atmosphere_effect(*m.shader));
    if (plan.atmosphere) lay_in_distance_value(scene.atmosphere, depth, out.k);
    out.base = palette_lookup(*m.palette, l);
    out.n = n;
    out.material = mat;
    out.sun = sh;
    return out;
}

Color surface_hit_color(const Shot& shot, const FrameView& view, const FramePlan& plan,
                        const RenderSettings& rs, const RayScene* sun_rays, const RayHit& h,
                        const glm::dvec3& world, const glm::vec3& n, const glm::dvec3& dir,
                        float depth) {
    const SurfaceHit s = surface_hit(shot, view, plan, rs, sun_rays, h, world, n, dir, depth);
    return finish_color(s.k, s.base);
}

}  // namespace pleinair
