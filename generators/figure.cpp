// A figure as tapered tubes and balls (head, hands) posed by a few joints, its touches laid on a
// jittered grid over each part's surface: even cover without the clumps of plain random draws.
#include "generators/figure.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "generators/rng.h"

namespace pleinair {

namespace {

// A tapered tube from a (radius ra) to b (radius rb), or a ball about a (a == b, radius ra), in
// the figure's frame (+y up, +z forward) in units of its height.
struct Part {
    glm::dvec3 a, b;
    double ra, rb;
    FigurePart colour;
    bool head = false;  // its top and back take the hair's (or the cap's) colour
};

using Parts = std::vector<Part>;

void tube(Parts& p, glm::dvec3 a, glm::dvec3 b, double ra, double rb, FigurePart c) {
    p.push_back({a, b, ra, rb, c});
}
void ball(Parts& p, glm::dvec3 at, double r, FigurePart c) { p.push_back({at, at, r, r, c}); }
void head_at(Parts& p, glm::dvec3 at, double r) {
    p.push_back({at, at, r, r, FigurePart::kSkin, true});
}

// An arm from the shoulder through the elbow to the hand, in the sleeve's colour, the hand bare.
void arm(Parts& p, glm::dvec3 shoulder, glm::dvec3 elbow, glm::dvec3 hand) {
    tube(p, shoulder, elbow, 0.032, 0.028, FigurePart::kTop);
    tube(p, elbow, hand, 0.028, 0.024, FigurePart::kTop);
    ball(p, hand, 0.026, FigurePart::kSkin);
}

// The skirt from the waist to the ground, or two legs, from `hips` high (the feet
// `forward` of the hips when the figure bends).
void lower_body(Parts& p, bool dress, double hips, double forward) {
    if (dress) {
        tube(p, {0, hips + 0.04, 0}, {0, 0.015, forward}, 0.095, 0.17, FigurePart::kBottom);
        return;
    }
    for (double side : {-1.0, 1.0}) {
        tube(p, {side * 0.055, hips, 0}, {side * 0.06, 0.27, 0.5 * forward}, 0.055, 0.04,
             FigurePart::kBottom);
        tube(p, {side * 0.06, 0.27, 0.5 * forward}, {side * 0.065, 0.02, forward}, 0.04, 0.035,
             FigurePart::kBottom);
    }
}

// The pose's parts. Proportions after a standing adult of eight heads; a child (height under
// 1.3) keeps a larger head.
Parts pose_parts(const FigureParams& p) {
    const double head = 0.064 + 0.03 * std::clamp((1.3 - p.height) / 0.6, 0.0, 1.0);
    Parts parts;
    switch (p.pose) {
        case FigurePose::kStanding:
        case FigurePose::kReaching: {
            const bool reach = p.pose == FigurePose::kReaching;
            head_at(parts, {0, 1 - head, reach ? 0.012 : 0}, head);
            tube(parts, {0, 0.53, 0}, {0, 0.80, 0}, 0.085, 0.1, FigurePart::kTop);
            lower_body(parts, p.dress, 0.52, 0.0);
            arm(parts, {-0.11, 0.79, 0}, {-0.13, 0.63, 0.02}, {-0.12, 0.48, 0.05});
            if (reach)
                // Up into the branches, as the woman under Mortefontaine's leaning tree.
                arm(parts, {0.11, 0.80, 0}, {0.15, 0.98, 0.06}, {0.16, 1.16, 0.10});
            else
                arm(parts, {0.11, 0.79, 0}, {0.13, 0.63, 0.02}, {0.12, 0.48, 0.05});
            break;
        }
        case FigurePose::kBending: {
            // The back 65 degrees forward of upright, the hands near the ground ahead.
            const glm::dvec3 hips(0, 0.52, 0), along(0, 0.423, 0.906);
            tube(parts, hips, hips + 0.29 * along, 0.085, 0.1, FigurePart::kTop);
            head_at(parts, hips + (0.31 + head) * along, head);
            const glm::dvec3 shoulder = hips + 0.27 * along;
            for (double side : {-1.0, 1.0})
                arm(parts, shoulder + glm::dvec3(side * 0.1, 0, 0),
                    {side * 0.1, 0.42, shoulder.z + 0.05}, {side * 0.08, 0.22, shoulder.z + 0.1});
            lower_body(parts, p.dress, 0.5, 0.06);
            break;
        }
        case FigurePose::kSeated: {
            // On the ground, the knees raised, the hands on them.
            head_at(parts, {0, 0.48, 0}, head);
            tube(parts, {0, 0.1, 0}, {0, 0.37, 0}, 0.09, 0.1, FigurePart::kTop);
            for (double side : {-1.0, 1.0})
                arm(parts, {side * 0.11, 0.36, 0}, {side * 0.12, 0.24, 0.08},
                    {side * 0.07, 0.2, 0.22});
            if (p.dress) {
                tube(parts, {0, 0.08, 0}, {0, 0.12, 0.3}, 0.12, 0.09, FigurePart::kBottom);
                tube(parts, {0, 0.12, 0.3}, {0, 0.04, 0.45}, 0.09, 0.07, FigurePart::kBottom);
            } else {
                for (double side : {-1.0, 1.0}) {
                    tube(parts, {side * 0.055, 0.07, 0}, {side * 0.06, 0.19, 0.25}, 0.05, 0.04,
                         FigurePart::kBottom);
                    tube(parts, {side * 0.06, 0.19, 0.25}, {side * 0.065, 0.03, 0.42}, 0.04, 0.035,
                         FigurePart::kBottom);
                }
            }
            break;
        }
    }
    return parts;
}

// Two unit vectors square to d and to each other.
void square_to(const glm::dvec3& d, glm::dvec3& u, glm::dvec3& v) {
    const glm::dvec3 ref = std::abs(d.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    u = glm::normalize(glm::cross(ref, d));
    v = glm::cross(d, u);
}

// The part's touches in the figure's frame: a grid of rows along the tube (or latitude bands
// of the ball) and columns about it, each cell's touch jittered inside it.
void lay_touches(const Part& part, double width, double density, Rng& rng, FigureTouches& out) {
    const double len = glm::length(part.b - part.a);
    const bool is_ball = len < 1e-9;
    const double r = 0.5 * (part.ra + part.rb);
    const double area = is_ball ? 4 * pmath::kPi * r * r : 2 * pmath::kPi * r * len;
    const double cells = std::max(2.0, std::round(density * area / (width * width)));
    const int around = std::max(
        2,
        static_cast<int>(std::round(std::sqrt(cells * 2 * pmath::kPi * r / std::max(len, 2 * r)))));
    const int rows = std::max(1, static_cast<int>(std::round(cells / around)));
    const glm::dvec3 d = is_ball ? glm::dvec3(0, 1, 0) : (part.b - part.a) / len;
    glm::dvec3 u, v;
    square_to(d, u, v);
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < around; ++j) {
            const double t = (i + rand1(rng)) / rows;
            const double a = 2 * pmath::kPi * (j + rand1(rng)) / around;
            double s, c;
            pmath::sincos(a, s, c);
            glm::dvec3 n, at;
            if (is_ball) {
                // Bands of equal area: the height along d is uniform on a sphere.
                const double z = 2 * t - 1, ring = std::sqrt(std::max(0.0, 1 - z * z));
                n = z * d + ring * (c * u + s * v);
                at = part.a + r * n;
            } else {
                n = c * u + s * v;
                at = part.a + t * (part.b - part.a) + (part.ra + t * (part.rb - part.ra)) * n;
            }
            at.y = std::max(at.y, 0.0);  // a hem or a foot on the ground, not under it
            out.position.push_back(glm::vec3(at));
            out.normal.push_back(glm::vec3(n));
            const bool hair = part.head && (n.y > 0.3 || n.z < -0.25);
            out.part.push_back(hair ? FigurePart::kHair : part.colour);
        }
}

}  // namespace

glm::vec3 figure_color(const FigureParams& p, FigurePart part) {
    switch (part) {
        case FigurePart::kSkin:
            return p.skin;
        case FigurePart::kHair:
            return p.hair;
        case FigurePart::kTop:
            return p.top;
        case FigurePart::kBottom:
            return p.bottom;
    }
    return p.top;
}

FigureTouches generate_figure(const FigureParams& in, uint64_t seed, const glm::dvec3& foot) {
    FigureParams p = in;
    p.height = std::clamp(std::isfinite(p.height) ? p.height : 1.65, 0.05, 10.0);
    p.stroke_size = std::clamp(std::isfinite(p.stroke_size) ? p.stroke_size : 0.1, 0.01, 0.5);
    p.touches = std::clamp(std::isfinite(p.touches) ? p.touches : 1.5, 0.05, 8.0);
    const double width = p.stroke_size;  // in heights
    FigureTouches local;
    const Parts parts = pose_parts(p);
    for (size_t k = 0; k < parts.size(); ++k) {
        Rng rng = make_rng(seed, Purpose::kFigure, k);
        lay_touches(parts[k], width, p.touches, rng, local);
    }
    // Into the world: turned to face `facing`, scaled to the height, stood at the foot.
    double sf, cf;
    pmath::sincos(std::isfinite(p.facing) ? p.facing * pmath::kPi / 180 : 0.0, sf, cf);
    auto turn = [&](const glm::vec3& q) {
        return glm::dvec3(cf * q.x + sf * q.z, q.y, -sf * q.x + cf * q.z);
    };
    FigureTouches out;
    for (size_t i = 0; i < local.size(); ++i) {
        out.position.push_back(glm::vec3(foot + p.height * turn(local.position[i])));
        out.normal.push_back(glm::vec3(glm::normalize(turn(local.normal[i]))));
        out.width.push_back(static_cast<float>(width * p.height));
        out.part.push_back(local.part[i]);
    }
    return out;
}

}  // namespace pleinair
