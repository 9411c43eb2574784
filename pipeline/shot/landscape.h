// The landscape of a scene built once: terrain, water and rock surfaces in world space, and the
// stroke particles the generalized stroke builder emits over them (IV.7).
#pragma once

#include <memory>
#include <vector>

#include "generators/quad_mesh.h"
#include "generators/surface_strokes.h"
#include "generators/terrain.h"
#include "pipeline/input/scene.h"

namespace pleinair {

struct BuiltLandscape {
    bool has_terrain = false, has_water = false;
    QuadMesh terrain_mesh;                // world
    QuadMesh water_mesh;                  // world, flat at the water level
    std::vector<QuadMesh> rocks;          // world: the scene's rocks, then its glTF meshes
    std::vector<uint32_t> rock_material;  // each one's material
    // The strokes in chunks (a band of sections of one surface each, in order): emitted in
    // parallel and painted chunk by chunk, never copied into one array. material: index into
    // SceneDesc::materials.
    std::vector<SurfaceParticles> chunks;
    std::vector<float> chunk_size;  // each chunk's sprite size factor after surface_density
    // The near field's chunk (V.3): smaller detail strokes on the ground wherever the camera
    // comes within its near-field circle; they appear, one by one, as it approaches. None: ~0.
    size_t near_chunk = ~size_t{0};
    // Where each chunk's particles come from: a particle file of the scene (/particles) and the
    // index of the chunk's first particle in it, or nothing (generated here).
    struct ChunkSource {
        const ImportedParticles* file = nullptr;
        size_t first = 0;
        float color_amount = 0;
        bool casts_shadows = false;  // the file's particles cast the sun's shadows
        bool contact = false;        // ground touches about trees' feet (add_contact)
    };
    std::vector<ChunkSource> chunk_source;                           // one per chunk
    std::vector<std::shared_ptr<const ImportedParticles>> imported;  // keeps them alive
    bool is_near(size_t chunk) const { return chunk == near_chunk; }
    size_t stroke_count() const;
    // All strokes in one array (tests and tools; the painter reads the chunks).
    SurfaceParticles all_strokes() const;
};

// Pure in the scene: terrain strokes take their material from noise and the bank mask and are
// dropped under water; water strokes only where the ground lies below the level.
// render.surface_density scales the particles per cluster. A camera with a near field (on
// `camera` or its track's keys) adds the near field's chunk along its path. The particle
// files' strokes come next, in chunks of kImportedChunk, and the figures' last, a chunk each
// (pipeline/shot/figures.h).
BuiltLandscape build_landscape(const SceneDesc& scene);
inline constexpr size_t kImportedChunk = 16384;

// A tree's foot: where its trunk meets the ground, and its scale.
struct TreeFoot {
    glm::dvec3 position{0.0};
    double scale = 1;
};

// The ground touches about trees' feet (SceneDesc::contact): one chunk of strokes of the
// contact's material (or the terrain's at each touch) in a disc about each foot, standing on the
// terrain (or at the foot's height without one), thinning towards the rim; each touch's distance
// from its foot over the disc's radius in its uv's u, which the frame shades by. Keyed by the
// tree's index, so a tree's touches are the same whatever other trees stand. None without a
// material for them.
void add_contact(const SceneDesc& scene, const std::vector<TreeFoot>& feet, BuiltLandscape& out);

// The terrain's material at a world point: the noise picks the second material, a region its
// own, the bank mask the bank's. Strokes and the underpainting agree through it.
uint32_t terrain_material_at(const SceneDesc& scene, const glm::dvec3& world);

// The index in /terrain/regions of the region that paints the ground at a world point (the
// last whose wandering rim holds it), or -1: none, or the bank mask wins.
int terrain_region_at(const SceneDesc& scene, const glm::dvec3& world);

}  // namespace pleinair
