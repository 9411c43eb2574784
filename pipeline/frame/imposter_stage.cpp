// Graftal imposters in a shot and in a frame: each mesh's edges, rows, colours and directions
// once, then per frame its silhouette (and the edges about to become one) extruded and drawn.
#include "pipeline/frame/imposter_stage.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "generators/rng.h"
#include "pipeline/frame/frame_view.h"
#include "pipeline/frame/graftal_stage.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/input/camera.h"
#include "pipeline/shot/landscape.h"
#include "pipeline/shot/rays.h"
#include "pipeline/shot/shot.h"
#include "shading/curves.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

glm::vec3 unit_or(const glm::dvec3& v, const glm::vec3& fallback) {
    const double l = glm::length(v);
    return l > 1e-12 && std::isfinite(l) ? glm::vec3(v / l) : fallback;
}

float smooth01(float e0, float e1, float x) {
    if (!(e1 > e0)) return x >= e1 ? 1.0f : 0.0f;
    const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

}  // namespace

std::vector<ImposterCandidate> imposter_candidates(const ImposterObject& o, const Camera& cam,
                                                   const glm::vec3& sun, double eye_speed) {
    std::vector<ImposterCandidate> out;
    const ImposterDesc& d = *o.desc;
    const QuadMesh& mesh = *o.mesh;
    const glm::dvec3 eye = glm::inverse(o.linear) * (cam.eye - o.position);
    const int columns = o.atlas ? o.atlas->columns : 1;
    for (uint32_t i = 0; i < o.edges.size(); ++i) {
        const MeshEdge& e = o.edges[i];
        glm::dvec3 pa(mesh.positions[e.a]), pb(mesh.positions[e.b]);
        const glm::dvec3 mid = 0.5 * (pa + pb);
        const glm::dvec3 to_eye = eye - mid;
        const double dist = glm::length(to_eye);
        if (!(dist > 0)) continue;
        const glm::vec3 v(to_eye / dist);
        const float fade = std::max(
            d.fade,
            static_cast<float>(std::min(1.0, 1.5 * d.fade_frames * eye_speed / (dist * o.scale))));
        const float c0 = glm::dot(o.normals[e.face0], v);
        float w = 0;
        uint32_t front = e.face0;
        if (e.face1 == MeshEdge::kBorder) {
            w = c0 > 0 ? 1.0f : 1.0f - smooth01(0.0f, fade, -c0);
        } else {
            const float c1 = glm::dot(o.normals[e.face1], v);
            // (N1.V)(N2.V) <= 0: a silhouette; otherwise as near to one as the nearer to edge-on
            // of its faces.
            w = c0 * c1 <= 0 ? 1.0f
                             : 1.0f - smooth01(0.0f, fade, std::min(std::abs(c0), std::abs(c1)));
            if (c1 > c0) front = e.face1;
        }
        const int row = o.rows[i];
        if (!(w > 0.0f) || row < 0) continue;
        if (d.width > 0) {
            // A base of the set length about the edge's middle (in the mesh's units, which a
            // tree's scale carries).
            const glm::dvec3 along = pb - pa;
            const double len = glm::length(along);
            if (len > 0) {
                const glm::dvec3 half = along * (0.5 * double(d.width) / len);
                pa = mid - half, pb = mid + half;
            }
        }
        ImposterCandidate c;
        c.edge = i;
        ImposterQuad& q = c.quad;
        const glm::dvec3 dir =
            glm::dvec3(unit_or(o.linear * glm::dvec3(o.directions[i]), glm::vec3(0, 1, 0))) *
            o.height;
        q.v0 = o.position + o.linear * pa, q.v1 = o.position + o.linear * pb;
        q.t0 = q.v0 + dir, q.t1 = q.v1 + dir;
        const Projection a = project(cam, q.v0), b = project(cam, q.v1);
        const Projection ta = project(cam, q.t0), tb = project(cam, q.t1);
        if (!a.in_front || !b.in_front || !ta.in_front || !tb.in_front) continue;
        const float lo_x = std::min({a.x, b.x, ta.x, tb.x}),
                    hi_x = std::max({a.x, b.x, ta.x, tb.x});
        const float lo_y = std::min({a.y, b.y, ta.y, tb.y}),
                    hi_y = std::max({a.y, b.y, ta.y, tb.y});
        if (!(hi_x > 0 && hi_y > 0 && lo_x < cam.width && lo_y < cam.height)) continue;
        // Its size on screen, not foreshortened (an edge turning end-on to the eye shrinks on
        // screen in a few frames; its imposter turns edge-on with it and needs no fade).
        if (d.min_edge_px > 0) {
            const double size_px = glm::length(q.v1 - q.v0) * cam.focal_px /
                                   std::max<double>(0.5 * (a.depth + b.depth), cam.near_depth);
            w *= smooth01(0.5f * d.min_edge_px, d.min_edge_px, static_cast<float>(size_px));
        }
        if (!(w > 0.0f)) continue;
        c.weight = w;
        q.row = row;
        // Each edge keeps its variation whatever the view: a hash of its vertices.
        q.column = static_cast<int>(hash_keys(o.key, std::min(e.a, e.b), std::max(e.a, e.b)) %
                                    static_cast<uint64_t>(columns));
        const glm::vec3 n = unit_or(o.linear * glm::dvec3(o.normals[front]), glm::vec3(0, 1, 0));
        const float shade = 1.0f - d.light + d.light * std::max(0.0f, glm::dot(n, sun));
        q.color0 = o.colors[e.a] * shade, q.color1 = o.colors[e.b] * shade;
        out.push_back(c);
    }
    return out;
}

