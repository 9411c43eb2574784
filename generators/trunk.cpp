// The trunk generator: cube, then repeated extrusion of the top face.
#include "generators/trunk.h"

#include <cmath>

#include "shading/portable_math.h"

namespace pleinair {

void grow_trunk(TreeMesh& tm, const TreeParams& p, uint64_t seed) {
    Rng tree_rng = make_rng(seed, Purpose::kTree);
    const double size = sample(p.trunk.initial_size, tree_rng) * p.unit;
    const double max_height = sample(p.trunk.max_height, tree_rng) * p.unit;
    const double lean = sample(p.trunk.lean, tree_rng);
    const double lean_azimuth = rand1(tree_rng);
    const int max_steps = sample_whole(p.trunk.max_steps, tree_rng);
    tm.unit = p.unit;

    // Corners at 45 + 90 j degrees in the (z, x) plane: counter-clockwise about +y, so the top
    // face's normal points up and the bottom's (reversed) down.
    const double r = size / std::sqrt(2.0);
    auto& m = tm.mesh;
    Ring a, b;
    for (int j = 0; j < 4; ++j) {
        double ang = radians(45.0 + 90.0 * j);
        double z = r * pmath::cos(ang), x = r * pmath::sin(ang);
        a[j] = m.add_vertex({x, 0.0, z});
        b[j] = m.add_vertex({x, size, z});
    }
    m.add_face(a[3], a[2], a[1], a[0]);
    Limb trunk;
    trunk.key = 1;
    trunk.level = 0;
    for (int j = 0; j < 4; ++j) {
        int k = (j + 1) & 3;
        trunk.sides.push_back(m.add_face(a[j], a[k], b[k], b[j]));
    }
    trunk.top = m.add_face(b[0], b[1], b[2], b[3]);
    trunk.rings = {a, b};
    trunk.centers = {glm::dvec3(0), glm::dvec3(0, size, 0)};
    trunk.radii = {r, r};
    trunk.direction = glm::dvec3(0, 1, 0);
    trunk.heading = wobble_direction(trunk.direction, lean, lean_azimuth);
    trunk.length = size;
    tm.limbs = {trunk};
    // 2% of the trunk's radius: small enough to read as a point, large enough that every face
    // keeps a well-defined normal at any unit.
    tm.min_radius = 0.02 * r;

    Rng rng = make_rng(seed, Purpose::kTrunk);
    const auto& t = p.trunk;
    StepParams sp{&t.extrude_length, &t.twist, &t.taper, &t.wobble};
    StopRule stop;
    stop.max_steps = max_steps;
    stop.max_height = max_height;
    grow_limb(tm, 0, sp, stop, rng);
}

}  // namespace pleinair
