// Graftals drawn by Cairo into patches: the area and colour of a known shape, growth and
// opacity, the near plane, the size bound, and the same bytes on every thread.
#include "pipeline/shot/graftal_draw.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "pipeline/input/graftal_io.h"

namespace pleinair {
namespace {

// A unit square standing on its base (x across, y along the normal), red, opaque.
GraftalDesc square_desc() {
    GraftalDesc d;
    d.frame = GraftalFrame::kView;
    d.tuft.grow_from = 0.2f;
    GraftalExample ex;
    ex.vertices = {{-0.5f, 0, 0}, {0.5f, 0, 0}, {0.5f, 1, 0}, {-0.5f, 1, 0}};
    GraftalPrimitive p;
    p.type = PrimitiveType::kPolygon;
    p.vertices = {0, 1, 2, 3};
    p.color = {1, 0, 0};
    ex.primitives.push_back(p);
    d.examples.push_back(ex);
    return d;
}

// Looking down -z at the square's plane from 10 units: 100 pixels per unit at depth 10.
Camera front_camera() {
    CameraParams cp;
    cp.position = {0, 0.5, 10};
    cp.look_at = {0, 0.5, 0};
    cp.width = 200, cp.height = 200;
    cp.fov = 2.0 * std::atan(1.0) * 180.0 / 3.14159265358979323846;  // 90 degrees
    Camera c;
    EXPECT_EQ(make_camera(cp, c), "");
    return c;
}

GraftalInstance upright(double length = 0.5) {
    GraftalInstance g;
    g.position = {0, 0.25, 0};
    g.normal = {0, 1, 0};
    g.length = static_cast<float>(length);
    return g;
}

double coverage(const GraftalPatch& p) {
    double sum = 0;
    for (uint32_t px : p.pixels) sum += (px >> 24) / 255.0;
    return sum;
}

TEST(GraftalDraw, ASquareCoversItsAreaInItsColour) {
    const Camera cam = front_camera();
    GraftalInstance g = upright(2.0);
    g.position = {0, -0.5, 0};  // the square from y = -0.5 to 1.5, centred on the view
    const GraftalPatch p = draw_graftal(square_desc(), g, cam, {});
    ASSERT_FALSE(p.empty());
    // A 90 degree field over 200 pixels: 100 pixels per unit at depth 1, so 2 units at depth 10
    // span 20 pixels.
    ASSERT_NEAR(cam.focal_px, 100.0, 1e-9);
    const double side = 2.0 * cam.focal_px / 10.0;
    EXPECT_NEAR(coverage(p), side * side, 0.02 * side * side);
    // Its centre pixel is the file's red exactly, opaque.
    const int cx = static_cast<int>(std::floor(cam.width / 2.0)) - p.x0;
    const int cy = static_cast<int>(std::floor(cam.height / 2.0)) - p.y0;
    ASSERT_TRUE(cx >= 0 && cy >= 0 && cx < p.width && cy < p.height);
    EXPECT_EQ(p.pixels[static_cast<size_t>(cy) * p.width + cx], 0xffff0000u);
}

TEST(GraftalDraw, GrowthScalesFromGrowFromAndOpacityMultiplies) {
    const Camera cam = front_camera();
    const GraftalDesc d = square_desc();
    const GraftalInstance g = upright(2.0);
    const double full = coverage(draw_graftal(d, g, cam, {}));
    GraftalPose half;
    half.tau = 0.5f;  // scale 0.2 + 0.8 x 0.5 = 0.6 of its length: 0.36 of its area
    EXPECT_NEAR(coverage(draw_graftal(d, g, cam, half)) / full, 0.36, 0.01);
    GraftalPose faint;
    faint.opacity = 0.5f;
    EXPECT_NEAR(coverage(draw_graftal(d, g, cam, faint)) / full, 0.5, 0.01);
    GraftalPose gone;
    gone.tau = 0;
    EXPECT_TRUE(draw_graftal(d, g, cam, gone).empty());
}

TEST(GraftalDraw, NothingBehindTheEyeOrThroughTheNearPlane) {
    const Camera cam = front_camera();
    GraftalInstance behind = upright();
    behind.position = {0, 0.25, 12};
    EXPECT_TRUE(draw_graftal(square_desc(), behind, cam, {}).empty());
    // Lying along the view axis from in front of the eye to behind it.
    GraftalInstance through = upright(4.0);
    through.position = {0, 0.5, 8};
    through.normal = {0, 0, 1};
    EXPECT_TRUE(draw_graftal(square_desc(), through, cam, {}).empty());
    // Off the frame entirely.
    GraftalInstance aside = upright();
    aside.position = {40, 0.25, 0};
    EXPECT_TRUE(draw_graftal(square_desc(), aside, cam, {}).empty());
}

TEST(GraftalDraw, AGraftalAtTheEyeIsBoundedAndFinite) {
    const Camera cam = front_camera();
    GraftalInstance near = upright(50.0);
    near.position = {0, -20, 9.9};
    const GraftalPatch p = draw_graftal(square_desc(), near, cam, {}, 64);
    ASSERT_FALSE(p.empty());
    EXPECT_LE(p.width, 64);
    EXPECT_LE(p.height, 64);
    EXPECT_GE(p.x0, 0);
    EXPECT_GE(p.y0, 0);
}

TEST(GraftalDraw, ShippedTuftsDrawTheSameBytesOnEveryThread) {
    const Camera cam = front_camera();
    for (const char* name : {"seuss-leaf-tuft", "grass-tuft", "corot-leaf", "truffula-tuft"})
        for (GraftalRaster raster : {GraftalRaster::kScanline, GraftalRaster::kCairo}) {
            const GraftalDesc d = load_graftal(name);
            std::vector<GraftalInstance> gs;
            for (int i = 0; i < 64; ++i) {
                GraftalInstance g = upright(0.8);
                g.position = {0.1 * (i % 8) - 0.4, 0.1 * (i / 8) - 0.2, -0.05 * i};
                g.angle = 7.0f * i;
                g.example = static_cast<uint16_t>(i % d.examples.size());
                gs.push_back(g);
            }
            std::vector<GraftalPatch> serial, parallel(gs.size());
            for (const auto& g : gs)
                serial.push_back(draw_graftal(d, g, cam, {2.0f, 1, 1, 1}, 2048, raster));
            tbb::parallel_for(size_t{0}, gs.size(), [&](size_t i) {
                parallel[i] = draw_graftal(d, gs[i], cam, {2.0f, 1, 1, 1}, 2048, raster);
            });
            double drawn = 0;
            for (size_t i = 0; i < gs.size(); ++i) {
                EXPECT_EQ(serial[i].pixels, parallel[i].pixels) << name << " " << i;
                EXPECT_EQ(serial[i].x0, parallel[i].x0);
                drawn += coverage(serial[i]);
            }
            EXPECT_GT(drawn, 64.0) << name;  // they do draw something
        }
}

TEST(GraftalDraw, AStrokeTapersAlongItsPath) {
    GraftalDesc d = square_desc();
    GraftalPrimitive s;
    s.type = PrimitiveType::kStroke;
    s.vertices = {1, 2};   // up the square's right edge
    s.widths = {0.4f, 0};  // wide at the base, a point at the top
    d.examples[0].primitives = {s};
    const Camera cam = front_camera();
    const GraftalPatch p = draw_graftal(d, upright(2.0), cam, {});
    ASSERT_FALSE(p.empty());
    auto row_cover = [&](int y) {
        double sum = 0;
        for (int x = 0; x < p.width; ++x) sum += (p.pixels[size_t(y) * p.width + x] >> 24) / 255.0;
        return sum;
    };
    // A triangle 0.4 x 2 units, 8 x 20 pixels: rows a quarter of the way from its base are
    // three times as wide as rows a quarter of the way from its tip.
    int top = -1, bottom = -1;
    for (int y = 0; y < p.height; ++y)
        if (row_cover(y) > 0.01) bottom = y, top = top < 0 ? y : top;
    ASSERT_GT(bottom - top, 12);
    const int h = bottom - top + 1;
    const double base = row_cover(bottom - h / 4), tip = row_cover(top + h / 4);
    EXPECT_NEAR(base / tip, 3.0, 0.5);
    EXPECT_NEAR(coverage(p), 0.5 * 8 * 20, 0.05 * 80);
}

}  // namespace
}  // namespace pleinair

