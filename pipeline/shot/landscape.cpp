// Terrain, water and rocks to surfaces and strokes, with the materials chosen per particle.
#include "pipeline/shot/landscape.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "generators/rock.h"
#include "pipeline/input/camera_track.h"
#include "pipeline/shot/figures.h"
#include "shading/curves.h"
#include "shading/noise.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace {

constexpr uint64_t kTerrainKey = 1, kWaterKey = 2, kNearKey = 3, kContactKey = 4, kRockKey = 100,
                   kMeshKey = 1ull << 32, kRegionKey = 1ull << 33;

// Near-field strokes are this much smaller than the terrain's own, and a cell of their grid
// (which holds as many as a section of the terrain) half as wide as a terrain stroke.
constexpr float kNearStrokeScale = 0.25f;
constexpr double kNearCellScale = 0.5;

// Trees whose contact touches share a chunk (add_contact).
constexpr size_t kContactTrees = 32;

// Whether the bank mask paints the ground at `world` (it wins over the regions).
bool on_bank(const SceneDesc& s, const glm::dvec3& world) {
    const TerrainDesc& t = s.terrain;
    return t.bank_material >= 0 && s.water.present && world.y < s.water.level + t.bank_height;
}

// The terrain's point and unit normal (central differences `d` apart) at (x, z), or false off
// the terrain or under the water: where near-field strokes and contact touches stand.
bool terrain_point(const SceneDesc& s, double x, double z, double d, glm::vec3& pos, glm::vec3& n) {
    const TerrainDesc& t = s.terrain;
    const TerrainParams& p = t.params;
    if (x < p.min.x || x > p.max.x || z < p.min.y || z > p.max.y) return false;
    const double h = terrain_height(p, t.seed, x, z);
    const double level = s.water.present ? s.water.level : -1e300;
    if (h < level - 0.02) return false;
    const double dx = terrain_height(p, t.seed, x + d, z) - terrain_height(p, t.seed, x - d, z);
    const double dz = terrain_height(p, t.seed, x, z + d) - terrain_height(p, t.seed, x, z - d);
    pos = glm::vec3(glm::dvec3(x, h, z));
    n = glm::vec3(glm::normalize(glm::dvec3(-dx, 2 * d, -dz)));
    return true;
}

// The largest near-field circle the camera carries anywhere, and the ground points (x, z) it
// passes over: the still camera's, or each frame's along the track.
double near_field_path(const SceneDesc& s, std::vector<glm::dvec2>& eyes) {
    double near = s.circles.near_field;
    for (const CameraKey& k : s.camera_track.keys) near = std::max(near, k.near_field);
    if (!(near > 0)) return 0;
    if (s.camera_track.keys.empty()) {
        eyes.push_back({s.camera_params.position.x, s.camera_params.position.z});
        return near;
    }
    const int first = track_first_frame(s.camera_track, s.fps);
    const int last = track_last_frame(s.camera_track, s.fps);
    for (int f = first; f <= last; ++f) {
        const glm::dvec3 p = track_at(s.camera_track, frame_time(f, s.fps)).position;
        eyes.push_back({p.x, p.z});
    }
    return near;
}

