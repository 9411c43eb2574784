// σ, ρ, τ and λ of graftals, and the tuft level filter with hysteresis and timed transitions.
#include "pipeline/shot/graftal_lod.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace pleinair {

namespace {

float finite_or_zero(double x) { return std::isfinite(x) ? static_cast<float>(x) : 0.0f; }

// v with its component along unit n removed, normalised; `fallback` where that leaves nothing.
glm::vec3 perpendicular_part(const glm::vec3& v, const glm::vec3& n, const glm::vec3& fallback) {
    const glm::vec3 p = v - n * glm::dot(v, n);
    const float len = glm::length(p);
    return len > 1e-6f && std::isfinite(len) ? p / len : fallback;
}

// A unit vector perpendicular to unit n, chosen from n alone (the axis n is least along).
glm::vec3 fixed_perpendicular(const glm::vec3& n) {
    const glm::vec3 a = std::abs(n.x) < 0.57f   ? glm::vec3(1, 0, 0)
                        : std::abs(n.y) < 0.57f ? glm::vec3(0, 1, 0)
                                                : glm::vec3(0, 0, 1);
    return glm::normalize(a - n * glm::dot(a, n));
}

}  // namespace

float graftal_sigma(double world_length, double preferred_px, double distance, double focal_px) {
    if (!(distance > 0) || !(preferred_px > 0) || !(focal_px > 0) || !(world_length > 0))
        return 0.0f;
    const double d = preferred_px * distance / focal_px;  // D, world units
    return finite_or_zero(std::min(world_length / d, 1e6));
}

float graftal_rho(GraftalRho rule, const glm::vec3& n, const glm::vec3& v) {
    const float c = std::clamp(std::abs(glm::dot(n, v)), 0.0f, 1.0f);  // NaN clamps to 0
    switch (rule) {
        case GraftalRho::kSilhouette:
            return std::isfinite(c) ? 1.0f - c : 0.0f;
        case GraftalRho::kFrontFacing:
            return std::isfinite(c) ? c : 0.0f;
        case GraftalRho::kNone:
            break;
    }
    return 1.0f;
}

float graftal_lambda(GraftalLambda rule, float sigma, float rho, float tau) {
    const float s = std::max(finite_or_zero(sigma), 0.0f);
    const float r = std::clamp(finite_or_zero(rho), 0.0f, 1.0f);
    const float t = std::clamp(finite_or_zero(tau), 0.0f, 1.0f);
    switch (rule) {
        case GraftalLambda::kRhoSigma:
            return r * s;
        case GraftalLambda::kTauRhoSigma:
            return t * r * s;
        case GraftalLambda::kSigma:
            break;
    }
    return s;
}

float lod_ramp(const LodRamp& ramp, float lambda) {
    if (!(ramp.lambda_to > ramp.lambda_from)) return ramp.at_end;
    const float u =
        std::clamp((lambda - ramp.lambda_from) / (ramp.lambda_to - ramp.lambda_from), 0.0f, 1.0f);
    const float t = std::isfinite(u) ? u : 0.0f;
    return ramp.at_start + (ramp.at_end - ramp.at_start) * t;
}

GraftalAxes graftal_axes(GraftalFrame rule, const glm::vec3& n_in, const glm::vec3& v,
                         const glm::vec3& tangent) {
    const float len = glm::length(n_in);
    const glm::vec3 y = len > 1e-12f && std::isfinite(len) ? n_in / len : glm::vec3(0, 1, 0);
    const glm::vec3 fallback = fixed_perpendicular(y);
    glm::vec3 x;
    switch (rule) {
        case GraftalFrame::kView:
            // n x v is perpendicular to n and to the view's component across it.
            x = perpendicular_part(glm::cross(y, v), y, fallback);
            break;
        case GraftalFrame::kUpright:
            x = perpendicular_part(glm::cross(y, glm::cross(y, glm::vec3(0, 1, 0))), y, fallback);
            break;
        case GraftalFrame::kSurface:
            x = perpendicular_part(tangent, y, fallback);
            break;
    }
    return {x, y, glm::cross(x, y)};
}

int tuft_level(const std::vector<TuftLevel>& levels, float lambda) {
    int level = 0;
    for (size_t i = 1; i < levels.size(); ++i)
        if (levels[i].lambda <= lambda) level = static_cast<int>(i);
    return level;
}

void step_tuft(TuftState& s, const TuftRules& rules, int chosen, double dt) {
    const int top = static_cast<int>(rules.levels.size()) - 1;
    chosen = std::clamp(chosen, 0, std::max(top, 0));
    const size_t queue = static_cast<size_t>(std::max(rules.queue, 1));
    // The first frame fills the queue with its choice: a shot opens on a settled tuft, not one
    // whose average swings while the queue fills.
    if (!s.started) s.recent.assign(queue, chosen);
    s.recent.push_back(chosen);
    while (s.recent.size() > queue) s.recent.erase(s.recent.begin());
    // The mean of small integers: exact in double whatever the order.
    double sum = 0;
    for (int c : s.recent) sum += c;
    s.average = static_cast<float>(sum / static_cast<double>(s.recent.size()));
    s.tau.resize(rules.levels.size(), 0.0f);
    if (!s.started) {
        s.started = true;
        s.level = chosen;
        for (size_t i = 0; i < s.tau.size(); ++i)
            s.tau[i] = static_cast<int>(i) <= s.level ? 1.0f : 0.0f;
        return;
    }
    // Hysteresis around the half-way points: from level i, up once u >= i + 1/2 + h, down
    // once u < i - 1/2 - h (the paper's 2.75 and 2.25 for h = 1/4).
    const float h = rules.hysteresis;
    while (s.level < top && s.average >= static_cast<float>(s.level) + 0.5f + h) ++s.level;
    while (s.level > 0 && s.average < static_cast<float>(s.level) - 0.5f - h) --s.level;
    const float step =
        rules.transition_seconds > 0 ? static_cast<float>(dt / rules.transition_seconds) : 1.0f;
    for (size_t i = 0; i < s.tau.size(); ++i) {
        const bool on = static_cast<int>(i) <= s.level;
        float t = s.tau[i] + (on ? step : -step);
        // n steps of 1/n do not sum to exactly 1 in float: snap what is within rounding.
        if (t > 1.0f - 1e-5f) t = 1.0f;
        if (t < 1e-5f) t = 0.0f;
        s.tau[i] = t;
    }
}

TuftState replay_tuft(const TuftRules& rules, const std::function<float(int)>& lambda_at, int frame,
                      double fps) {
    TuftState s;
    const double dt = fps > 0 ? 1.0 / fps : 0.0;
    std::vector<int> chosen(static_cast<size_t>(std::max(frame + 1, 0)));
    for (int f = 0; f <= frame; ++f)
        chosen[static_cast<size_t>(f)] = tuft_level(rules.levels, lambda_at(f));
    // Most tufts choose one level all along (far ones, or a still): stepping them would end
    // where the first frame starts, so start there (the same state, member for member).
    if (!chosen.empty() &&
        std::all_of(chosen.begin(), chosen.end(), [&](int c) { return c == chosen[0]; })) {
        step_tuft(s, rules, chosen[0], dt);
        return s;
    }
    for (int c : chosen) step_tuft(s, rules, c, dt);
    return s;
}

}  // namespace pleinair
