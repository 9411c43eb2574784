// Graftals in a shot and in a frame: sites and tufts once, then per frame the tufts' levels
// (replayed along the track), the graftals' poses and their patches.
#include "pipeline/frame/graftal_stage.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "generators/rng.h"
#include "generators/tree_mesh.h"
#include "pipeline/frame/frame_view.h"
#include "pipeline/frame/graftal_placement.h"
#include "pipeline/shot/graftal_draw.h"
#include "pipeline/shot/graftal_lod.h"
#include "pipeline/shot/shot.h"
#include "shading/curves.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

// λ of a graftal of world length `length` at `position` with normal `n`, seen by `cam`, at τ
// (its ρ too, when asked).
float lambda_of(const GraftalDesc& d, const Camera& cam, const glm::dvec3& position,
                const glm::vec3& n, double length, float tau, float* rho_out = nullptr) {
    const glm::dvec3 to_eye = cam.eye - position;
    const double dist = glm::length(to_eye);
    const glm::vec3 v(safe_normalize(to_eye, -cam.forward));
    const float sigma = graftal_sigma(length, d.preferred_size_px, dist, cam.focal_px);
    const float rho = graftal_rho(d.rho, n, v);
    if (rho_out) *rho_out = rho;
    return graftal_lambda(d.lambda, sigma, rho, tau);
}

// Each tuft's state at the last frame of `path`, its λ replayed along it, tufts in parallel.
std::vector<TuftState> tuft_states(const Shot& shot, const ShotGraftals& g,
                                   const std::vector<FrameView>& path) {
    const GraftalDesc& d = *g.desc;
    std::vector<TuftState> states(g.sites.size());
    tbb::parallel_for(size_t{0}, g.sites.size(), [&](size_t s) {
        const GraftalSite& site = g.sites[s];
        states[s] = replay_tuft(
            d.tuft,
            [&](int f) {
                return lambda_of(d, path[static_cast<size_t>(f)].camera, site.position, site.normal,
                                 d.length, 1.0f);
            },
            static_cast<int>(path.size()) - 1, shot.scene.fps);
    });
    return states;
}

// A graftal's τ: it waits `delay` of its level's transition, then grows over the rest.
float instance_tau(const GraftalInstance& inst, const TuftState& st) {
    const float level_tau = inst.level < st.tau.size() ? st.tau[inst.level] : 0.0f;
    return inst.delay < 1.0f ? clamp01((level_tau - inst.delay) / (1.0f - inst.delay))
                             : (level_tau >= 1.0f ? 1.0f : 0.0f);
}

// Whether a graftal's base lies on screen, or near enough that it may reach onto it.
bool near_screen(const Camera& cam, const GraftalInstance& inst, Projection& p) {
    p = project(cam, inst.position);
    const double reach =
        2.0 * inst.length * cam.focal_px / std::max<double>(p.depth, cam.near_depth);
    return p.in_front && p.x >= -reach && p.y >= -reach && p.x <= cam.width + reach &&
           p.y <= cam.height + reach;
}

}  // namespace

