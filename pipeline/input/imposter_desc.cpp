// Graftal imposters' textures as described: bilinear samples, texture coordinates over an
// object's box, the control texture's rows.
#include "pipeline/input/imposter_desc.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "shading/color.h"
#include "shading/portable_math.h"

namespace pleinair {

glm::vec4 ImposterImage::sample(float u, float v, bool wrap_u) const {
    if (empty()) return glm::vec4(0.0f);
    if (!std::isfinite(u)) u = 0;
    if (!std::isfinite(v)) v = 0;
    if (wrap_u) {
        u -= std::floor(u);
    } else {
        // Clamped: the texel centres at either side hold to the edge.
        u = std::clamp(u, 0.5f / width, 1.0f - 0.5f / width);
    }
    const float fx = u * width - 0.5f;
    const float fy = std::clamp(v * height - 0.5f, 0.0f, float(height - 1));
    const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(fy);
    const float ax = fx - std::floor(fx), ay = fy - y0;
    const int xa = (x0 % width + width) % width, xb = (xa + 1) % width;
    const int y1 = std::min(y0 + 1, height - 1);
    const glm::vec4 top = texel(xa, y0) * (1 - ax) + texel(xb, y0) * ax;
    const glm::vec4 bot = texel(xa, y1) * (1 - ax) + texel(xb, y1) * ax;
    return top * (1 - ay) + bot * ay;
}

glm::vec2 imposter_uv(ImposterUv uv, const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
    const glm::vec3 size = glm::max(hi - lo, glm::vec3(1e-6f));
    if (uv == ImposterUv::kPlan) return {(p.x - lo.x) / size.x, (p.z - lo.z) / size.z};
    const glm::vec3 c = 0.5f * (lo + hi);
    const float angle = static_cast<float>(pmath::atan2(double(p.z - c.z), double(p.x - c.x)));
    // v up the height: 0 at the bottom (the texture's last row), 1 at the top (its first).
    return {angle * (0.5f / 3.14159265f) + 0.5f, std::clamp((p.y - lo.y) / size.y, 0.0f, 1.0f)};
}

int control_row(const ImposterDesc& d, const glm::vec2& uv) {
    if (!d.control.empty()) {
        const glm::vec4 c = d.control.sample(uv.x, 1.0f - uv.y, d.uv == ImposterUv::kCylinder);
        if (c.w < 0.5f) return -1;
        return c.x >= c.y && c.x >= c.z ? 0 : c.y >= c.z ? 1 : 2;
    }
    if (d.rows.empty()) return 0;
    const size_t i = std::min(d.rows.size() - 1,
                              static_cast<size_t>(std::clamp(uv.y, 0.0f, 1.0f) * d.rows.size()));
    return d.rows[i];
}

}  // namespace pleinair
