// distance_mass_amount, luminance_of_lstar and lay_in_distance_value.
#include "pipeline/frame/distance_mass.h"

#include <algorithm>

#include "pipeline/input/scene.h"
#include "shading/curves.h"
#include "shading/stroke_shader.h"

namespace pleinair {

float distance_mass_amount(const Atmosphere& a, float depth) {
    if (!(a.value_pull > 0.0f)) return 0.0f;
    return std::clamp(a.value_pull, 0.0f, 1.0f) * smoothstep(a.value_near, a.value_far, depth);
}

float luminance_of_lstar(float lstar) {
    const float l = std::clamp(lstar, 0.0f, 100.0f);
    if (l <= 8.0f) return l / 903.3f;
    const float f = (l + 16.0f) / 116.0f;
    return f * f * f;
}

void lay_in_distance_value(const Atmosphere& a, float depth, StrokeConstants& k) {
    const float amount = distance_mass_amount(a, depth);
    if (!(amount > 0.0f)) return;
    k.key_luminance = luminance_of_lstar(a.value);
    k.key_amount = amount;
}

}  // namespace pleinair
