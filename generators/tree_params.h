// Tree presets as plain parameter structs with in-class defaults, and the one table that names,
// bounds and documents every key (read by the preset loader, the saver, the validator and the
// reference in the README).
#pragma once

#include <cmath>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "generators/rng.h"

namespace pleinair {

// A number drawn per tree or per step: base + var * N(0, 1), clamped to [lo, hi]. `var` is the
// gaussian's standard deviation, in the same unit as `base`; 0 means no variation. lo/hi are the
// key's valid range, fixed by the declaration below, never read from a preset.
struct Param {
    double base = 0;
    double var = 0;
    double lo = 0;
    double hi = 1;
    bool whole = false;
};

// Always consumes the same number of draws, so a stream's later numbers do not depend on
// whether this parameter varies.
inline double sample(const Param& p, Rng& rng) {
    double g = rand_gaussian(rng);
    double x = p.base + p.var * g;
    return x < p.lo ? p.lo : (x > p.hi ? p.hi : x);
}
inline int sample_whole(const Param& p, Rng& rng) {
    return static_cast<int>(std::lround(sample(p, rng)));
}

// A constant pull on growth: each step's heading becomes normalize(heading + strength * direction).
// Gravity droops willows; a small upward pull keeps poplars fastigiate.
struct Tropism {
    glm::dvec3 direction{0, -1, 0};
    Param strength{0, 0, 0, 10};
    double increase = 0;  // added to the strength per unit of length grown (negative: eases)
};

struct TrunkParams {
    Param initial_size{0.8, 0.05, 1e-3, 1e3};
    Param max_height{10, 1, 1e-3, 1e5};
    Param max_steps{12, 0, 0, 256, true};
    Param extrude_length{1.0, 0.1, 1e-3, 1e3};
    Param twist{0, 4, -360, 360};
    Param taper{0.93, 0.02, 0, 1};
    Param wobble{3, 1.5, 0, 90};
    Param lean{0, 0, 0, 80};
};

// One level of branches; `branches` grow from the trunk, `twigs` (the thesis has no second
// level) from the branches.
struct BranchParams {
    bool enabled = true;
    Param min_height{0.35, 0, 0, 1};
    Param max_height{0.95, 0, 0, 1};
    Param probability{0.35, 0, 0, 1};
    Param angle{55, 10, 0, 180};
    Param max_length{5, 1, 1e-3, 1e5};
    Param max_steps{8, 0, 1, 256, true};
    Param first_length{0.08, 0.01, 1e-4, 1e3};
    Param first_taper{0.75, 0.05, 0.01, 1};
    Param extrude_length{0.8, 0.1, 1e-3, 1e3};
    Param twist{0, 5, -360, 360};
    Param taper{0.85, 0.03, 0, 1};
    Param wobble{8, 4, 0, 90};
    // Apical dominance: max_length scaled from length_at_base (the lowest eligible point on the
    // parent) to length_at_top (the highest), linearly.
    double length_at_base = 1;
    double length_at_top = 1;
    Tropism tropism;
};

// Level-of-detail fade thresholds (thesis IV.6), in the tree's distance value: 0 at the near
// circle, 1 at the far circle.
struct FadeParams {
    double threshold_bias = 0.5;
    double threshold_var = 0.05;
    Param length{0.3, 0.05, 0, 10};
    double length_min = 0.15;
    double keep = 0.2;  // share of the innermost leaves that never fade
};

struct LeafParams {
    int lowest_level = 0;  // limbs of a lower level (0 trunk, 1 branches, 2 twigs) bear none
    Param lowest_step_trunk{4, 0, 0, 1024, true};
    Param trim_top_steps_trunk{0, 0, 0, 1024, true};
    Param steps_from_center{1, 0, 0, 1024, true};
    Param steps_from_tip{0, 0, 0, 1024, true};
    Param probability{0.75, 0, 0, 1};
    Param branch_angle{140, 10, 0, 180};
    Param branching_distance{0.35, 0.05, 1e-4, 1e3};
    Param branching_steps{7, 0, 1, 64, true};
    Param branch_dir_wobble{25, 8, 0, 180};
    Tropism tropism;
    FadeParams fade;
};

// Stiffness of a tree's parts against the wind (generators/wind.h): a part twice as stiff bends
// half as far at the same wind.
struct WindStiffness {
    double trunk = 1, limbs = 1, leaves = 1;
};

struct TreeParams {
    std::string name = "tree";
    std::string description;
    std::string bark_palette;  // the species' bark colours, where a scene names none
    double unit = 1;
    int subdivision_levels = 2;
    glm::dvec3 center_offset{0, 0, 0};
    TrunkParams trunk;
    BranchParams branches;
    BranchParams twigs = default_twigs();
    LeafParams leaves;
    int lod_subdivision_levels = 1;
    WindStiffness stiffness;