ImposterStageReport add_imposter_sprites(const Shot& shot, const FrameView& view,
                                         SpriteSet& sprites, const SeenWindow* window) {
    ImposterStageReport rep;
    if (shot.imposters.empty()) return rep;
    const Camera& cam = view.camera;
    const glm::vec3 sun = glm::vec3(glm::normalize(view.sun_direction));
    rep.objects = shot.imposters.size();
    std::vector<std::vector<ImposterCandidate>> per_object(shot.imposters.size());
    tbb::parallel_for(size_t{0}, shot.imposters.size(), [&](size_t i) {
        per_object[i] = imposter_candidates(shot.imposters[i], cam, sun, view.eye_speed);
    });
    struct Draw {
        uint32_t object;
        ImposterCandidate c;
    };
    std::vector<Draw> draws;
    for (size_t i = 0; i < per_object.size(); ++i)
        for (const ImposterCandidate& c : per_object[i])
            draws.push_back({static_cast<uint32_t>(i), c});
    rep.candidates = draws.size();
    // How much of each the eye sees past the opaque surfaces, from points up its middle (its
    // base lies on the surface it grows from): the quad is the same whichever frame looks, so a
    // lattice time's ray is the same whichever frame casts it.
    std::vector<float> seen(draws.size(), 1.0f);
    std::vector<GraftalPatch> patches(draws.size());
    const bool windowed = window && !window->cameras.empty();
    tbb::parallel_for(size_t{0}, draws.size(), [&](size_t k) {
        const ImposterQuad& q = draws[k].c.quad;
        if (shot.view_rays) {
            const glm::dvec3 base = 0.5 * (q.v0 + q.v1), tip = 0.5 * (q.t0 + q.t1);
            auto seen_from = [&](const glm::dvec3& eye, int height) {
                const glm::dvec3 from = base + (tip - base) * ((height + 1) / 3.0);
                const glm::dvec3 to_eye = eye - from;
                const double dist = glm::length(to_eye);
                return !(dist > 0) || !shot.view_rays->occluded(from, glm::vec3(to_eye / dist),
                                                                static_cast<float>(dist) * 0.999f);
            };
            int n = 0, rays = 0;
            if (windowed) {
                for (size_t i = 0; i < window->cameras.size(); ++i)
                    n += seen_from(window->cameras[i].eye, window->heights[i]), ++rays;
            } else {
                for (int h = 0; h < 3; ++h) n += seen_from(cam.eye, h), ++rays;
            }
            seen[k] = float(n) / float(rays);
            if (n == 0) return;
        }
        patches[k] = draw_imposter(*shot.imposters[draws[k].object].atlas, q, cam);
    });
    const uint32_t first_item = static_cast<uint32_t>(shot.item_count() + shot.graftals.size());
    for (size_t k = 0; k < draws.size(); ++k) {
        if (!(seen[k] > 0.0f)) ++rep.hidden;
        GraftalPatch& patch = patches[k];
        if (patch.empty()) continue;
        const Draw& dr = draws[k];
        const ImposterObject& o = shot.imposters[dr.object];
        const ImposterQuad& q = dr.c.quad;
        const glm::dvec3 centre = 0.25 * (q.v0 + q.v1 + q.t0 + q.t1);
        Sprite sp = patch_sprite(patch, view, centre);
        sp.item = first_item + dr.object, sp.particle = dr.c.edge;
        sp.object_id = o.object_id;
        sp.fade = dr.c.weight * seen[k];
        sp.k.lightness = 1;
        rep.pixels += add_patch_sprite(sprites, sp, std::move(patch));
        ++rep.drawn;
    }
    return rep;
}

