// A scene file (presets/scenes/*.json): camera, sun, background, atmosphere, render settings,
// tree families with their shaders and palettes, and the trees placed in the world.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "generators/figure.h"
#include "generators/rock.h"
#include "generators/scatter.h"
#include "generators/surface_strokes.h"
#include "generators/terrain.h"
#include "generators/tree_params.h"
#include "pipeline/input/camera.h"
#include "pipeline/input/camera_track.h"
#include "pipeline/input/graftal_desc.h"
#include "pipeline/input/particle_files.h"
#include "pipeline/input/settings.h"
#include "shading/cloud_shadow.h"
#include "shading/color.h"
#include "shading/sky.h"
#include "shading/stroke_shader.h"
#include "shading/surface_shader.h"

namespace pleinair {

struct ImposterDesc;  // imposter_desc.h

// Sky and ground as seen from the camera: a gradient by elevation, broken by slow noise so no
// area reads as flat CG. With `canvas` set, one canvas colour instead.
struct Background {
    Color sky_zenith{0.62f, 0.71f, 0.77f};  // sRGB
    Color sky_horizon{0.91f, 0.89f, 0.80f};
    Color ground_horizon{0.66f, 0.64f, 0.47f};
    Color ground_near{0.42f, 0.41f, 0.27f};
    float horizon_softness = 0.02f;  // elevation (sine) over which sky and ground blend
    float texture = 0.06f;           // amplitude of the slow noise on the lightness
    bool canvas = false;
    Color canvas_color{0.86f, 0.82f, 0.72f};
};

// A painted sky: brushed strokes over the background's gradient, at infinity (they follow the
// camera's rotation, never its translation), shaded by sky_sample (shading/sky.h) and painted by
// a stroke shader preset and its palette.
struct SkyDesc {
    bool present = false;
    SkyParams params;
    uint64_t seed = 1;
    std::string shader_name = "corot-sky", palette_name;  // as written
    StrokeShaderParams shader;
    Palette palette;
};

// Distances along the view axis between which atmospheric perspective grows from 0 to 1.
struct Atmosphere {
    float near_distance = 10;
    float far_distance = 200;
    // The distance laid in as one value (issue 52 section 1): every touch's luminance is taken
    // towards L* `value`, by value_pull times smoothstep(value_near, value_far) of its depth, so
    // the far bank, the far shore and the far water read as one mass. value_pull 0: none.
    float value = 60;
    float value_near = 0, value_far = 0;
    float value_pull = 0;
};

// A named look for surface strokes (grass, dirt, rock, water): a stroke shader with IV.7's
// surface section and a palette; materials share palettes (IV.7's material functions).
struct Material {
    std::string name;
    StrokeShaderParams shader;
    SurfaceShaderParams surface;
    Palette palette;
    // The material's style: null paints its strokes; a graftal description (file 000) draws
    // tufts on its surfaces instead, over the underpainting's flat colour.
    std::shared_ptr<const GraftalDesc> graftal;
    std::string style = "strokes";  // as written in the scene
    // Graftal imposters (file 002) on the silhouettes of its rocks and terrain, or null.
    std::shared_ptr<const ImposterDesc> imposters;
    std::string imposters_name;  // as written
    // Trees grown for the family (instancing): its trees are drawn from this many, each placed
    // with its own transform and stroke noise, sharing geometry and particles. 0: every tree
    // grown from its own seed.
    int members = 0;
};

// A disc of the terrain painted with its own material (a meadow, a sandy path, a patch of
// bare earth): IV.7's material chosen by a mask.
struct MaterialRegion {
    glm::dvec2 center{0.0};  // (x, z)
    double radius = 10;
    std::string material_name;
    uint32_t material = 0;
    double density = 1;  // strokes per area over the terrain's; they shrink to keep its cover
};

// The ground: a heightfield turned into strokes. Its material comes from noise (grass and
// dirt on one hillside) and from a mask (the bank just above the water).
// /terrain/height_map: heights from an image (pipeline/input/height_map_io.h).
struct HeightMapDesc {
    bool present = false;
    std::string file;  // relative to the scene's folder
    double low = 0, high = 1;
};

struct TerrainDesc {
    bool present = false;
    HeightMapDesc height_map;  // read into params.height_map with the scene
    uint64_t seed = 1;
    TerrainParams params;
    SurfaceStrokeParams strokes;
    std::string material_name = "grass", second_material_name, bank_material_name;
    uint32_t material = 0;               // index into SceneDesc::materials
    int32_t second_material = -1;        // chosen where noise > material_threshold
    float material_noise_frequency = 6;  // cycles over the terrain
    float material_threshold = 0.62f;
    int32_t bank_material = -1;  // within bank_height above the water
    double bank_height = 0.4;
    std::vector<MaterialRegion> regions;  // discs painted with their own material
};

// Still water: a level plane painted where the ground lies below it.
struct WaterDesc {
    bool present = false;
    double level = 0;
    SurfaceStrokeParams strokes;
    std::string material_name = "water";
    uint32_t material = 0;
    // How much its strokes mirror (pipeline/frame/reflection.h): what they show of the reflected
    // world at grazing angles, scaled down towards the viewer by water's Fresnel reflectance.
    float reflection = 0.85f;
    float ripple = 0.02f;  // how far ripples lean a stroke's mirror normal, towards a random one
    int mirror_rays = 4;   // reflected rays a water stroke averages
    float mirror_saturation = 0.6f;  // share of its saturation a mirrored colour keeps
    // Share of the mirror kept where Fresnel's reflectance falls towards the viewer (0: Fresnel
    // alone): a painter's pond stays a light sheet of sky (reflection.h, set_mirror).
    float silver = 0.0f;
};

struct RockDesc {
    RockParams params;
    uint64_t seed = 1;
    glm::dvec3 position{0.0};     // with a terrain, y is the height above the ground
    SurfaceStrokeParams strokes;  // spans are per face of the rock mesh
    std::string material_name = "rock";
    uint32_t material = 0;
};

// Surfaces from a glTF file (/meshes): the triangles of some of its mesh nodes, painted with a
// material's strokes; they cast and receive shadows and hide what lies behind them, as rocks.
struct MeshFileDesc {
    std::string file;   // relative to the scene's folder
    std::string nodes;  // node names, comma-separated; empty: every mesh node
    glm::dvec3 position{0.0};
    double scale = 1;
    uint64_t seed = 1;
    double density = 0;  // strokes per square world unit; 0: 2 per stroke's square
    double displacement = 0.05;
    std::string material_name = "rock";
    uint32_t material = 0;
    std::shared_ptr<const QuadMesh> mesh;  // world; read with the scene
};

// /camera/gltf: the camera track from a camera node of a glTF file (a shot laid out in Blender).
struct GltfCameraDesc {
    bool present = false;
    std::string file;
    std::string camera;  // node name; empty: the first camera
    double focus_distance = 10;
};

// Trees scattered over the terrain (Poisson disk), a weighted mix of families.
struct TreeGroup {
    ScatterParams params;  // weights: one per entry of `families`
    std::vector<uint32_t> families;
    uint64_t seed = 1;
};

struct Family {
    std::string name;
    std::string preset;  // as written in the scene
    TreeParams params;
    StrokeShaderParams leaf_shader, bark_shader;
    Palette leaf_palette, bark_palette;
    // The crowns' style: null paints leaf strokes; a graftal description draws its graftals at
    // the leaf particles instead (bark stays strokes).
    std::shared_ptr<const GraftalDesc> graftal;
    std::string style = "strokes";
    // Graftal imposters (file 002) on the silhouettes of its trunks and branches, or null.
    std::shared_ptr<const ImposterDesc> imposters;
    std::string imposters_name;  // as written
    // Trees grown for the family (instancing): its trees are drawn from this many, each placed
    // with its own transform and stroke noise, sharing geometry and particles. 0: every tree
    // grown from its own seed.
    int members = 0;
};

// Ground touches about each tree's foot (issue 52 §3): strokes of the ground in a disc around
// the trunk's base, darker towards it and thinning towards the rim, painted over the foot so the
// tree stands in the ground instead of floating on the picture. Documented where parsed.
struct ContactDesc {
    int touches = 60;     // strokes about a tree of scale 1 (scale^2 times as many); 0: none
    double radius = 2.0;  // the disc's radius about a tree of scale 1, world units
    float size = 0.4f;    // the strokes' size over their material's sprite_size
    float shade = 0.8f;   // light the trunk takes from the touches at its foot, fading outwards
    std::string material_name;  // empty: the terrain's own, or a ground material (below)
    int32_t material = -1;      // resolved; -1: the terrain's material at each touch
};

// A figure of the scene's /figures (issue 52 §6): staffage painted in a few touches, standing
// in the world, so every camera sees it and it holds still in motion. Documented where parsed.
struct FigureDesc {
    uint64_t seed = 1;
    glm::dvec3 position{0.0};  // its feet; with a terrain, y is the height above the ground
    FigureParams params;       // its colours are set from those below when the shot is built
    // sRGB, as written: skin, hair (or cap, or kerchief), blouse and sleeves, skirt or legs.
    glm::vec3 skin{0.77f, 0.56f, 0.42f}, hair{0.24f, 0.19f, 0.15f};
    glm::vec3 top{0.83f, 0.80f, 0.71f}, bottom{0.27f, 0.26f, 0.23f};
    std::string material_name;  // empty: the "figure" material (the figure shader preset)
    int32_t material = -1;      // resolved
};

struct PlacedTree {
    uint32_t family = 0;
    uint64_t seed = 1;
    glm::dvec3 position{0.0};
    double rotation = 0;  // about +y, degrees
    double scale = 1;
};

struct SceneDesc {
    std::string description;
    double fps = 24;  // frame N of an animated scene is at (N - 1) / fps seconds
    CameraParams camera_params;
    Camera camera;
    CameraTrack camera_track;    // keys empty: a still, seen from camera_params
    GltfCameraDesc camera_gltf;  // read into camera_track (or camera_params) with the scene
    DistanceCircles circles;     // the camera's; a track's keys override them circle by circle
    glm::dvec3 sun_direction{-0.5, 0.8, 0.4};  // towards the sun, unit
    std::vector<SunKey> sun_track;             // empty: the sun stays at sun_direction
    bool sun_casts_shadows = false;
    CloudShadowParams clouds;  // the clouds' shadows on the land (/sun/clouds)
    WindDesc wind;  // absent (present false): still air
    Background background;
    SkyDesc sky;
    bool has_atmosphere = false;
    Atmosphere atmosphere;
    BuildSettings build;
    RenderSettings render;
    std::vector<Family> families;
    std::vector<PlacedTree> trees;  // explicit trees, then the groups' scattered ones
    size_t explicit_trees = 0;
    std::vector<Material> materials;
    TerrainDesc terrain;
    WaterDesc water;
    std::vector<RockDesc> rocks;
    std::vector<MeshFileDesc> meshes;  // glTF surfaces
    std::vector<TreeGroup> groups;
    std::vector<ParticleFileDesc> particles;  // files of particles from other tools
    ContactDesc contact;
    std::vector<FigureDesc> figures;

