// frame_wind, wind_tiers and wind_move: the shot's trees posed by its wind at a frame's time.
#include "pipeline/frame/wind_stage.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <glm/geometric.hpp>
#include <string>

#include "pipeline/shot/shot.h"
#include "shading/curves.h"

namespace pleinair {

WindTiers wind_tiers(const FrameLod& lod, size_t tree) {
    WindTiers t;
    if (!lod.leaves || tree >= lod.trees.size()) return t;
    const float v = lod.trees[tree].leaf;
    t.limbs = 1.0f - smoothstep(0.55f, 1.0f, v);
    t.leaves = 1.0f - smoothstep(0.0f, 0.3f, v);
    return t;
}

namespace {

// The wind at tree i at time t, in the tree's own frame: its gusts where it stands, its
// direction turned back by the tree's rotation, its phases seeded by the tree's number.
WindAtTree wind_at_tree(const Shot& shot, size_t i, double t) {
    const WindDesc& desc = shot.scene.wind;
    const WindKey mean = wind_at(desc, t);
    const TreePlacement& pl = shot.placements[i];
    WindAtTree w;
    w.speed = gust_speed(desc, mean, pl.position);
    const glm::dvec3 d = mean.direction;
    w.direction = glm::vec3(glm::dvec3(pl.c * d.x - pl.s * d.z, 0.0, pl.s * d.x + pl.c * d.z));
    w.time = t;
    w.seed = hash_keys(desc.seed, (*shot.trees)[i].id);
    return w;
}

}  // namespace

FrameWind frame_wind(const Shot& shot, double time, const FrameLod& lod) {
    FrameWind fw;
    const std::vector<BuiltTree>& trees = *shot.trees;
    if (!shot.plan.wind || shot.wind_rigs.size() != trees.size()) return fw;
    fw.on = true;
    fw.now.resize(trees.size()), fw.before.resize(trees.size());
    fw.next.resize(trees.size()), fw.reach.resize(trees.size());
    const double frame = 1.0 / shot.scene.fps;
    tbb::parallel_for(size_t{0}, trees.size(), [&](size_t i) {
        const BuiltTree& b = trees[i];
        const WindTiers tiers = wind_tiers(lod, i);
        const WindStiffness& st = shot.scene.families[b.family].params.stiffness;
        const WindRig& rig = *shot.wind_rigs[i];
        fw.now[i] = pose_tree(b.tree(), rig, st, wind_at_tree(shot, i, time), tiers);
        fw.before[i] = pose_tree(b.tree(), rig, st, wind_at_tree(shot, i, time - frame), tiers);
        fw.next[i] = pose_tree(b.tree(), rig, st, wind_at_tree(shot, i, time + frame), tiers);
        fw.reach[i] =
            static_cast<float>(std::max({fw.now[i].reach, fw.before[i].reach, fw.next[i].reach}) *
                               shot.placements[i].scale);
    });
    return fw;
}

FrameWind wind_stage(const FrameContext& ctx, const FrameLod& lod) {
    if (!ctx.plan.wind) return {};
    StagePhase phase(ctx, "wind");
    FrameWind fw = frame_wind(ctx.shot, ctx.view.time, lod);
    size_t posed = 0, limbs = 0, fluttering = 0;
    for (size_t i = 0; i < fw.now.size(); ++i) {
        posed += !fw.now[i].at_rest();
        limbs += wind_tiers(lod, i).limbs > 0;
        fluttering += fw.now[i].flutter > 0;
    }
    phase.done(
        "the trees bend with the wind at the frame's time (far ones as a whole, nearer "
        "ones by their limbs, the nearest with their leaves' flutter); each stroke keeps "
        "the light it has at rest",
        std::to_string(posed) + " of " + std::to_string(fw.now.size()) + " trees posed, " +
            std::to_string(limbs) + " by their limbs, " + std::to_string(fluttering) +
            " fluttering");
    return fw;
}

WindMove wind_move(const Shot& shot, const FrameWind& wind, size_t item, bool leaf, size_t j,
                   const glm::vec3& local, float label) {
    WindMove m;
    if (!wind.on || item >= wind.now.size()) return m;
    const TreePose& now = wind.now[item];
    const TreePose& before = wind.before[item];
    const TreePose& next = wind.next[item];
    if (leaf) m.spin = leaf_flutter(now, label);
    if (now.at_rest() && before.at_rest() && next.at_rest()) return m;
    const WindRig& rig = *shot.wind_rigs[item];
    const std::vector<uint32_t>& joints = leaf ? rig.leaf_joint : rig.bark_joint;
    if (j >= joints.size() || joints[j] == WindRig::kNone) return m;
    const uint32_t k = joints[j];
    const TreePlacement& pl = shot.placements[item];
    const glm::dmat3 place = pl.linear();
    glm::vec3 at = local, earlier = local, later = local;
    if (!now.at_rest()) at = now.joints[k].apply(local), m.turn = now.joints[k].m;
    if (!before.at_rest()) earlier = before.joints[k].apply(local);
    if (!next.at_rest()) later = next.joints[k].apply(local);
    m.delta = place * glm::dvec3(at - local);
    m.speed = static_cast<float>(std::max(glm::length(place * glm::dvec3(later - at)),
                                          glm::length(place * glm::dvec3(at - earlier))));
    // The particle's directions turn with its joint; world = rotate_y * local, so the turn in
    // the world is rotate_y * turn * rotate_y^-1.
    const glm::mat3 y(glm::vec3(float(pl.c), 0, float(-pl.s)), glm::vec3(0, 1, 0),
                      glm::vec3(float(pl.s), 0, float(pl.c)));
    m.turn = y * m.turn * glm::transpose(y);
    m.moved = true;
    return m;
}

}  // namespace pleinair