std::vector<std::vector<float>> difference_placement(const Shot& shot, const Camera& cam) {
    std::vector<std::vector<float>> placed(shot.graftals.size());
    const GraftalDesc* first = nullptr;
    for (size_t gi = 0; gi < shot.graftals.size(); ++gi) {
        const ShotGraftals& g = shot.graftals[gi];
        if (g.desc->placement != GraftalPlacement::kDifference) continue;
        placed[gi].assign(g.sites.size(), 0.0f);
        if (!first) first = g.desc.get();
    }
    if (!first) return placed;
    // One image of dots for every such group (the first one's cell, dot and threshold), so
    // tufts of crowns overlapping on screen space each other out; it covers the frame and a
    // margin of a quarter of its larger side, where tufts standing outside reach in.
    const int cell = std::max(first->cell_px, 1);
    const int margin = (std::max(cam.width, cam.height) / 4 + cell - 1) / cell * cell;
    DesireImage img;
    img.width = (cam.width + 2 * margin + cell - 1) / cell;
    img.height = (cam.height + 2 * margin + cell - 1) / cell;
    const size_t cells = static_cast<size_t>(img.width) * img.height;
    img.desire.assign(cells, 0.0f);
    img.id.assign(cells, 0u);
    std::vector<float> nearest(cells, std::numeric_limits<float>::infinity());
    std::vector<float> other(cells, std::numeric_limits<float>::infinity());
    std::vector<GraftalCandidate> candidates;
    std::vector<std::pair<uint32_t, uint32_t>> from;  // (group, site) of each candidate
    std::vector<float> depth;
    std::vector<size_t> cell_of;
    for (size_t gi = 0; gi < shot.graftals.size(); ++gi) {
        const ShotGraftals& g = shot.graftals[gi];
        if (placed[gi].empty()) continue;
        for (size_t s = 0; s < g.sites.size(); ++s) {
            const GraftalSite& site = g.sites[s];
            const Projection p = project(cam, site.position);
            // In the frame or its margin: a tuft standing just outside still reaches in.
            const double px = p.x + margin, py = p.y + margin;
            if (!p.in_front || !(px >= 0) || !(py >= 0) || !(px < img.width * double(cell)) ||
                !(py < img.height * double(cell)))
                continue;
            const int cx = std::min(static_cast<int>(px) / cell, img.width - 1);
            const int cy = std::min(static_cast<int>(py) / cell, img.height - 1);
            const size_t c = static_cast<size_t>(cy) * img.width + cx;
            // Desire where detail is wanted: the description's ρ (file 004's N.V).
            const glm::vec3 v(safe_normalize(cam.eye - site.position, -cam.forward));
            const float rho = graftal_rho(g.desc->rho, site.normal, v);
            // The nearest candidate of each cell, and the nearest of any other object.
            if (p.depth < nearest[c]) {
                if (img.id[c] != site.object) other[c] = nearest[c];
                nearest[c] = p.depth, img.id[c] = site.object;
            } else if (site.object != img.id[c] && p.depth < other[c]) {
                other[c] = p.depth;
            }
            // Its own desire, exactly where it stands: it changes smoothly as the view moves,
            // where the image's cell values jump as candidates cross cells.
            candidates.push_back({glm::vec2(float(px / cell), float(py / cell)), site.object,
                                  mix64(site.object) ^ site.key, rho});
            depth.push_back(p.depth), cell_of.push_back(c);
            from.emplace_back(static_cast<uint32_t>(gi), static_cast<uint32_t>(s));
        }
    }
    // Hidden candidates want nothing: a candidate further than the nearest of another object in
    // its cell (another crown) by more than 2% of its distance loses its desire over the next
    // 6%, so occlusion fades a tuft instead of refusing it outright when the nearest changes.
    for (size_t k = 0; k < candidates.size(); ++k) {
        const size_t c = cell_of[k];
        const float occluder = candidates[k].object == img.id[c] ? other[c] : nearest[c];
        const float behind = (depth[k] - occluder) / std::max(depth[k], 1e-6f);
        candidates[k].desire *= 1.0f - smoothstep(0.02f, 0.08f, behind);
    }
    img.id.clear();  // occlusion is in the candidates' own desire
    DifferencePlacement params;
    params.dot_row = std::max(first->dot_cells - 1, 0);
    params.threshold = first->threshold;
    params.band = first->band;
    std::vector<float> weights;
    const std::vector<uint32_t> chosen = place_candidates(img, candidates, params, &weights);
    for (size_t i = 0; i < chosen.size(); ++i)
        placed[from[chosen[i]].first][from[chosen[i]].second] = weights[i];
    return placed;
}

namespace {

// One graftal to draw: where it comes from and its pose.
struct Draw {
    uint32_t group, instance;
    GraftalPose pose;
    float weight;  // the difference image's (1 for other placements)
};

}  // namespace