// The near field's detail strokes: on a world grid of cells half a terrain stroke wide, those
// within 1.2 near-field radii of any eye on the camera's path, in the order of their cells.
void emit_near_field(const SceneDesc& s, const SurfaceStrokeParams& tp, float size,
                     BuiltLandscape& out) {
    std::vector<glm::dvec2> eyes;
    const double near = near_field_path(s, eyes);
    if (!(near > 0)) return;
    const TerrainDesc& t = s.terrain;
    const double cell = kNearCellScale * s.materials[t.material].shader.sprite_size * size;
    if (!(cell > 0)) return;
    const double reach = 1.2 * near;
    std::set<std::pair<int, int>> picked;
    for (const glm::dvec2& e : eyes) {
        const int x0 = static_cast<int>(std::floor((e.x - reach) / cell));
        const int x1 = static_cast<int>(std::floor((e.x + reach) / cell));
        const int z0 = static_cast<int>(std::floor((e.y - reach) / cell));
        const int z1 = static_cast<int>(std::floor((e.y + reach) / cell));
        for (int x = x0; x <= x1; ++x)
            for (int z = z0; z <= z1; ++z)
                if (pmath::hypot((x + 0.5) * cell - e.x, (z + 0.5) * cell - e.y) < reach)
                    picked.emplace(x, z);
    }
    std::vector<glm::ivec2> cells;
    for (const auto& [x, z] : picked) cells.push_back({x, z});
    const GroundAt ground = [&](double x, double z, glm::vec3& pos, glm::vec3& n) {
        return terrain_point(s, x, z, 0.25 * cell, pos, n);
    };
    SurfaceParticles strokes;
    emit_cell_strokes(cells, cell, tp, t.seed, kNearKey, ground, strokes);
    for (size_t i = 0; i < strokes.size(); ++i)
        strokes.material[i] =
            static_cast<uint16_t>(terrain_material_at(s, glm::dvec3(strokes.position[i])));
    out.near_chunk = out.chunks.size();
    out.chunks.push_back(std::move(strokes));
    out.chunk_size.push_back(size * kNearStrokeScale);
}

// The region at `world` when it paints the ground at its own density, else -1.
int dense_region(const SceneDesc& s, const glm::dvec3& world) {
    const int r = terrain_region_at(s, world);
    return r >= 0 && s.terrain.regions[static_cast<size_t>(r)].density != 1 ? r : -1;
}

// The strokes of the regions with a density of their own, in place of the terrain's there: on
// a world grid of cells as large as a terrain section, each holding the section's count of
// strokes, the cells shrunk by the square root of the density and the strokes with them (the
// same cover), each kept where its region paints the ground (later regions and the bank win).
// A band of kRows rows of cells makes a chunk.
void emit_regions(const SceneDesc& s, const SurfaceStrokeParams& tp, float size,
                  BuiltLandscape& out) {
    constexpr int kRows = 8;
    const TerrainDesc& t = s.terrain;
    const glm::dvec2 extent = t.params.max - t.params.min;
    const double section = std::sqrt(extent.x / std::max(tp.particle_spans_u, 1) * extent.y /
                                     std::max(tp.particle_spans_v, 1));
    for (size_t ri = 0; ri < t.regions.size(); ++ri) {
        const MaterialRegion& r = t.regions[ri];
        if (r.density == 1 || !(section > 0)) continue;
        const double cell = section / std::sqrt(r.density), reach = 1.25 * r.radius;
        const int x0 = static_cast<int>(std::floor((r.center.x - reach) / cell));
        const int x1 = static_cast<int>(std::floor((r.center.x + reach) / cell));
        const int z0 = static_cast<int>(std::floor((r.center.y - reach) / cell));
        const int z1 = static_cast<int>(std::floor((r.center.y + reach) / cell));
        const GroundAt ground = [&](double x, double z, glm::vec3& pos, glm::vec3& n) {
            return terrain_point(s, x, z, 0.25 * cell, pos, n);
        };
        const StrokeKeep keep = [&](SurfaceParticles& p, size_t i) {
            if (dense_region(s, glm::dvec3(p.position[i])) != static_cast<int>(ri)) return false;
            p.material[i] = static_cast<uint16_t>(r.material);
            return true;
        };
        for (int zb = z0; zb <= z1; zb += kRows) {
            std::vector<glm::ivec2> cells;
            for (int z = zb; z <= std::min(zb + kRows - 1, z1); ++z)
                for (int x = x0; x <= x1; ++x) cells.push_back({x, z});
            SurfaceParticles strokes;
            emit_cell_strokes(cells, cell, tp, t.seed, kRegionKey + ri, ground, strokes, false,
                              keep);
            if (strokes.size() == 0) continue;
            out.chunks.push_back(std::move(strokes));
            out.chunk_size.push_back(size / static_cast<float>(std::sqrt(r.density)));
        }
    }
}

