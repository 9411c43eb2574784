// The imposters stage (file 002): edges built once give the silhouette a frame finds, edges near
// it fade in continuously as the eye moves (measured along an orbit, not judged from one
// frame), each edge keeps its column, the vector field directs the quads, the control and its
// coverage choose faces, and the truffula frames with imposters depend on no thread count.
#include "pipeline/frame/imposter_stage.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <map>
#include <set>

#include "generators/rock.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/camera.h"
#include "pipeline/input/presets.h"
#include "pipeline/shot/shot.h"
#include "test_util.h"

namespace pleinair {
namespace {

std::shared_ptr<ImposterDesc> plain_desc() {
    auto d = std::make_shared<ImposterDesc>();
    ImposterImage img;
    img.width = img.height = 4;
    img.pixels.assign(16, glm::vec4(1, 0, 0, 1));
    d->atlas_source = img;
    d->atlas_rows = 1, d->atlas_columns = 4;
    d->min_edge_px = 0;
    d->fade = 0;
    return d;
}

Camera looking_from(const glm::dvec3& eye, int size = 512) {
    CameraParams p;
    p.position = eye;
    p.look_at = glm::dvec3(0.0);
    p.width = p.height = size;
    p.fov = 30;
    Camera cam;
    EXPECT_EQ(make_camera(p, cam), "");
    return cam;
}

TEST(ImposterEdges, BuiltOnceWithTheirFaces) {
    const auto edges = mesh_edges(test::unit_cube());
    ASSERT_EQ(edges.size(), 12u);
    for (const MeshEdge& e : edges) EXPECT_NE(e.face1, MeshEdge::kBorder);
    QuadMesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
    quad.quads = {{0, 3, 2, 1}};
    const auto open = mesh_edges(quad);
    ASSERT_EQ(open.size(), 4u);
    for (const MeshEdge& e : open) EXPECT_EQ(e.face1, MeshEdge::kBorder);
    // Two faces running 0 -> 1 the same way (not oriented): still one edge 0-1, seven in all.
    QuadMesh folded;
    folded.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {0, 1, 0}, {1, 1, 0}};
    folded.quads = {{0, 1, 2, 3}, {0, 1, 5, 4}};
    EXPECT_EQ(mesh_edges(folded).size(), 7u);
}

TEST(ImposterStage, OnTheSilhouetteOnlyWithoutFade) {
    const QuadMesh m = test::unit_cube();
    const ImposterObject o =
        make_imposter_object(plain_desc(), m, glm::dvec3(0.0), glm::dmat3(1.0), 1.0, 1, 7);
    const glm::dvec3 eye(3, 2.5, 4);
    const auto c = imposter_candidates(o, looking_from(eye), glm::vec3(0, 1, 0));
    std::set<std::pair<uint32_t, uint32_t>> got, want;
    for (const ImposterCandidate& x : c) {
        const MeshEdge& e = o.edges[x.edge];
        got.insert({std::min(e.a, e.b), std::max(e.a, e.b)});
        EXPECT_FLOAT_EQ(x.weight, 1.0f);
    }
    for (const SilhouetteEdge& e : silhouette_edges(m, eye))
        want.insert({std::min(e.a, e.b), std::max(e.a, e.b)});
    EXPECT_EQ(got.size(), 6u);
    EXPECT_EQ(got, want);
}

// The most an edge's weight changes from one camera to the next along `cameras` (an edge absent
// is at 0; the rock stays in every frame), with the eye moving `speed` a frame.
float steepest_along(const ImposterObject& o, const std::vector<Camera>& cameras, double speed) {
    std::map<uint32_t, float> before;
    float steepest = 0;
    for (size_t step = 0; step < cameras.size(); ++step) {
        std::map<uint32_t, float> now;
        for (const ImposterCandidate& c : imposter_candidates(o, cameras[step], {0, 1, 0}, speed))
            now[c.edge] = c.weight;
        if (step > 0) {
            for (const auto& [e, w] : now)
                steepest = std::max(steepest, std::abs(w - (before.count(e) ? before[e] : 0.0f)));
            for (const auto& [e, w] : before)
                if (!now.count(e)) steepest = std::max(steepest, w);
        }
        before = std::move(now);
    }
    return steepest;
}

// An orbit round a rock, a quarter of a degree a frame: how much an edge's weight can change
// from one frame to the next. Half the edges are allowed, and only on the rock's upper half, so
// an edge whose two faces the control would treat differently is tried as the silhouette passes.
float steepest_change(float fade) {
    RockParams rp;
    const QuadMesh rock = generate_rock(rp, 3, glm::dvec3(0.0));
    auto d = plain_desc();
    d->fade = fade;
    d->coverage = 0.5f;
    d->rows = {-1, 0};
    const ImposterObject o =
        make_imposter_object(d, rock, glm::dvec3(0.0), glm::dmat3(1.0), 1.0, 1, 7);
    std::vector<Camera> orbit;
    for (int step = 0; step <= 240; ++step) {
        const double a = step * 0.25 * M_PI / 180.0;
        orbit.push_back(looking_from({6 * std::sin(a), 1.5, 6 * std::cos(a)}));
    }
    return steepest_along(o, orbit, 0.0);
}

TEST(ImposterStage, EdgesNearingTheSilhouetteFadeInInsteadOfPopping) {
    EXPECT_FLOAT_EQ(steepest_change(0.0f), 1.0f);  // silhouettes alone pop
    EXPECT_LT(steepest_change(0.15f), 0.3f);
}

// A walk past a rock, close and fast (a tenth of its radius a frame): each edge turns by
// several degrees a frame, more than `fade` alone spreads; the band widened by the eye's speed
// keeps every edge fading over fade_frames frames.
float steepest_walking_past(float fade_frames) {
    RockParams rp;
    const QuadMesh rock = generate_rock(rp, 3, glm::dvec3(0.0));
    auto d = plain_desc();
    d->fade = 0.15f;
    d->fade_frames = fade_frames;
    const ImposterObject o =
        make_imposter_object(d, rock, glm::dvec3(0.0), glm::dmat3(1.0), 1.0, 1, 7);
    const double speed = 0.1;
    std::vector<Camera> walk;
    for (int step = 0; step <= 60; ++step) {
        CameraParams p;
        p.position = glm::dvec3(-3 + speed * step, 0.4, 1.8);
        p.look_at = glm::dvec3(0.0);
        p.width = p.height = 512;
        p.fov = 90;
        walk.emplace_back();
        make_camera(p, walk.back());
    }
    return steepest_along(o, walk, speed);
}

TEST(ImposterStage, NearAMovingEyeTheFadeBandWidensWithItsSpeed) {
    EXPECT_GT(steepest_walking_past(0), 0.4f);
    EXPECT_LE(steepest_walking_past(4), 0.26f);
}

TEST(ImposterStage, ColumnsStayDirectionsFollowTheFieldControlAndCoverageChoose) {
    RockParams rp;
    const QuadMesh rock = generate_rock(rp, 5, glm::dvec3(0.0));
    auto d = plain_desc();
    d->normal = 0, d->up = 1, d->height = 0.5f;
    const ImposterObject o =
        make_imposter_object(d, rock, glm::dvec3(0.0), glm::dmat3(1.0), 2.0, 1, 7);
    const auto a = imposter_candidates(o, looking_from({5, 2, 5}), {0, 1, 0});
    const auto b = imposter_candidates(o, looking_from({-5, 3, 4}), {0, 1, 0});
    ASSERT_FALSE(a.empty());
    std::map<uint32_t, int> column;
    std::set<int> columns;
    for (const ImposterCandidate& c : a) {
        column[c.edge] = c.quad.column, columns.insert(c.quad.column);
        // Straight up, the description's height times the scale.
        EXPECT_NEAR(c.quad.t0.x - c.quad.v0.x, 0, 1e-9);
        EXPECT_NEAR(c.quad.t0.y - c.quad.v0.y, 1.0, 1e-6);
    }
    EXPECT_GT(columns.size(), 1u);  // the columns vary from edge to edge
    int shared = 0;
    for (const ImposterCandidate& c : b)
        if (column.count(c.edge)) {
            ++shared;
            EXPECT_EQ(column[c.edge], c.quad.column);
        }
    EXPECT_GT(shared, 0);

    // The control's rows: nothing from edges in the lower half of the rock.
    auto upper = plain_desc();
    upper->rows = {-1, 0};
    upper->fade = 1;  // every edge that turns at all
    const ImposterObject u =
        make_imposter_object(upper, rock, glm::dvec3(0.0), glm::dmat3(1.0), 1.0, 1, 7);
    size_t allowed = 0;
    for (int8_t r : u.rows) allowed += r >= 0;
    EXPECT_GT(allowed, 0u);
    EXPECT_LT(allowed, u.rows.size());
    const Bounds box = bounds_of(rock.positions);
    for (const ImposterCandidate& c : imposter_candidates(u, looking_from({5, 2, 5}), {0, 1, 0})) {
        const MeshEdge& e = u.edges[c.edge];
        EXPECT_GE(0.5f * (rock.positions[e.a].y + rock.positions[e.b].y),
                  box.min.y + 0.5f * (box.max.y - box.min.y) - 1e-5f);
    }
    // A control image's green asks for row 1 of a one-row atlas: none there.
    auto green = plain_desc();
    green->control.width = green->control.height = 1;
    green->control.pixels = {glm::vec4(0, 1, 0, 1)};
    const ImposterObject g =
        make_imposter_object(green, rock, glm::dvec3(0.0), glm::dmat3(1.0), 1.0, 1, 7);
    for (int8_t r : g.rows) EXPECT_EQ(r, -1);
    // Coverage thins the edges by a hash: about the share asked, the same every time.
    auto half = plain_desc();
    half->coverage = 0.5f;
    const ImposterObject h1 =
        make_imposter_object(half, rock, glm::dvec3(0.0), glm::dmat3(1.0), 1.0, 1, 7);
    const ImposterObject h2 =
        make_imposter_object(half, rock, glm::dvec3(0.0), glm::dmat3(1.0), 1.0, 1, 7);
    size_t kept = 0;
    for (int8_t r : h1.rows) kept += r >= 0;
    EXPECT_NEAR(double(kept) / h1.rows.size(), 0.5, 0.1);
    EXPECT_EQ(h1.rows, h2.rows);
}

SceneDesc truffula(std::vector<std::string> more = {}) {
    std::vector<std::string> sets = {"/camera/width=256", "/camera/height=144"};
    sets.insert(sets.end(), more.begin(), more.end());
    return load_scene(resolve_preset("scenes", "truffula", "SCENE"), sets);
}

TEST(ImposterStage, TruffulaFramesWithImpostersDependOnNoThreadCount) {
    const Shot shot = build_shot(truffula());
    ASSERT_FALSE(shot.imposters.empty());
    const FrameView view = still_view(shot.scene);
    FrameReport rep;
    Frame one, two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = paint_frame(shot, view, scene_frame_settings(shot.scene), &rep);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = paint_frame(shot, view, scene_frame_settings(shot.scene));
    }
    EXPECT_GT(rep.imposter_sprites, 50u);
    EXPECT_EQ(one.rgba, two.rgba);
    for (float v : one.rgba) ASSERT_TRUE(std::isfinite(v));
    SpriteSet sprites;
    const ImposterStageReport r = add_imposter_sprites(shot, view, sprites);
    EXPECT_EQ(r.drawn, rep.imposter_sprites);
    EXPECT_GT(r.hidden, 0u);  // the hill hides the far trunks' lower silhouettes

    // Named by no family or material: no imposters, and the plan says so.
    const Shot none = build_shot(
        truffula({"/families/truffula/imposters=\"\"", "/materials/turf/imposters=\"\""}));
    EXPECT_TRUE(none.imposters.empty());
    FrameReport nrep;
    const Frame f = paint_frame(none, view, scene_frame_settings(none.scene), &nrep);
    EXPECT_EQ(nrep.imposter_sprites, 0u);
    EXPECT_NE(f.rgba, one.rgba);
}

}  // namespace
}  // namespace pleinair
