// A crown up close (issue 13 §4): lights gather on the sunlit side, strokes shrink and break
// towards the edge, and the outer crown opens in holes; with every crown key at 0 the thesis's
// crown is painted as before.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "pipeline/frame/lod.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/shot/shot.h"
#include "shading/stroke_shader.h"

namespace pleinair {
namespace {

TEST(Crown, ShadingFunctionsKeepTheThesisAtZero) {
    StrokeShaderParams p;
    for (float l : {0.0f, 0.3f, 0.9f})
        for (float side : {0.0f, 0.5f, 1.0f}) EXPECT_EQ(crown_side_lightness(p, l, side), l);
    EXPECT_EQ(crown_edge_size(p, 1.0f), 1.0f);
    EXPECT_EQ(crown_edge_fade(p, 1.0f), 1.0f);
    EXPECT_FALSE(crown_hole(p, 1, 2, 3, 1.0f));
    p.sun_side = 0.6f, p.edge_shrink = 0.5f, p.edge_break = 0.5f, p.holes = 0.5f;
    EXPECT_GT(crown_side_lightness(p, 0.5f, 1.0f), crown_side_lightness(p, 0.5f, 0.5f));
    EXPECT_GT(crown_side_lightness(p, 0.5f, 0.5f), crown_side_lightness(p, 0.5f, 0.0f));
    EXPECT_LE(crown_side_lightness(p, 1.0f, 1.0f), 1.0f);
    EXPECT_GE(crown_side_lightness(p, 0.1f, 0.0f), 0.0f);
    EXPECT_EQ(crown_edge_size(p, 0.0f), 1.0f);
    EXPECT_NEAR(crown_edge_size(p, 1.0f), 0.5f, 1e-6f);
    EXPECT_EQ(crown_edge_fade(p, 0.4f), 1.0f);
    EXPECT_NEAR(crown_edge_fade(p, 1.0f), 0.5f, 1e-6f);
    // No hole within half the centre distance; about `holes` of the leaves at the edge.
    int inner = 0, edge = 0, n = 0;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j, ++n) {
            inner += crown_hole(p, 0.7f * i, 0.3f * j, 0.5f * (i + j), 0.45f);
            edge += crown_hole(p, 0.7f * i, 0.3f * j, 0.5f * (i + j), 1.0f);
        }
    EXPECT_EQ(inner, 0);
    EXPECT_NEAR(double(edge) / n, 0.5, 0.2);
}

// The leaf sprites of a lone oak lit from the left: their lightness against the side of the
// crown they are on (Pearson), how many the holes leave out, and the outer strokes' size
// against the inner ones'.
struct CrownStats {
    double side_correlation = 0, outer_over_inner_size = 0;
    size_t leaves = 0;
};

CrownStats crown_stats(bool corot) {
    const std::string text = R"({
        "camera": {"position": [0, 7, 30], "look_at": [0, 7, 0], "fov": 40,
                   "width": 320, "height": 240},
        "sun": {"direction": [-1, 0.4, 0.3]},
        "families": {"oak": {"preset": "oak"}},
        "trees": [{"family": "oak", "seed": 3, "position": [0, 0, 0]}]})";
    SceneDesc scene = parse_scene(text, "test");
    if (!corot) {
        StrokeShaderParams& p = scene.families[0].leaf_shader;
        p.sun_side = p.edge_shrink = p.edge_break = p.holes = 0;
    }
    const Shot shot = build_shot(std::move(scene));
    const FrameView view = still_view(shot.scene);
    const FrameSettings fs = scene_frame_settings(shot.scene);
    const FramePlan plan = plan_frame(shot, fs);
    const FrameLod lod = level_of_detail(shot, view, fs.render);
    const SpriteSet set = make_sprites({shot, view, plan, fs.render, lod, nullptr});
    const BuiltTree& b = (*shot.trees)[0];
    const glm::vec3 sun = glm::normalize(glm::vec3(-1, 0.4f, 0.3f));
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, inner = 0, outer = 0;
    size_t n = 0, ni = 0, no = 0;
    for (const Sprite& sp : set.sprites) {
        if (sp.kind != SpriteKind::kLeaf) continue;
        const glm::vec3 local = b.tree().leaves.position[sp.particle] - b.tree().center;
        const double side = glm::dot(placement(b).turn(glm::normalize(local)), sun);
        const double l = sp.k.lightness;
        sx += side, sy += l, sxx += side * side, syy += l * l, sxy += side * l, ++n;
        const float cd = b.tree().leaves.center_distance[sp.particle];
        if (cd < 0.4f) inner += sp.half_w, ++ni;
        if (cd > 0.85f) outer += sp.half_w, ++no;
    }
    CrownStats s;
    s.leaves = n;
    const double N = double(n);
    s.side_correlation = (sxy / N - sx / N * sy / N) /
                         std::sqrt((sxx / N - sx / N * sx / N) * (syy / N - sy / N * sy / N));
    s.outer_over_inner_size = (outer / double(no)) / (inner / double(ni));
    return s;
}

TEST(Crown, LightsGatherOnTheSunlitSideAndTheEdgeOpens) {
    const CrownStats thesis = crown_stats(false), corot = crown_stats(true);
    EXPECT_GT(corot.side_correlation, thesis.side_correlation + 0.12)
        << corot.side_correlation << " vs " << thesis.side_correlation;
    EXPECT_LT(corot.outer_over_inner_size, 0.8 * thesis.outer_over_inner_size);
    EXPECT_LT(corot.leaves, thesis.leaves);                        // holes
    EXPECT_GT(double(corot.leaves), 0.7 * double(thesis.leaves));  // but a crown still
}

}  // namespace
}  // namespace pleinair