Sprite patch_sprite(const GraftalPatch& patch, const FrameView& view, const glm::dvec3& at) {
    const Camera& cam = view.camera;
    Sprite sp;
    sp.kind = SpriteKind::kGraftal;
    sp.x = patch.x0 + 0.5f * patch.width, sp.y = patch.y0 + 0.5f * patch.height;
    sp.half_l = 0.5f * patch.width, sp.half_w = 0.5f * patch.height;
    sp.ax = 1, sp.ay = 0;
    sp.swap_speed =
        static_cast<float>(view.eye_speed * pmath::hypot(sp.half_w, sp.half_l) / cam.focal_px);
    sp.depth = project(cam, at).depth;
    sp.range = static_cast<float>(glm::length(cam.eye - at));
    return sp;
}

uint64_t add_patch_sprite(SpriteSet& sprites, Sprite sp, GraftalPatch patch) {
    const uint64_t pixels = patch.pixels.size();
    sp.patch = static_cast<int32_t>(sprites.patches.size());
    sprites.patches.push_back(std::move(patch));
    sprites.sprites.push_back(sp);
    ++sprites.graftal;
    return pixels;
}

GraftalStageReport add_graftal_sprites(const Shot& shot, const FrameView& view,
                                       const RenderSettings& settings, SpriteSet& sprites,
                                       const FrameView* lod_view) {
    GraftalStageReport rep;
    if (shot.graftals.empty()) return rep;
    const Camera& cam = view.camera;
    // The frames whose λ the filters have seen: the track from its first frame to this one.
    const std::vector<FrameView> path = replay_path(shot.scene, lod_view ? *lod_view : view);
    rep.replayed = path.size();
    const glm::vec3 sun = glm::vec3(glm::normalize(view.sun_direction));

    const std::vector<std::vector<float>> placed = difference_placement(shot, cam);
    std::vector<std::vector<Draw>> per_group(shot.graftals.size());
    std::vector<uint64_t> culled(shot.graftals.size(), 0), growing(shot.graftals.size(), 0);
    for (size_t gi = 0; gi < shot.graftals.size(); ++gi) {
        const ShotGraftals& g = shot.graftals[gi];
        const GraftalDesc& d = *g.desc;
        rep.tufts += g.sites.size();
        const std::vector<TuftState> states = tuft_states(shot, g, path);
        if (rep.at_level.size() < d.tuft.levels.size()) rep.at_level.resize(d.tuft.levels.size());
        for (const TuftState& st : states) ++rep.at_level[static_cast<size_t>(st.level)];
        // Each tuft's graftals that are in (τ > 0) and on screen, posed.
        std::vector<std::vector<Draw>> per_site(g.sites.size());
        tbb::parallel_for(size_t{0}, g.sites.size(), [&](size_t s) {
            const TuftState& st = states[s];
            // The difference image's choice, and how strongly (its weight fades the tuft).
            const float weight = placed[gi].empty() ? 1.0f : placed[gi][s];
            if (!(weight > 0.0f)) return;
            for (uint32_t k = g.first[s]; k < g.first[s + 1]; ++k) {
                const GraftalInstance& inst = g.instances[k];
                const float tau = instance_tau(inst, st);
                Projection p;
                if (!(tau > 0.0f) || !near_screen(cam, inst, p)) continue;
                float rho = 1;
                Draw dr{static_cast<uint32_t>(gi), k, {}, weight};
                dr.pose.tau = tau;
                dr.pose.lambda =
                    lambda_of(d, cam, inst.position, inst.normal, inst.length, tau, &rho);
                // τ's fade is the sprite's (below), where the coherence bench reads presence.
                dr.pose.opacity = d.alpha_from_rho ? rho : 1.0f;
                dr.pose.shade =
                    1.0f - d.light + d.light * std::max(0.0f, glm::dot(inst.normal, sun));
                per_site[s].push_back(dr);
            }
        });
        for (size_t s = 0; s < g.sites.size(); ++s) {
            culled[gi] += (g.first[s + 1] - g.first[s]) - per_site[s].size();
            for (const Draw& dr : per_site[s]) {
                if (dr.pose.tau < 1.0f) ++growing[gi];
                per_group[gi].push_back(dr);
            }
        }
    }
    std::vector<Draw> draws;
    for (size_t gi = 0; gi < per_group.size(); ++gi) {
        rep.culled += culled[gi], rep.growing += growing[gi];
        draws.insert(draws.end(), per_group[gi].begin(), per_group[gi].end());
    }
    std::vector<GraftalPatch> patches(draws.size());
    PassTimer drawing;
    tbb::parallel_for(size_t{0}, draws.size(), [&](size_t i) {
        const Draw& dr = draws[i];
        const ShotGraftals& g = shot.graftals[dr.group];
        patches[i] = draw_graftal(*g.desc, g.instances[dr.instance], cam, dr.pose, 2048,
                                  settings.graftal_raster);
    });
    rep.draw_ms = drawing.ms();
    const uint32_t first_item = static_cast<uint32_t>(shot.item_count());
    for (size_t i = 0; i < draws.size(); ++i) {
        GraftalPatch& patch = patches[i];
        if (patch.empty()) {
            ++rep.culled;
            continue;
        }
        const Draw& dr = draws[i];
        const ShotGraftals& g = shot.graftals[dr.group];
        const GraftalInstance& inst = g.instances[dr.instance];
        Sprite sp = patch_sprite(patch, view, inst.position);
        sp.item = first_item + dr.group, sp.particle = dr.instance;
        sp.object_id = inst.object;
        sp.fade = dr.pose.tau * dr.weight;
        sp.k.lightness = inst.lightness * dr.pose.shade;
        rep.pixels += add_patch_sprite(sprites, sp, std::move(patch));
        ++rep.drawn;
    }
    return rep;
}

}  // namespace pleinair

