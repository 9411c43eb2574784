// Sampling of varied parameters and validation of tree parameters against the key table.
#include "generators/tree_params.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pleinair {

BranchParams TreeParams::default_twigs() {
    BranchParams t;
    t.enabled = false;
    t.min_height = {0.2, 0, 0, 1};
    t.max_height = {1.0, 0, 0, 1};
    t.probability = {0.3, 0, 0, 1};
    t.angle = {45, 10, 0, 180};
    t.max_length = {1.5, 0.3, 1e-3, 1e5};
    t.max_steps = {4, 0, 1, 256, true};
    t.first_length = {0.05, 0.01, 1e-4, 1e3};
    t.first_taper = {0.7, 0.05, 0.01, 1};
    t.extrude_length = {0.4, 0.05, 1e-3, 1e3};
    t.taper = {0.8, 0.03, 0, 1};
    t.wobble = {12, 5, 0, 90};
    return t;
}

std::string format_number(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

std::string format_range(double lo, double hi) {
    // Appends rather than "[" + string: GCC 12 warns falsely (-Wrestrict) on the latter.
    std::string s("[");
    s.append(format_number(lo)).append(", ").append(format_number(hi)).append("]");
    return s;
}

std::string format_vector(double x, double y, double z) {
    std::string s("[");
    s.append(format_number(x)).append(", ").append(format_number(y)).append(", ");
    s.append(format_number(z)).append("]");
    return s;
}

namespace {

// Visits the key table and records every value outside its range, with its JSON pointer.
class Validator {
  public:
    std::vector<std::string> problems;

    template <class Fn>
    void object(const char* key, const char*, Fn&& fn) {
        path_.push_back(key);
        fn();
        path_.pop_back();
    }
    void param(const char* key, const Param& p, const char*, const char*) {
        path_.push_back(key);
        check("base", p.base, p.lo, p.hi);
        check("var", p.var, 0, std::max(p.hi - p.lo, 0.0));
        if (p.whole && std::isfinite(p.base) && p.base != std::floor(p.base))
            problems.push_back(pointer("base") + ": must be a whole number, got " +
                               format_number(p.base));
        path_.pop_back();
    }
    void number(const char* key, double x, Range r, const char*, const char*) {
        check(key, x, r.lo, r.hi);
    }
    void integer(const char* key, int x, Range r, const char*) { check(key, x, r.lo, r.hi); }
    void boolean(const char*, bool, const char*) {}
    void vector(const char* key, const glm::dvec3& x, const char*, const char*) {
        if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
            problems.push_back(pointer(key) + ": must be three finite numbers");
    }
    void text(const char*, const std::string&, const char*) {}

  private:
    std::vector<std::string> path_;

    std::string pointer(const char* key) const {
        std::string s;
        for (const auto& k : path_) s += "/" + k;
        return s + "/" + key;
    }
    void check(const char* key, double x, double lo, double hi) {
        if (!(x >= lo && x <= hi))  // also rejects NaN
            problems.push_back(pointer(key) + ": must be in " + format_range(lo, hi) + ", got " +
                               format_number(x));
    }
};

}  // namespace

std::vector<std::string> validate(const TreeParams& params) {
    Validator v;
    visit_tree_params(params, v);
    auto cross = [&](const BranchParams& b, const char* name) {
        if (b.min_height.base > b.max_height.base)
            v.problems.push_back(std::string("/") + name + "/min_height/base: must not exceed " +
                                 "max_height (" + format_number(b.max_height.base) + "), got " +
                                 format_number(b.min_height.base));
    };
    cross(params.branches, "branches");
    cross(params.twigs, "twigs");
    // A pull needs a direction: a zero one was normalised to nothing and quietly ignored.
    auto pull = [&](const Tropism& t, const char* name) {
        if (t.direction == glm::dvec3(0.0) && (t.strength.base != 0 || t.strength.var != 0))
            v.problems.push_back(std::string("/") + name +
                                 "/tropism/direction: must not be [0, 0, 0] while the strength "
                                 "is not 0");
    };
    pull(params.branches.tropism, "branches");
    pull(params.twigs.tropism, "twigs");
    pull(params.leaves.tropism, "leaves");
    return v.problems;
}

}  // namespace pleinair
