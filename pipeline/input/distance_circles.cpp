// Distance values from the circles, and their validation.
#include "pipeline/input/distance_circles.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pleinair {

float circle_value(double depth, double near, double far) {
    if (std::isnan(depth)) return 1.0f;
    if (near > far) std::swap(near, far);
    if (depth <= near) return 0.0f;
    if (depth >= far) return 1.0f;
    return static_cast<float>(std::clamp((depth - near) / (far - near), 0.0, 1.0));
}

float near_field_value(double depth, double near_field) {
    if (!(near_field > 0) || !(depth < near_field)) return 0.0f;
    if (depth <= 0) return 1.0f;
    return static_cast<float>(1.0 - depth / near_field);
}

std::vector<Problem> validate_circles(const DistanceCircles& c, const std::string& pointer) {
    std::vector<Problem> problems;
    auto number = [](double v) {
        std::ostringstream s;
        s << v;
        return s.str();
    };
    const std::pair<double, const char*> all[] = {{c.leaf_near, "leaf_near"},
                                                  {c.leaf_far, "leaf_far"},
                                                  {c.trunk_near, "trunk_near"},
                                                  {c.trunk_far, "trunk_far"},
                                                  {c.near_field, "near_field"}};
    for (auto [v, name] : all)
        if (!(v >= 0) || !std::isfinite(v))
            problems.push_back(
                {pointer + "/" + name, "must be a finite distance >= 0, got " + number(v)});
    if (!problems.empty()) return problems;
    for (int i = 0; i < 4; i += 2) {
        const auto [near, near_name] = all[i];
        const auto [far, far_name] = all[i + 1];
        if (near > 0 && far == 0)
            problems.push_back({pointer + "/" + far_name, std::string("missing: ") + near_name +
                                                              " is set, and a near "
                                                              "circle needs its far one"});
        else if (far > 0 && near > far)
            problems.push_back({pointer + "/" + far_name, std::string("must be >= ") + near_name +
                                                              " (" + number(near) + "), got " +
                                                              number(far)});
    }
    return problems;
}

}  // namespace pleinair
