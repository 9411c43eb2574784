// Graftal imposters drawn (file 002): the keyed blend's three cases, an atlas drawn from graftal
// descriptions (cells standing on their base, empty at their borders, levels keeping their
// coverage), and a quad inverted into its cell: its area, its orientation, its colour across it.
#include <gtest/gtest.h>

#include <cmath>

#include "pipeline/frame/imposter_draw.h"
#include "pipeline/input/camera.h"
#include "pipeline/input/graftal_io.h"
#include "pipeline/input/imposter_desc.h"

namespace pleinair {
namespace {

ImposterImage solid(int w, int h, const glm::vec4& v) {
    ImposterImage img;
    img.width = w, img.height = h;
    img.pixels.assign(static_cast<size_t>(w) * h, v);
    return img;
}

// A camera on +z looking at the origin, `px` pixels a world unit at depth 10.
Camera front_camera(int size = 64, double px = 6.4) {
    Camera cam;
    cam.eye = glm::dvec3(0, 0, 10);
    cam.width = cam.height = size;
    cam.focal_px = px * 10;
    cam.focus_distance = 10;
    return cam;
}

float alpha(uint32_t px) { return float(px >> 24) / 255.0f; }

TEST(ImposterBlend, KeyedAsThePaperSays) {
    const glm::vec3 surface(0.2f, 0.5f, 0.1f);
    // Inside (key red 1): the surface's colour.
    glm::vec4 in = keyed_blend({1, 0, 0, 1}, surface);
    EXPECT_NEAR(in.x, 0.2f, 1e-6f);
    EXPECT_NEAR(in.y, 0.5f, 1e-6f);
    EXPECT_NEAR(in.w, 1, 1e-6f);
    // The outline (red 0): its own green and blue.
    glm::vec4 out = keyed_blend({0, 0.1f, 0.3f, 1}, surface);
    EXPECT_NEAR(out.x, 0, 1e-6f);
    EXPECT_NEAR(out.y, 0.1f, 1e-6f);
    EXPECT_NEAR(out.z, 0.3f, 1e-6f);
    // Half covered, premultiplied: alpha kept, the key read unpremultiplied.
    glm::vec4 half = keyed_blend({0.5f, 0, 0, 0.5f}, surface);
    EXPECT_NEAR(half.w, 0.5f, 1e-6f);
    EXPECT_NEAR(half.y, 0.25f, 1e-6f);
    // Outside: nothing.
    EXPECT_EQ(keyed_blend({0, 0, 0, 0}, surface), glm::vec4(0.0f));
}

TEST(ImposterAtlas, DrawnFromGraftalsEachCellStandsOnItsBase) {
    const std::vector<GraftalDesc> d = {load_graftal("fringe-blades"), load_graftal("grass-tuft")};
    const ImposterAtlas a = atlas_from_graftals(d, 5, 32);
    ASSERT_EQ(a.rows, 2);
    ASSERT_EQ(a.columns, 5);
    ASSERT_EQ(a.levels.size(), 6u);  // 32, 16, 8, 4, 2, 1
    const ImposterImage& img = a.levels[0];
    ASSERT_EQ(img.width, 160);
    ASSERT_EQ(img.height, 64);
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 5; ++c) {
            SCOPED_TRACE(testing::Message() << "cell " << r << ", " << c);
            auto at = [&](int x, int y) {
                return img.pixels[size_t(r * 32 + y) * 160 + c * 32 + x];
            };
            double sum = 0, bottom = 0, top = 0, outline = 0;
            for (int y = 0; y < 32; ++y)
                for (int x = 0; x < 32; ++x) {
                    const glm::vec4 p = at(x, y);
                    sum += p.w;
                    if (y >= 30) bottom += p.w;
                    if (y == 0) top += p.w;
                    if (p.w > 0.9f && p.x / p.w < 0.1f) ++outline;
                    ASSERT_GE(p.w, 0.0f);
                    ASSERT_LE(p.w, 1.0f);
                    ASSERT_LE(p.x, p.w + 1e-5f);  // premultiplied
                }
            EXPECT_GT(sum, 10.0);    // something drawn
            EXPECT_GT(bottom, 0.2);  // it stands on the cell's bottom row: its base
            EXPECT_LT(top, 0.05);    // and fits under its top
            // fringe-blades is outlined: pixels of outline (red 0, opaque); grass-tuft is not.
            if (r == 0) {
                EXPECT_GT(outline, 0.0);
            } else {
                EXPECT_EQ(outline, 0.0);
            }
        }
    // Each level the mean of the one above it, cell by cell: a cell's coverage is kept.
    for (size_t l = 1; l < a.levels.size(); ++l) {
        double s0 = 0, s1 = 0;
        for (const glm::vec4& p : a.levels[0].pixels) s0 += p.w;
        for (const glm::vec4& p : a.levels[l].pixels) s1 += p.w;
        EXPECT_NEAR(s1 / a.levels[l].pixels.size(), s0 / a.levels[0].pixels.size(), 0.01) << l;
    }
}

TEST(ImposterAtlas, FromAnImageCutIntoCellsWithStraightAlphaPremultiplied) {
    ImposterImage img = solid(8, 4, glm::vec4(1, 0, 0, 0.5f));
    const ImposterAtlas a = atlas_from_image(img, 2, 4);
    EXPECT_EQ(a.cell_w, 2);
    EXPECT_EQ(a.cell_h, 2);
    EXPECT_EQ(a.levels.size(), 2u);
    EXPECT_FLOAT_EQ(a.levels[0].pixels[0].x, 0.5f);
    EXPECT_FLOAT_EQ(a.levels[0].pixels[0].w, 0.5f);
}

// A full-red, opaque cell: every pixel of the quad shows the surface.
ImposterAtlas opaque_atlas() {
    return atlas_from_image(solid(16, 16, glm::vec4(1, 0, 0, 1)), 1, 1);
}

TEST(ImposterDraw, AQuadFacingTheCameraCoversItsArea) {
    const Camera cam = front_camera();
    ImposterQuad q;
    q.v0 = {-2, -1.5, 0}, q.v1 = {2, -1.5, 0}, q.t0 = {-2, 1.5, 0}, q.t1 = {2, 1.5, 0};
    q.color0 = q.color1 = glm::vec3(0.2f, 0.4f, 0.1f);
    const GraftalPatch p = draw_imposter(opaque_atlas(), q, cam);
    ASSERT_FALSE(p.empty());
    double area = 0;
    for (uint32_t px : p.pixels) area += alpha(px);
    const double want = (4 * 6.4) * (3 * 6.4);  // 25.6 x 19.2 pixels
    EXPECT_NEAR(area, want, 0.02 * want);
    // Its colour, in sRGB, unpremultiplied.
    const uint32_t mid = p.pixels[size_t(p.height / 2) * p.width + p.width / 2];
    EXPECT_EQ(mid >> 24, 255u);
    EXPECT_NEAR(float((mid >> 8) & 0xff) / 255.0f, 0.665f, 0.01f);  // sRGB of 0.4
    // The same bytes again; nothing through the near plane.
    EXPECT_EQ(draw_imposter(opaque_atlas(), q, cam).pixels, p.pixels);
    ImposterQuad behind = q;
    behind.t1.z = behind.t0.z = 20;
    EXPECT_TRUE(draw_imposter(opaque_atlas(), behind, cam).empty());
}

double shoelace(const Camera& cam, const ImposterQuad& q) {
    const glm::dvec3 w[4] = {q.v0, q.v1, q.t1, q.t0};
    double a = 0;
    for (int i = 0; i < 4; ++i) {
        const Projection p = project(cam, w[i]), n = project(cam, w[(i + 1) % 4]);
        a += double(p.x) * n.y - double(n.x) * p.y;
    }
    return std::abs(0.5 * a);
}

TEST(ImposterDraw, AQuadRecedingInDepthCoversItsTrapezoid) {
    // Tips far behind the base: a trapezoid on screen, inverted bilinearly.
    const Camera cam = front_camera(128, 6.4);
    ImposterQuad q;
    q.v0 = {-3, -2, 2}, q.v1 = {3, -2, 2}, q.t0 = {-3, 2, -6}, q.t1 = {3, 2, -6};
    const GraftalPatch p = draw_imposter(opaque_atlas(), q, cam);
    ASSERT_FALSE(p.empty());
    double area = 0;
    for (uint32_t px : p.pixels) area += alpha(px);
    EXPECT_NEAR(area, shoelace(cam, q), 0.02 * shoelace(cam, q));
}

TEST(ImposterDraw, TurningEdgeOnItsInkFollowsItsAreaSmoothly) {
    // A quad turned about its base through edge-on, a tenth of a degree at a time: thinner than
    // a pixel it is widened and made fainter, so its ink is its area and never jumps.
    const Camera cam = front_camera(64, 6.4);
    double before = -1, steepest = 0;
    for (int step = -100; step <= 100; ++step) {
        const double a = (90.0 + step * 0.1) * M_PI / 180.0;  // 90: edge-on
        ImposterQuad q;
        q.v0 = {-2, 0, 0}, q.v1 = {2, 0, 0};
        q.t0 = q.v0 + 2.0 * glm::dvec3(0, std::cos(a), std::sin(a));
        q.t1 = q.v1 + 2.0 * glm::dvec3(0, std::cos(a), std::sin(a));
        const GraftalPatch p = draw_imposter(opaque_atlas(), q, cam);
        double ink = 0;
        for (uint32_t px : p.pixels) ink += alpha(px);
        const double area = shoelace(cam, q);
        EXPECT_NEAR(ink, area, 0.15 * area + 2.0) << step;
        if (before >= 0) steepest = std::max(steepest, std::abs(ink - before));
        before = ink;
    }
    EXPECT_LT(steepest, 3.0);  // pixels of ink a step, on a quad 25 pixels long
}

TEST(ImposterDraw, TheCellRunsFromBaseToTipAndItsColourFromEndToEnd) {
    // The cell's top half (the tip's) opaque, its bottom half empty.
    ImposterImage img = solid(8, 8, glm::vec4(0.0f));
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) img.pixels[size_t(y) * 8 + x] = glm::vec4(1, 0, 0, 1);
    const ImposterAtlas a = atlas_from_image(img, 1, 1);
    const Camera cam = front_camera();
    ImposterQuad q;  // base at the bottom of the screen, tip at the top
    q.v0 = {-3, -3, 0}, q.v1 = {3, -3, 0}, q.t0 = {-3, 3, 0}, q.t1 = {3, 3, 0};
    q.color0 = glm::vec3(1, 0, 0), q.color1 = glm::vec3(0, 0, 1);
    const GraftalPatch p = draw_imposter(a, q, cam);
    ASSERT_FALSE(p.empty());
    double upper = 0, lower = 0;
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x)
            (y < p.height / 2 ? upper : lower) += alpha(p.pixels[size_t(y) * p.width + x]);
    EXPECT_GT(upper, 10 * (lower + 1));
    // v0's colour at v0's end (left), v1's at the other.
    const uint32_t left = p.pixels[size_t(p.height / 4) * p.width + 1];
    const uint32_t right = p.pixels[size_t(p.height / 4) * p.width + p.width - 2];
    EXPECT_GT((left >> 16) & 0xff, 200u);
    EXPECT_LT(left & 0xff, 60u);
    EXPECT_GT(right & 0xff, 200u);
    EXPECT_LT((right >> 16) & 0xff, 60u);
    // Turned over (tip below the base), the opaque half follows the tip.
    ImposterQuad flipped = q;
    std::swap(flipped.v0, flipped.t0), std::swap(flipped.v1, flipped.t1);
    const GraftalPatch f = draw_imposter(a, flipped, cam);
    upper = lower = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x)
            (y < f.height / 2 ? upper : lower) += alpha(f.pixels[size_t(y) * f.width + x]);
    EXPECT_GT(lower, 10 * (upper + 1));
}