// The scene's stroke parameters with the material's detail threshold and the density applied.
SurfaceStrokeParams strokes_for(const SurfaceStrokeParams& in, const Material& m, uint32_t index,
                                float density, float& size) {
    SurfaceStrokeParams p = in;
    p.material = index;
    p.detail_threshold = m.surface.detail_threshold;
    const int n = std::max(1, static_cast<int>(std::lround(p.particles_per_cluster * density)));
    // Fewer or more sprites cover the same area: each grows or shrinks by the square root.
    size = std::sqrt(static_cast<float>(p.particles_per_cluster) / static_cast<float>(n));
    p.particles_per_cluster = n;
    return p;
}

// emit_surface_strokes over bands of section rows in parallel, one chunk per band in row
// order: the same particles as one serial call, on any number of threads.
void emit_bands(const GridSurface& g, const SurfaceStrokeParams& p, uint64_t seed, uint64_t key,
                float size, BuiltLandscape& out, const StrokeKeep& keep) {
    constexpr int kRows = 8;
    const int bands = (std::max(p.particle_spans_v, 1) + kRows - 1) / kRows;
    const size_t first = out.chunks.size();
    out.chunks.resize(first + static_cast<size_t>(bands));
    out.chunk_size.resize(out.chunks.size(), size);
    tbb::parallel_for(0, bands, [&](int b) {
        emit_surface_strokes(g, p, seed, key, out.chunks[first + static_cast<size_t>(b)], keep,
                             b * kRows, (b + 1) * kRows);
    });
}

}  // namespace

size_t BuiltLandscape::stroke_count() const {
    size_t n = 0;
    for (const auto& c : chunks) n += c.size();
    return n;
}

SurfaceParticles BuiltLandscape::all_strokes() const {
    SurfaceParticles all;
    all.reserve(stroke_count());
    for (const auto& c : chunks) all.append(c);
    return all;
}

uint32_t terrain_material_at(const SceneDesc& s, const glm::dvec3& world) {
    const TerrainDesc& t = s.terrain;
    uint32_t m = t.material;
    const glm::dvec2 size = t.params.max - t.params.min;
    const float u = static_cast<float>((world.x - t.params.min.x) / size.x);
    const float v = static_cast<float>((world.z - t.params.min.y) / size.y);
    const float offset = static_cast<float>(t.seed % 997) * 0.37f;
    if (t.second_material >= 0 &&
        noise_material(u, v, t.material_noise_frequency, t.material_threshold, offset))
        m = static_cast<uint32_t>(t.second_material);
    if (on_bank(s, world)) return static_cast<uint32_t>(t.bank_material);
    const int r = terrain_region_at(s, world);
    return r >= 0 ? t.regions[static_cast<size_t>(r)].material : m;
}

int terrain_region_at(const SceneDesc& s, const glm::dvec3& world) {
    if (on_bank(s, world)) return -1;
    const std::vector<MaterialRegion>& regions = s.terrain.regions;
    for (size_t i = regions.size(); i-- > 0;) {
        const MaterialRegion& r = regions[i];
        // The rim wanders by a quarter of the radius (slow noise), so a region reads as a
        // patch of ground, not a drawn circle.
        const double d = pmath::hypot(world.x - r.center.x, world.z - r.center.y) / r.radius;
        const float rim =
            0.75f + 0.5f * noise(static_cast<float>(world.x - r.center.x) * 0.35f + 31.7f,
                                 static_cast<float>(world.z - r.center.y) * 0.35f + 11.3f);
        if (d < rim) return static_cast<int>(i);
    }
    return -1;
}

