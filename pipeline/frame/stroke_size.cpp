// stroke_screen_px: true perspective scaled by (z / focus)^(1 - stroke_perspective).
#include "pipeline/frame/stroke_size.h"

#include <algorithm>

#include "shading/portable_math.h"

namespace pleinair {

// focal world / (focus^(1 - p) z^p), as focal world / focus (focus / z)^p: one power, not two
// (it is evaluated several times for every stroke a frame looks at).
float stroke_screen_px(const Camera& cam, const RenderSettings& r, double world, double z) {
    const double p = std::clamp<double>(r.stroke_perspective, 0.0, 1.0);
    const double px =
        cam.focal_px * world / cam.focus_distance * pmath::pow(cam.focus_distance / z, p);
    return static_cast<float>(px);
}

}  // namespace pleinair