    static BranchParams default_twigs();
};

struct Range {
    double lo;
    double hi;
};

// The key table. V is a visitor with these members (see pipeline/input/json_params.cpp for readers
// and writers, tree_params.cpp for the validator):
//   object(key, doc, fn)                  nested object; fn() visits its keys
//   param(key, Param&, unit, doc)         a gaussian-varied number {"base": b, "var": v} or b
//   number(key, double&, Range, unit, doc)
//   integer(key, int&, Range, doc)
//   boolean(key, bool&, doc)
//   vector(key, dvec3&, unit, doc)
//   text(key, string&, doc)
// P is TreeParams or const TreeParams.
template <class P, class V>
void visit_branch_params(P& b, V& v) {
    v.boolean("enabled", b.enabled, "Grow this level at all.");
    v.param("min_height", b.min_height, "fraction",
            "Lowest eligible point on the parent, as a fraction of its length (for the trunk: "
            "of its height). Per tree.");
    v.param("max_height", b.max_height, "fraction",
            "Highest eligible point on the parent, same measure as min_height. Per tree.");
    v.param("probability", b.probability, "",
            "Chance that an eligible side face of the parent grows a branch. Per tree.");
    v.param("angle", b.angle, "deg",
            "Angle between the parent's axis and the branch's initial heading; 90 is "
            "perpendicular. Per branch.");
    v.param("max_length", b.max_length, "units", "Length at which the branch stops. Per branch.");
    v.number("length_at_base", b.length_at_base, Range{0, 10}, "",
             "max_length's scale for a branch at min_height; from there it changes linearly to "
             "length_at_top's at max_height (apical dominance: a conifer's short top branches, "
             "an oak's long low limbs).");
    v.number("length_at_top", b.length_at_top, Range{0, 10}, "",
             "max_length's scale for a branch at max_height.");
    v.param("max_steps", b.max_steps, "",
            "Most extrusions per branch, the short first one included. Per branch.");
    v.param("first_length", b.first_length, "units",
            "Length of the short first extrusion whose face is forced square and planar, so the "
            "subdivided joint stays round (thesis Fig. 12). Per branch.");
    v.param("first_taper", b.first_taper, "",
            "Half-diagonal of that square as a fraction of the largest square the parent face "
            "holds (and of the parent's radius). Per branch.");
    v.param("extrude_length", b.extrude_length, "units",
            "Length of each later extrusion. Per step.");
    v.param("twist", b.twist, "deg", "Rotation of each new face about the growth axis. Per step.");
    v.param("taper", b.taper, "",
            "Scale of each new face relative to the previous one; 1 keeps the radius, 0 ends the "
            "branch in a point (clamped to a minimum radius). Per step.");
    v.param("wobble", b.wobble, "deg",
            "Random turn of the heading at each step, about a random axis. Per step.");
    v.object("tropism", "A constant pull on the heading (gravity, light).", [&] {
        v.vector("direction", b.tropism.direction, "",
                 "Direction of the pull; normalised when used ([0, -1, 0] is gravity).");
        v.param("strength", b.tropism.strength, "",
                "Weight of the pull added to the heading at each step. Per branch.");
        v.number("increase", b.tropism.increase, Range{-10, 10}, "1/units",
                 "Added to the strength for each unit of the branch's length grown, the sum "
                 "kept at 0 or more: a branch that rises, then arches over and falls (the "
                 "willow's hanging branchlets).");
    });
}

template <class P, class V>
void visit_tree_params(P& p, V& v) {
    v.text("name", p.name, "Short name of the family.");
    v.text("description", p.description, "One or two lines on what the family looks like.");
    v.text("bark_palette", p.bark_palette,
           "Palette the bark is painted with on `family`'s contact sheet and in a scene whose "
           "family names none (a silver birch's white bark: \"birch-bark\"); empty: the bark "
           "shader's.");
    v.number("unit", p.unit, Range{1e-6, 1e6}, "world",
             "Size of one tree unit in world units; every length of the preset is in tree units.");
    v.integer("subdivision_levels", p.subdivision_levels, Range{0, 4},
              "Catmull-Clark levels from the control mesh to the render mesh.");
    v.vector("center_offset", p.center_offset, "units",
             "Offset of the centre locator from the canopy's centroid (the centroid of the leaf "
             "particles); moves where leaves count as inner (darker) and outer (lighter, first to "
             "fade).");
    v.object("trunk", "The trunk: a cube extruded upward from its top face (thesis IV.3).", [&] {
        auto& t = p.trunk;
        v.param("initial_size", t.initial_size, "units", "Edge of the starting cube. Per tree.");
        v.param("max_height", t.max_height, "units",
                "Height at which the trunk stops growing. Per tree.");
        v.param("max_steps", t.max_steps, "",
                "Most extrusions of the top face after the cube. Per tree.");
        v.param("extrude_length", t.extrude_length, "units", "Length of each extrusion. Per step.");
        v.param("twist", t.twist, "deg",
                "Rotation of each new face about the growth axis. Per step.");
        v.param("taper", t.taper, "",
                "Scale of each new face relative to the previous one; 1 keeps the radius, 0 "
                "collapses the face (clamped to a minimum radius, and the trunk stops). Per step.");
        v.param("wobble", t.wobble, "deg",
                "Random turn of the growth direction at each step. Per step.");
        v.param("lean", t.lean, "deg",
                "Tilt of the trunk's heading from vertical, toward a random azimuth. Per tree.");
    });
    v.object("branches", "First level of branches, grown from the trunk's side faces.",
             [&] { visit_branch_params(p.branches, v); });
    v.object("twigs", "Optional second level, grown from the branches' side faces.",
             [&] { visit_branch_params(p.twigs, v); });
    v.object(
        "leaves",
        "Leaf particles emitted as implied branches from mesh vertices (thesis "
        "IV.3, Fig. 13 and 14).",
        [&] {
            auto& l = p.leaves;
            v.integer("lowest_level", l.lowest_level, Range{0, 2},
                      "Limbs of a lower level bear no leaves (0 the trunk, 1 branches, 2 twigs): "
                      "2 hangs the leaves on the twigs alone, so the crown breaks into clumps "
                      "at the ends of its limbs.");
            v.param("lowest_step_trunk", l.lowest_step_trunk, "",
                    "Trunk rings below this one (0 is the ground) emit no leaves. Per tree.");
            v.param("trim_top_steps_trunk", l.trim_top_steps_trunk, "",
                    "This many rings at the top of the trunk emit no leaves. Per tree.");
            v.param(
                "steps_from_center", l.steps_from_center, "",
                "Branch rings closer than this to the branch's base emit no leaves. Per branch.");
            v.param("steps_from_tip", l.steps_from_tip, "",
                    "This many rings at a branch's tip emit no leaves. Per branch.");
            v.param("probability", l.probability, "",
                    "Chance that an eligible vertex emits an implied branch of leaves. Per tree.");
            v.param("branch_angle", l.branch_angle, "deg",
                    "Aperture of the cone around the vertex's outward normal in which the implied "
                    "branch starts. Per implied branch.");
            v.param("branching_distance", l.branching_distance, "units",
                    "Distance from one particle to the next along its normal. Per particle.");
            v.param("branching_steps", l.branching_steps, "",
                    "Particles per implied branch. Per implied branch.");
            v.param("branch_dir_wobble", l.branch_dir_wobble, "deg",
                    "Random turn of the direction before each particle. Per particle.");
            v.object(
                "tropism", "A constant pull on implied branches (hanging willow strands).", [&] {
                    v.vector("direction", l.tropism.direction, "",
                             "Direction of the pull; normalised.");
                    v.param("strength", l.tropism.strength, "",
                            "Weight of the pull added before each particle. Per implied branch.");
                    v.number("increase", l.tropism.increase, Range{-10, 10}, "1/units",
                             "Added to the strength for each unit of the implied branch's "
                             "length, the sum kept at 0 or more.");
                });
            v.object(
                "fade",
                "Level-of-detail fade thresholds (thesis IV.6), in the tree's distance "
                "value (0 at the near circle, 1 at the far one). Leaves farther from the "
                "centre fade first, by their rank in that distance, so a crown thins at one "
                "pace across the circles; each fade ends by the far circle.",
                [&] {
                    auto& f = l.fade;
                    v.number(
                        "threshold_bias", f.threshold_bias, Range{0.001, 0.999}, "",
                        "Bias applied to (1 - the leaf's rank in distance from the centre, 0 "
                        "innermost, 1 outermost) to place where it starts fading; below 0.5 every "
                        "leaf fades sooner.");
                    v.number("threshold_var", f.threshold_var, Range{0, 1}, "",
                             "Gaussian standard deviation added to each leaf's start.");
                    v.param("length", f.length, "",
                            "Span of distance values over which a leaf fades out. Per leaf.");
                    v.number("length_min", f.length_min, Range{0, 1}, "",
                             "Smallest span of a fade.");
                    v.number("keep", f.keep, Range{0, 1}, "",
                             "Share of the innermost leaves that never fade: the tree beyond the "
                             "far circle is painted with them, grown. Every other leaf has "
                             "faded out completely by the far circle.");
                });
        });
    v.object("stiffness",
             "How the tree's parts resist the wind (the scene's /wind): a part twice as stiff "
             "bends half as far.",
             [&] {
                 auto& w = p.stiffness;
                 v.number("trunk", w.trunk, Range{0.05, 100}, "",
                          "The trunk, bending from its root with the whole wind (an oak's is "
                          "stiffer than a willow's).");
                 v.number("limbs", w.limbs, Range{0.05, 100}, "",
                          "Branches and twigs, each bending from where it leaves its parent.");
                 v.number("leaves", w.leaves, Range{0.05, 100}, "",
                          "The leaves' flutter about their own normal (an aspen's or a "
                          "birch's: low).");
             });
    v.object("lod",
             "The low-detail model (the thesis's LOD button): trunk and first-level "
             "branches only.",
             [&] {
                 v.integer("subdivision_levels", p.lod_subdivision_levels, Range{0, 4},
                           "Catmull-Clark levels of the low-detail mesh.");
             });
}

// Every problem with the values, one line each: "/trunk/taper/base: must be in [0, 1], got 1.7".
std::vector<std::string> validate(const TreeParams& params);

// The one number format of messages and the reference (shortest %g-like), so they agree.
std::string format_number(double x);
// "[lo, hi]" in that format.
std::string format_range(double lo, double hi);
// "[x, y, z]" in that format.
std::string format_vector(double x, double y, double z);

}  // namespace pleinair