namespace {

// The particle files' strokes, in chunks small enough to spread over threads.
void add_imported(const SceneDesc& s, BuiltLandscape& out) {
    out.chunk_source.resize(out.chunks.size());
    for (const ParticleFileDesc& p : s.particles) {
        if (!p.particles) continue;
        out.imported.push_back(p.particles);
        const SurfaceParticles& all = p.particles->strokes;
        for (size_t first = 0; first < all.size(); first += kImportedChunk) {
            const size_t n = std::min(kImportedChunk, all.size() - first);
            SurfaceParticles c;
            c.append(all, first, n);
            out.chunks.push_back(std::move(c));
            out.chunk_size.push_back(1.0f);
            out.chunk_source.push_back({p.particles.get(), first, p.color_amount, p.casts_shadows});
        }
    }
}

// A chunk per figure (pipeline/shot/figures.h), painted in its own colours (color_amount 1),
// casting the sun's shadows.
void add_figures(const SceneDesc& s, BuiltLandscape& out) {
    out.chunk_source.resize(out.chunks.size());
    for (const FigureDesc& f : s.figures) {
        auto particles = std::make_shared<const ImportedParticles>(
            figure_particles(f, glm::vec3(s.sun_direction)));
        if (particles->strokes.size() == 0) continue;
        out.chunks.push_back(particles->strokes);
        out.chunk_size.push_back(1.0f);
        out.chunk_source.push_back({particles.get(), 0, 1.0f, true});
        out.imported.push_back(std::move(particles));
    }
}

void build_surfaces(const SceneDesc& s, BuiltLandscape& out) {
    const float density = s.build.surface_density;
    if (!s.terrain.present) return;
    const TerrainDesc& t = s.terrain;
    out.has_terrain = true;
    GridSurface grid = generate_terrain(t.params, t.seed);
    out.terrain_mesh = grid_mesh(grid);

    float size = 1;
    SurfaceStrokeParams tp =
        strokes_for(t.strokes, s.materials[t.material], t.material, density, size);
    const double level = s.water.present ? s.water.level : -1e300;
    emit_bands(grid, tp, t.seed, kTerrainKey, size, out, [&](SurfaceParticles& p, size_t i) {
        const glm::vec3& ground = p.position[i];
        if (s.water.present && ground.y < level - 0.02) return false;
        if (dense_region(s, glm::dvec3(ground)) >= 0) return false;  // emit_regions' ground
        p.material[i] = static_cast<uint16_t>(terrain_material_at(s, glm::dvec3(ground)));
        return true;
    });
    emit_regions(s, tp, size, out);
    emit_near_field(s, tp, size, out);

    if (s.water.present) {
        out.has_water = true;
        const WaterDesc& w = s.water;
        GridSurface plane;
        plane.nu = plane.nv = 2;
        const float y = static_cast<float>(w.level);
        const auto& mn = t.params.min;
        const auto& mx = t.params.max;
        plane.positions = {glm::vec3(mn.x, y, mn.y), glm::vec3(mx.x, y, mn.y),
                           glm::vec3(mn.x, y, mx.y), glm::vec3(mx.x, y, mx.y)};
        out.water_mesh = grid_mesh(plane);
        SurfaceStrokeParams wp =
            strokes_for(w.strokes, s.materials[w.material], w.material, density, size);
        emit_bands(plane, wp, t.seed, kWaterKey, size, out, [&](SurfaceParticles& p, size_t i) {
            const glm::vec3& q = p.position[i];
            return terrain_height(t.params, t.seed, q.x, q.z) < level + 0.05;
        });
    }

    for (size_t i = 0; i < s.rocks.size(); ++i) {
        const RockDesc& r = s.rocks[i];
        out.rocks.push_back(generate_rock(r.params, r.seed, r.position));
        out.rock_material.push_back(r.material);
        SurfaceStrokeParams rp =
            strokes_for(r.strokes, s.materials[r.material], r.material, density, size);
        out.chunks.emplace_back();
        out.chunk_size.push_back(size);
        emit_mesh_strokes(out.rocks.back(), rp, r.seed, kRockKey + i, out.chunks.back());
    }
}

// The glTF surfaces (/meshes), with or without a terrain: each a rock-like mesh and one chunk
// of strokes, as many per area whatever its triangles' sizes.
void add_meshes(const SceneDesc& s, BuiltLandscape& out) {
    const float density = std::max(s.build.surface_density, 1e-6f);
    for (size_t i = 0; i < s.meshes.size(); ++i) {
        const MeshFileDesc& m = s.meshes[i];
        if (!m.mesh) continue;
        out.rocks.push_back(*m.mesh);
        out.rock_material.push_back(m.material);
        const Material& mat = s.materials[m.material];
        SurfaceStrokeParams p;
        p.material = m.material;
        p.detail_threshold = mat.surface.detail_threshold;
        p.displacement_height = m.displacement;
        const double w = std::max<double>(mat.shader.sprite_size, 1e-3);
        const double per_area = (m.density > 0 ? m.density : 2.0 / (w * w)) * density;
        out.chunks.emplace_back();
        // Fewer or more strokes cover the same area: each grows or shrinks by the square root.
        out.chunk_size.push_back(1.0f / std::sqrt(density));
        emit_triangle_strokes(*m.mesh, p, per_area, m.seed, kMeshKey + i, out.chunks.back());
    }
}

}  // namespace