namespace pleinair {
namespace {

// pleinair's scanline coverage against Cairo, shape by shape: the same area and nearly the same
// pixels (both are exact-area antialiasing; they differ in 8-bit rounding and in how overlapping
// outline pieces join).
TEST(GraftalDraw, TheScanlineRasteriserAgreesWithCairo) {
    const Camera cam = front_camera();
    GraftalInstance g = upright(2.0);
    g.position = {0.13, -0.47, 0};  // off the pixel grid
    const GraftalPatch a = draw_graftal(square_desc(), g, cam, {}, 2048, GraftalRaster::kCairo);
    const GraftalPatch b = draw_graftal(square_desc(), g, cam, {}, 2048, GraftalRaster::kScanline);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_NEAR(coverage(b), coverage(a), 0.5);  // of 400 pixels
    for (const char* name : {"seuss-leaf-tuft", "grass-tuft", "corot-leaf", "truffula-tuft"}) {
        const GraftalDesc d = load_graftal(name);
        for (uint16_t e = 0; e < d.examples.size(); ++e) {
            GraftalInstance t = upright(1.6);
            t.example = e, t.angle = 17.0f * e;
            const GraftalPatch pa =
                draw_graftal(d, t, cam, {3.0f, 1, 1, 1}, 2048, GraftalRaster::kCairo);
            const GraftalPatch pb =
                draw_graftal(d, t, cam, {3.0f, 1, 1, 1}, 2048, GraftalRaster::kScanline);
            ASSERT_EQ(pa.pixels.size(), pb.pixels.size()) << name << " " << e;
            const double ca = coverage(pa), cb = coverage(pb);
            EXPECT_NEAR(cb / ca, 1.0, 0.03) << name << " " << e;
            // Mean difference of each channel, in 8-bit levels.
            double diff = 0;
            for (size_t i = 0; i < pa.pixels.size(); ++i)
                for (int sh = 0; sh < 32; sh += 8)
                    diff += std::abs(int((pa.pixels[i] >> sh) & 0xff) -
                                     int((pb.pixels[i] >> sh) & 0xff));
            EXPECT_LT(diff / (4.0 * pa.pixels.size()), 3.0) << name << " " << e;
        }
    }
}

}  // namespace
}  // namespace pleinair