    // A camera, a sun or a wind track: frames differ with time (a still camera in the wind has
    // frames too).
    bool animated() const {
        return !camera_track.keys.empty() || !sun_track.empty() || !wind.track.empty();
    }
};

// pleinair's world: every coordinate a scene places (the camera and its track, trees, rocks,
// the terrain, the water, groups) lies within +-kMaxWorldCoordinate units, 100 km at a metre a
// unit. Float positions there are 8 mm apart, finer than any stroke, and a landscape paints
// the same picture there as at the origin (tests/pipeline/landscape_test.cpp); beyond it the
// scene is refused with the key, instead of aborting inside Embree at 1e19.
inline constexpr double kMaxWorldCoordinate = 1e5;

// The material a scene without terrain paints its trees' feet with: its own "grass" if it
// has one, else a material named "ground" added from the grass shader preset. Its index.
uint32_t add_ground_material(SceneDesc& scene, const std::string& source);

// Throws InputError listing every problem (file, JSON pointer, expected, found).
SceneDesc parse_scene(const std::string& text, const std::string& source,
                      const std::vector<std::string>& overrides = {});
SceneDesc load_scene(const std::filesystem::path& file,
                     const std::vector<std::string>& overrides = {});

// Markdown table of every scene key.
std::string scene_reference();

// The /wind keys with the scene's values, as the studio's controls read them (json_params.h's
// tree_key_catalog gives a tree's).
std::string wind_key_catalog(const WindDesc& wind);

}  // namespace pleinair
