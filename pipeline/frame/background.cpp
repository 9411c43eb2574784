// paint_background and background_at: a gradient under slow noise, evaluated on a lattice and
// interpolated.
#include "pipeline/frame/background.h"

#include <tbb/parallel_for.h>

#include "pipeline/shot/shot.h"
#include "shading/curves.h"
#include "shading/noise.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

// The background's colour in direction dir (unit), and in `sky_share` how much of it is sky
// (the painted sky's strokes cover that much of it). `lin`: zenith or canvas, sky horizon,
// ground horizon, ground near, linear.
Color background_color(const Background& b, const Color lin[4], const glm::dvec3& dir,
                       float& sky_share) {
    float e = static_cast<float>(dir.y);
    Color c;
    sky_share = 0;
    if (b.canvas) {
        c = lin[0];
    } else {
        Color sky = mix(lin[1], lin[0], smoothstep(0.0f, 0.6f, e));
        Color ground = mix(lin[2], lin[3], smoothstep(0.0f, 0.5f, -e));
        sky_share = smoothstep(-b.horizon_softness, b.horizon_softness, e);
        c = mix(ground, sky, sky_share);
    }
    if (b.texture > 0) {
        // Attached to the view direction, so it does not swim when the camera moves.
        float az = static_cast<float>(pmath::atan2(dir.x, -dir.z));
        float n = fractal_noise(az * 9.0f + 50.0f, e * 9.0f + 50.0f, 3);
        c *= 1.0f + 2.0f * b.texture * (n - 0.5f);
    }
    return c;
}

void background_linear(const Background& bg, Color lin[4]) {
    lin[0] = srgb_to_linear(bg.canvas ? bg.canvas_color : bg.sky_zenith);
    lin[1] = srgb_to_linear(bg.sky_horizon);
    lin[2] = srgb_to_linear(bg.ground_horizon);
    lin[3] = srgb_to_linear(bg.ground_near);
}

}  // namespace

Color background_at(const Background& bg, const glm::dvec3& dir) {
    Color lin[4];
    background_linear(bg, lin);
    float share;
    return background_color(bg, lin, dir, share);
}

void paint_background(const SceneDesc& scene, const Camera& cam, const StrokeLayer& strokes,
                      Frame& frame, const StrokeLayer* sky) {
    const Background& bg = scene.background;
    Color lin[4];
    background_linear(bg, lin);
    // The background is smooth (a gradient under slow noise): it is evaluated on a lattice of
    // every kBgStep-th pixel and interpolated bilinearly, 1/16 of the work.
    constexpr int kBgStep = 4;
    const int gw = (cam.width + kBgStep - 1) / kBgStep + 1;
    const int gh = (cam.height + kBgStep - 1) / kBgStep + 1;
    std::vector<Color> lattice(static_cast<size_t>(gw) * gh);
    std::vector<float> share(lattice.size());
    tbb::parallel_for(0, gh, [&](int j) {
        for (int i = 0; i < gw; ++i) {
            const size_t at = static_cast<size_t>(j) * gw + i;
            lattice[at] = background_color(
                bg, lin, ray_direction(cam, kBgStep * i + 0.5, kBgStep * j + 0.5), share[at]);
        }
    });
    tbb::parallel_for(0, cam.height, [&](int y) {
        const int j = y / kBgStep;
        const float fy = static_cast<float>(y % kBgStep) / kBgStep;
        const Color* r0 = &lattice[static_cast<size_t>(j) * gw];
        const Color* r1 = r0 + gw;
        for (int x = 0; x < cam.width; ++x) {
            if (strokes.covered(static_cast<size_t>(y) * cam.width + x)) continue;
            const int i = x / kBgStep;
            const float fx = static_cast<float>(x % kBgStep) / kBgStep;
            Color c = mix(mix(r0[i], r0[i + 1], fx), mix(r1[i], r1[i + 1], fx), fy);
            if (sky) {
                // The sky's strokes over the sky only: scaled by its share of the pixel.
                const size_t pi = static_cast<size_t>(y) * cam.width + x, at = r0 - &lattice[0];
                const float w = (share[at + i] * (1 - fx) + share[at + i + 1] * fx) * (1 - fy) +
                                (share[at + gw + i] * (1 - fx) + share[at + gw + i + 1] * fx) * fy;
                const float* s = &sky->color[3 * pi];
                c = Color(s[0], s[1], s[2]) * w + c * (1.0f - w * (1.0f - sky->through[pi]));
            }
            float* px = &frame.rgba[4 * (static_cast<size_t>(y) * cam.width + x)];
            px[0] = c.x, px[1] = c.y, px[2] = c.z, px[3] = 1.0f;
        }
    });
}

void background_stage(const FrameContext& ctx, const StrokeLayer& strokes, const StrokeLayer* sky,
                      Frame& frame) {
    StagePhase phase(ctx, "background");
    const SceneDesc& scene = ctx.shot.scene;
    paint_background(scene, ctx.view.camera, strokes, frame, sky);
    phase.done(scene.background.canvas ? "canvas colour" : "sky and ground seen from the camera");
}

}  // namespace pleinair