std::vector<float> imposter_presences(const Shot& shot, const FrameView& view) {
    std::vector<float> out;
    const Camera& cam = view.camera;
    const glm::vec3 sun = glm::vec3(glm::normalize(view.sun_direction));
    for (const ImposterObject& o : shot.imposters) {
        const size_t first = out.size();
        out.resize(first + o.edges.size(), 0.0f);
        for (size_t i = 0; i < o.edges.size(); ++i) {
            const MeshEdge& e = o.edges[i];
            const glm::dvec3 mid =
                o.position + o.linear * (0.5 * (glm::dvec3(o.mesh->positions[e.a]) +
                                                glm::dvec3(o.mesh->positions[e.b])));
            const Projection p = project(cam, mid);
            if (!p.in_front || !(p.x >= 0) || !(p.y >= 0) || !(p.x < cam.width) ||
                !(p.y < cam.height))
                out[first + i] = -1.0f;
        }
        for (const ImposterCandidate& c : imposter_candidates(o, cam, sun, view.eye_speed))
            if (out[first + c.edge] >= 0.0f) out[first + c.edge] = c.weight;
    }
    return out;
}

std::vector<uint64_t> imposter_keys(const Shot& shot) {
    std::vector<uint64_t> out;
    const uint32_t first_item = static_cast<uint32_t>(shot.item_count() + shot.graftals.size());
    for (size_t k = 0; k < shot.imposters.size(); ++k)
        for (size_t i = 0; i < shot.imposters[k].edges.size(); ++i)
            out.push_back(particle_key(first_item + static_cast<uint32_t>(k), SpriteKind::kGraftal,
                                       static_cast<uint32_t>(i)));
    return out;
}

void imposters_stage(const FrameContext& ctx, SpriteSet& sprites, const SeenWindow& seen) {
    StagePhase phase(ctx, "imposters");
    const ImposterStageReport im = add_imposter_sprites(ctx.shot, ctx.view, sprites, &seen);
    ctx.report.imposter_sprites = im.drawn;
    phase.done("silhouette edges (and edges turning towards one) of " + std::to_string(im.objects) +
                   " meshes extruded along the vector field, drawn from the atlas and keyed",
               std::to_string(im.candidates) + " edges the control allows, " +
                   std::to_string(im.hidden) + " hidden, " + std::to_string(im.drawn) +
                   " imposters drawn, " + std::to_string(im.pixels) + " patch pixels");
}

}  // namespace pleinair