namespace pleinair {

std::vector<float> graftal_presences(const Shot& shot, const FrameView& view) {
    std::vector<float> out;
    if (shot.graftals.empty()) return out;
    const std::vector<FrameView> path = replay_path(shot.scene, view);
    const std::vector<std::vector<float>> placed = difference_placement(shot, view.camera);
    for (size_t gi = 0; gi < shot.graftals.size(); ++gi) {
        const ShotGraftals& g = shot.graftals[gi];
        const std::vector<TuftState> states = tuft_states(shot, g, path);
        for (const GraftalInstance& inst : g.instances) {
            Projection p;
            const bool on = near_screen(view.camera, inst, p) && p.x >= 0 && p.y >= 0 &&
                            p.x < view.camera.width && p.y < view.camera.height;
            const float weight = placed[gi].empty() ? 1.0f : placed[gi][inst.tuft];
            out.push_back(!on ? -1.0f : weight * instance_tau(inst, states[inst.tuft]));
        }
    }
    return out;
}

std::vector<uint64_t> graftal_keys(const Shot& shot) {
    std::vector<uint64_t> out;
    const uint32_t first_item = static_cast<uint32_t>(shot.item_count());
    for (size_t gi = 0; gi < shot.graftals.size(); ++gi)
        for (size_t k = 0; k < shot.graftals[gi].instances.size(); ++k)
            out.push_back(particle_key(first_item + static_cast<uint32_t>(gi), SpriteKind::kGraftal,
                                       static_cast<uint32_t>(k)));
    return out;
}

void graftals_stage(const FrameContext& ctx, SpriteSet& sprites) {
    StagePhase phase(ctx, "graftals");
    const RenderSettings& rs = ctx.render();
    const GraftalStageReport g =
        add_graftal_sprites(ctx.shot, ctx.view, rs, sprites, ctx.settings.lod_view);
    ctx.report.graftal_sprites = sprites.graftal;
    std::string levels;
    for (size_t l = 0; l < g.at_level.size(); ++l)
        levels += (l ? ", " : "") + std::to_string(g.at_level[l]);
    phase.done("tufts' levels from λ" +
                   (ctx.view.on_track ? ", filtered over " + std::to_string(g.replayed) +
                                            " frames of the track replayed"
                                      : std::string()) +
                   "; graftals drawn by " +
                   (rs.graftal_raster == GraftalRaster::kCairo ? "Cairo" : "scanline coverage") +
                   " into patches (" + std::to_string(int(g.draw_ms + 0.5)) + " ms of it)",
               std::to_string(g.tufts) + " tufts (per level: " + levels + "), " +
                   std::to_string(g.drawn) + " graftals drawn (" + std::to_string(g.growing) +
                   " growing or fading), " + std::to_string(g.pixels) + " patch pixels");
}

}  // namespace pleinair