void add_contact(const SceneDesc& s, const std::vector<TreeFoot>& feet, BuiltLandscape& out) {
    const ContactDesc& c = s.contact;
    if (c.touches <= 0 || feet.empty() || (c.material < 0 && !s.terrain.present)) return;
    const uint32_t first_material =
        c.material >= 0 ? static_cast<uint32_t>(c.material) : s.terrain.material;
    SurfaceStrokeParams p = s.terrain.strokes;  // the ground's heights and displacement
    p.material = first_material;
    p.detail_threshold = s.materials[first_material].surface.detail_threshold;
    SurfaceParticles strokes, one;
    // A chunk per kContactTrees trees: a chunk is what the frame culls whole when it is off
    // screen or behind the distance circles, so a forest's far feet cost little.
    auto close_chunk = [&] {
        if (strokes.size() == 0) return;
        out.chunk_source.resize(out.chunks.size());
        out.chunks.push_back(std::move(strokes));
        out.chunk_size.push_back(c.size);
        out.chunk_source.push_back({});
        out.chunk_source.back().contact = true;
        strokes = SurfaceParticles();
    };
    for (size_t i = 0; i < feet.size(); ++i) {
        if (i % kContactTrees == 0) close_chunk();
        const TreeFoot& f = feet[i];
        const double r = c.radius * f.scale;
        p.particles_per_cluster =
            std::max(1, static_cast<int>(std::lround(c.touches * f.scale * f.scale)));
        // One cell of side 2 r per tree (cell (i, 0)), moved onto its foot: the tree's index
        // keys its touches.
        const double cell = 2 * r, cx = (static_cast<double>(i) + 0.5) * cell, cz = 0.5 * cell;
        const GroundAt ground = [&](double x, double z, glm::vec3& pos, glm::vec3& n) {
            const double dx = x - cx, dz = z - cz;
            if (pmath::hypot(dx, dz) > r) return false;
            const double wx = f.position.x + dx, wz = f.position.z + dz;
            if (!s.terrain.present) {
                pos = glm::vec3(glm::dvec3(wx, f.position.y, wz));
                n = glm::vec3(0, 1, 0);
                return true;
            }
            return terrain_point(s, wx, wz, 0.1 * r, pos, n);
        };
        one = SurfaceParticles();
        emit_cell_strokes({glm::ivec2(static_cast<int>(i), 0)}, cell, p, s.terrain.seed,
                          kContactKey, ground, one);
        for (size_t k = 0; k < one.size(); ++k) {
            const glm::dvec3 at(one.position[k]);
            const float q = static_cast<float>(
                std::min(1.0, pmath::hypot(at.x - f.position.x, at.z - f.position.z) / r));
            // Thinner towards the rim, by a draw of the label's other digits: no hard edge.
            const float draw = one.label[k] * 4099.0f - std::floor(one.label[k] * 4099.0f);
            if (draw < smoothstep(0.6f, 1.0f, q)) continue;
            one.uv_code[k] = encode_unorm(q);
            // Broad base strokes lying deep at the foot (inside_growth widens them into a
            // pool of shade), the grass's tufts standing only towards the rim.
            one.height_code[k] = encode_unorm(0.3f + 0.5f * q);
            one.material[k] = static_cast<uint16_t>(c.material >= 0 ? first_material
                                                                    : terrain_material_at(s, at));
            strokes.append(one, k, 1);
        }
    }
    close_chunk();
}

BuiltLandscape build_landscape(const SceneDesc& s) {
    BuiltLandscape out;
    build_surfaces(s, out);
    add_meshes(s, out);
    std::vector<TreeFoot> feet;
    for (const PlacedTree& t : s.trees) feet.push_back({t.position, t.scale});
    add_contact(s, feet, out);
    add_imported(s, out);
    add_figures(s, out);
    return out;
}

}  // namespace pleinair