TEST(ImposterDraw, SmallOnScreenItReadsASmallerLevel) {
    // A checkerboard of opaque and empty texels averages to half cover at the coarser levels: a
    // quad a few pixels across shows that, not the aliased texels of level 0.
    ImposterImage img = solid(64, 64, glm::vec4(0.0f));
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            if ((x + y) % 2 == 0) img.pixels[size_t(y) * 64 + x] = glm::vec4(1, 0, 0, 1);
    const ImposterAtlas a = atlas_from_image(img, 1, 1);
    const Camera cam = front_camera(64, 6.4);
    ImposterQuad q;
    q.v0 = {-0.5, -0.5, 0}, q.v1 = {0.5, -0.5, 0}, q.t0 = {-0.5, 0.5, 0}, q.t1 = {0.5, 0.5, 0};
    const GraftalPatch p = draw_imposter(a, q, cam);
    ASSERT_FALSE(p.empty());
    for (int y = 1; y + 1 < p.height; ++y)
        for (int x = 1; x + 1 < p.width; ++x)
            EXPECT_NEAR(alpha(p.pixels[size_t(y) * p.width + x]), 0.5f, 0.08f) << x << ", " << y;
}

TEST(ImposterTextures, UvAndControl) {
    const glm::vec3 lo(-1, 0, -1), hi(1, 4, 1);
    // Cylinder: v up the height, u round the axis.
    EXPECT_NEAR(imposter_uv(ImposterUv::kCylinder, {1, 1, 0}, lo, hi).y, 0.25f, 1e-6f);
    EXPECT_NEAR(imposter_uv(ImposterUv::kCylinder, {1, 1, 0}, lo, hi).x, 0.5f, 1e-6f);
    EXPECT_NEAR(imposter_uv(ImposterUv::kCylinder, {-1, 1, 1e-7f}, lo, hi).x, 1.0f, 1e-5f);
    // Plan: x and z across the box.
    const glm::vec2 p = imposter_uv(ImposterUv::kPlan, {0.5f, 3, -0.5f}, lo, hi);
    EXPECT_NEAR(p.x, 0.75f, 1e-6f);
    EXPECT_NEAR(p.y, 0.25f, 1e-6f);
    // Rows up v, a column of texels.
    ImposterDesc d;
    d.rows = {-1, 0, 1};
    EXPECT_EQ(control_row(d, {0.3f, 0.1f}), -1);
    EXPECT_EQ(control_row(d, {0.3f, 0.5f}), 0);
    EXPECT_EQ(control_row(d, {0.3f, 0.99f}), 1);
    EXPECT_EQ(control_row(d, {0.3f, 1.0f}), 1);
    // An image in the paper's encoding: alpha allows, red, green, blue pick rows 0, 1, 2. Its
    // first row is the top of the object (v = 1).
    d.control = solid(2, 2, glm::vec4(0.0f));
    d.control.pixels[0] = {0, 1, 0, 1}, d.control.pixels[1] = {0, 1, 0, 1};  // top: green
    d.control.pixels[2] = {0, 0, 1, 0}, d.control.pixels[3] = {0, 0, 1, 0};  // bottom: none
    EXPECT_EQ(control_row(d, {0.5f, 0.9f}), 1);
    EXPECT_EQ(control_row(d, {0.5f, 0.1f}), -1);
}

}  // namespace
}  // namespace pleinair
