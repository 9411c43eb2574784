// Scene files: the key table of the fixed sections (documented where parsed) and the families
// and trees lists, each resolved to presets with errors that name the scene file and key.
#include "pipeline/input/scene.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "generators/rng.h"
#include "pipeline/input/gltf_import.h"
#include "pipeline/input/graftal_io.h"
#include "pipeline/input/height_map_io.h"
#include "pipeline/input/imposter_io.h"
#include "pipeline/input/json_visitors.h"
#include "pipeline/input/limits.h"
#include "pipeline/input/presets.h"
#include "pipeline/input/shader_io.h"

namespace pleinair {

using namespace json_detail;
namespace fs = std::filesystem;

namespace {

template <class V>
void visit_strokes(SurfaceStrokeParams& p, V& v) {
    v.object("strokes", "The generalized stroke builder (IV.7, Fig. 24)", [&] {
        v.integer("particle_spans_u", p.particle_spans_u, {1, 4096},
                  "Sections along u; particles are emitted at random inside each.");
        v.integer("particle_spans_v", p.particle_spans_v, {1, 4096}, "Sections along v.");
        v.integer("particles_per_cluster", p.particles_per_cluster, {1, 4096},
                  "Particles emitted per section.");
        v.number("displacement_height", p.displacement_height, {0, 1e4}, "world units",
                 "Strokes sit up to this far above or below the surface.");
        v.number("fade_length", p.fade_length, {0, 1}, "distance value",
                 "Span over which a detail stroke fades (\"Fadeoff Length\").");
        v.number("fade_length_var", p.fade_length_var, {0, 1}, "",
                 "Gaussian deviation of that span.");
        v.number("min_fade_length", p.min_fade_length, {0, 1}, "",
                 "Shortest span (\"MIN fadeoff length\").");
    });
}

template <class T, class V>
void visit_terrain(T& t, V& v) {
    v.seed("seed", t.seed, "Seeds the terrain's noise and its strokes.");
    auto& p = t.params;
    v.vector2("min", p.min, "world units", "Corner (x, z) of the terrain.");
    v.vector2("max", p.max, "world units", "Opposite corner.");
    v.integer("resolution", p.resolution, {2, 4097}, "Grid points along each side.");
    v.number("base_height", p.base_height, {-1e9, 1e9}, "world units", "Height of the plain.");
    v.number("noise_amplitude", p.noise_amplitude, {0, 1e6}, "world units",
             "Peak-to-peak height of the fractal noise over the hills.");
    v.number("noise_frequency", p.noise_frequency, {0, 1e3}, "1/world unit",
             "Frequency of that noise.");
    v.integer("noise_octaves", p.noise_octaves, {1, 8}, "Octaves of that noise.");
    v.object("height_map",
             "Heights from an image over [min, max] (a survey's, a sculpted ground's), under the "
             "hills and noise (set noise_amplitude 0 for the map alone); absent: none",
             [&] {
                 HeightMapDesc& m = t.height_map;
                 m.present = true;
                 v.require("file");
                 v.text("file", m.file,
                        "One-channel image, relative to the scene's folder: 16-bit PNG or TIFF, or "
                        "float EXR or TIFF. Column 0 lies at min x, row 0 at min z (Blender's top "
                        "view of a glTF scene); its first and last samples at the edges. Set "
                        "resolution to its width to keep every sample.");
                 v.number("low", m.low, {-1e9, 1e9}, "world units",
                          "Height of a 16-bit sample 0, or of a float sample 0.");
                 v.number("high", m.high, {-1e9, 1e9}, "world units",
                          "Height of a 16-bit sample 65535, or of a float sample 1: with low 0 and "
                          "high 1 a float map's values are heights as they stand.");
             });
    v.text("material", t.material_name, "Material of the ground's strokes (/materials).");
    v.text("second_material", t.second_material_name,
           "Material where the noise below is over material_threshold (grass and dirt on one "
           "hillside); empty: none.");
    v.real("material_noise_frequency", t.material_noise_frequency, {0, 1e4}, "cycles",
           "Frequency of the noise that picks the second material, over the terrain.");
    v.real("material_threshold", t.material_threshold, {0, 1}, "",
           "Noise above which the second material is used.");
    v.text("bank_material", t.bank_material_name,
           "Material of the ground within bank_height above the water; empty: none.");
    v.number("bank_height", t.bank_height, {0, 1e6}, "world units", "Height of that bank.");
}

template <class V>
void visit_hill(Hill& h, V& v) {
    v.text("name", h.name, "A name, for the reader of the file.");
    v.vector2("center", h.center, "world units", "(x, z) of the summit.");
    v.number("radius", h.radius, {0, 1e9}, "world units", "Where the hill meets the plain.");
    v.number("height", h.height, {-1e6, 1e6}, "world units",
             "Height of the summit over the plain; negative digs a hollow (a pond).");
}

template <class V>
void visit_region(MaterialRegion& r, V& v) {
    v.vector2("center", r.center, "world units", "(x, z) of the disc.");
    v.number("radius", r.radius, {0, 1e9}, "world units",
             "Its radius; the rim wanders between 0.75 and 1.25 of it, by noise.");
    v.text("material", r.material_name, "Material of the ground's strokes inside it.");
    v.number("density", r.density, {0.25, 16}, "",
             "Its strokes per area over the terrain's, each smaller by the square root so they "
             "cover as much: a near meadow painted in more, smaller touches than the land "
             "beyond (a painter's foreground), without more strokes anywhere else.");
}

template <class V>
void visit_water(WaterDesc& w, V& v) {
    v.number("level", w.level, {-1e9, 1e9}, "world units",
             "Height of the still water; painted where the ground lies below it.");
    v.text("material", w.material_name, "Material of its strokes.");
    v.real("reflection", w.reflection, {0, 1}, "",
           "How much its strokes take the colour of what the water mirrors (terrain, rocks, "
           "trunks, leaf strokes, the sky, each in the atmosphere of the light's whole path, eye "
           "to water to it), by /water/mirror_rays reflected rays a stroke; scaled by water's "
           "Fresnel reflectance, so the water darkens to its own colour towards the viewer. 0: "
           "none, no ray.");
    v.real("ripple", w.ripple, {0, 1}, "",
           "How far ripples lean each stroke's mirror: its normal moves this share of the way "
           "towards the stroke's random direction (0.02 is about a degree: a tree's reflection "
           "stays whole but breaks at its edges).");
    v.integer("mirror_rays", w.mirror_rays, {1, 16},
              "Reflected rays a water stroke averages, each through its own ripple: more keep "
              "its colour from jumping as the camera moves its rays across an edge "
              "(BENCHMARKS.md, \"The Corot look\"), at that many rays' cost.");
    v.real("mirror_saturation", w.mirror_saturation, {0, 1}, "",
           "Share of its saturation a mirrored colour keeps (its luminance kept): paint greys a "
           "reflection, so a green bank lies silver-grey in the water (BENCHMARKS.md, \"A pond "
           "that mirrors\"). 1: the colour as the ray saw it.");
    v.real("silver", w.silver, {0, 1}, "",
           "Share of the mirror the water keeps where Fresnel's reflectance falls towards the "
           "viewer: the reflectance taken this share of the way to 1. Physics darkens near water "
           "to its body's colour; Corot's ponds stay a light, silvery sheet of the sky, the "
           "picture's second light after the sky (issue 52 section 1). 0: Fresnel alone.");
}

template <class V>
void visit_sky(SkyDesc& k, V& v) {
    SkyParams& p = k.params;
    v.text("shader", k.shader_name,
           "Stroke shader preset (name or file) of the sky's strokes: their mask, sub-stroke "
           "colour, aspect (stroke_aspect, length over width) and jitter; its palette, picked by "
           "lightness, holds the sky's colours (dark: shaded cloud, mid: clear sky, light: lit "
           "cloud and haze). Its sprite_size is not read: the sky's is stroke_size here.");
    v.text("palette", k.palette_name, "Palette instead of the shader's; empty: the shader's.");
    v.seed("seed", k.seed, "Seeds where the sky's strokes lie and their labels.");
    v.real("cloud_cover", p.cloud_cover, {0, 1}, "", "Share of the sky in cloud.");
    v.real("cloud_scale", p.cloud_scale, {0.05, 20}, "",
           "Size of the clouds: 1 puts a few across a 45-degree view, 2 doubles them.");
    v.real("cloud_softness", p.cloud_softness, {0.001, 0.5}, "noise",
           "Band of the cloud noise over which a cloud's edge fades into clear sky.");
    v.real("stroke_size", p.stroke_size, {1, 45}, "deg",
           "Angle of sky a base stroke spans along its length; small strokes along cloud edges "
           "are half as long.");
    v.real("detail", p.detail, {0, 1}, "",
           "How many of the small strokes along cloud edges are kept; 0: none.");
    v.real("haze", p.haze, {0.001, 1}, "sine of elevation",
           "Band above the horizon over which clouds thin out and strokes fade into the "
           "background's haze.");
    v.real("sun_glow", p.sun_glow, {0, 1}, "lightness", "Lightness added around the sun.");
    v.real("stroke_jitter", p.stroke_jitter, {0, 1}, "lightness",
           "How much lighter or darker than the sky's field a stroke may be (peak to peak, "
           "the load of paint varying from touch to touch).");
    v.real("jitter_coherence", p.jitter_coherence, {0, 1}, "",
           "Share of stroke_jitter drawn from a field a few strokes across rather than each "
           "stroke's label: neighbouring touches agree and the sky shimmers in patches; 0: each "
           "stroke on its own, which reads as a tiled pattern of same-size dabs.");
    v.real("cloud_masses", p.cloud_masses, {0, 1}, "",
           "How far the cloud cover rises and falls over the sky's large masses, about two "
           "across a 45-degree view: clouds gathered into banks and clear reaches between them "
           "(Corot's few large masses); 0: clouds spread evenly over the sky.");
    v.real("stroke_variety", p.stroke_variety, {0, 2}, "",
           "Strokes' size over the sky, 1 -/+ half this, from a field about ten strokes across: "
           "broad touches in some reaches, finer ones in others; 0: every stroke of stroke_size.");
    v.real("zenith_lightness", p.zenith_lightness, {0, 1}, "lightness",
           "Clear sky straight up (looked up in the palette).");
    v.real("horizon_lightness", p.horizon_lightness, {0, 1}, "lightness",
           "Clear sky at the horizon.");
    v.real("cloud_light", p.cloud_light, {0, 1}, "lightness", "A cloud's side facing the sun.");
    v.real("cloud_shade", p.cloud_shade, {0, 1}, "lightness", "A cloud's side away from it.");
}

template <class V>
void visit_rock(RockDesc& r, V& v) {
    v.seed("seed", r.seed, "Seeds the rock's shape and strokes.");
    v.vector("position", r.position, "world units",
             "Centre; with a terrain, y is the height above the ground.");
    v.number("radius", r.params.radius, {0, 1e6}, "world units", "Size before the squash.");
    v.vector("scale", r.params.scale, "", "Squash along x, y and z.");
    v.number("roughness", r.params.roughness, {0, 0.9}, "",
             "Radial displacement by noise, as a fraction of the radius.");
    v.number("noise_frequency", r.params.noise_frequency, {0, 1e3}, "1/radius",
             "Frequency of that noise.");
    v.integer("subdivision_levels", r.params.subdivision_levels, {0, 5},
              "Catmull-Clark levels of the rock mesh (6 x 4^levels faces).");
    v.text("material", r.material_name, "Material of its strokes.");
}

template <class V>
void visit_mesh_file(MeshFileDesc& m, V& v) {
    v.require("file");
    v.text("file", m.file,
           "A glTF 2.0 file (.glb or .gltf), relative to the scene's folder: its triangles, in "
           "metres with y up as glTF has them, each node's transform applied.");
    v.text("nodes", m.nodes,
           "Names of the mesh nodes to paint, comma-separated; empty: every mesh node of the "
           "file.");
    v.text("material", m.material_name, "Material of their strokes (/materials).");
    v.vector("position", m.position, "world units", "Where the file's origin goes.");
    v.number("scale", m.scale, {1e-6, 1e6}, "", "World units per file unit.");
    v.seed("seed", m.seed, "Seeds the strokes' places.");
    v.number("density", m.density, {0, 1e6}, "1/world unit^2",
             "Strokes per square world unit (before /build/surface_density); 0: two per square "
             "of the material's sprite_size.");
    v.number("displacement", m.displacement, {0, 1e3}, "world units",
             "How far a stroke stands off the surface, up or down along its normal.");
}

const std::pair<UpAxis, const char*> kUpAxes[] = {{UpAxis::kY, "y"}, {UpAxis::kZ, "z"}};

template <class V>
void visit_particle_file(ParticleFileDesc& p, V& v) {
    v.require("file");
    v.text("file", p.file,
           "A PLY file of particles (ASCII or binary, float or double, as Blender, Houdini and "
           "MeshLab write them), relative to the scene's folder. Only its vertices are read.");
    v.text("material", p.material_name,
           "Material (/materials) whose stroke shader and palette paint them (required unless "
           "material_by picks one per particle).");
    v.text("material_by", p.material_by,
           "Integer vertex property whose value picks each particle's material from "
           "`materials` (0 the first): one file paints ground, trunks and several crowns. "
           "Empty: every particle takes `material`.");
    v.text("materials", p.material_list,
           "With material_by: the materials (/materials), comma-separated, that the property's "
           "values 0, 1, 2, ... pick; a value past the list is refused with its vertex.");
    v.boolean("casts_shadows", p.casts_shadows,
              "Whether the particles cast the sun's shadows (when the scene's sun casts them), "
              "as cards facing the sun with their strokes' size and noise, like leaf strokes; "
              "they always receive them.");
    v.choice("up", p.up, kUpAxes,
             "The file's up axis: \"y\" (Houdini, MeshLab) or \"z\" (Blender's, turned so "
             "its z is pleinair's y and its y points away from the camera's default view).");
    v.vector("position", p.position, "world units", "Where the file's origin goes.");
    v.number("scale", p.scale, {1e-6, 1e6}, "", "World units per file unit (positions, sizes).");
    v.text("size", p.size,
           "Vertex property holding each particle's size (Houdini's pscale). Empty: pscale or "
           "radius when the file has one, else the material's sprite_size; \"none\": ignored.");
    v.number("size_to_width", p.size_to_width, {1e-6, 1e6}, "",
             "Stroke width per unit of size: 2 reads the size as a radius (pscale, MeshLab's "
             "radius).");
    v.text("label", p.label,
           "Integer vertex property giving each particle its stable label, so its stroke keeps "
           "its noise when the tool reorders points (Houdini's id). Empty: id when present, "
           "else the vertex index; \"none\": the index.");
    v.text("normal", p.normal,
           "Three vertex properties, comma-separated, holding the normal (Houdini's N and "
           "Blender's normals export as nx,ny,nz). Empty: nx,ny,nz when present, else each "
           "particle faces the sun; \"none\": faces the sun.");
    v.text("color", p.color,
           "Three vertex properties holding the colour (Houdini's Cd). Integer types are sRGB "
           "in their range, floats linear in 0..1. Empty: red,green,blue or r,g,b when "
           "present; \"none\": the palette alone.");
    v.real("color_amount", p.color_amount, {0, 1}, "",
           "How much of a stroke's colour is the file's, painted at the lightness the shader "
           "picks from the palette (so shadows stay painted, never black); 0: the palette's.");
    v.boolean("on_terrain", p.on_terrain,
              "Each particle's y is its height above the terrain at its (x, z), as a tree's "
              "position is: a scatter laid out on flat ground sits on the hills (needs "
              "/terrain). Off: y is the world's.");
}

const std::pair<FigurePose, const char*> kFigurePoses[] = {{FigurePose::kStanding, "standing"},
                                                           {FigurePose::kReaching, "reaching"},
                                                           {FigurePose::kBending, "bending"},
                                                           {FigurePose::kSeated, "seated"}};

template <class V>
void visit_figure(FigureDesc& f, V& v) {
    v.require("position");
    v.seed("seed", f.seed, "Seeds where its touches fall on the body.");
    v.vector("position", f.position, "world units",
             "Where its feet stand; with a terrain, y is the height above the ground.");
    v.choice("pose", f.params.pose, kFigurePoses,
             "\"standing\", \"reaching\" (one arm up into a tree's branches, as the woman "
             "under Mortefontaine's leaning tree), \"bending\" (gathering from the ground) or "
             "\"seated\" (on the ground, knees raised).");
    v.number("height", f.params.height, {0.2, 4}, "world units",
             "Standing height: 1.65 a woman, 1.0-1.3 a child.");
    v.number("facing", f.params.facing, {-360, 360}, "degrees",
             "Turn about +y; 0 faces +z (towards a default camera).");
    v.boolean("dress", f.params.dress, "A long skirt to the ground; false: two legs.");
    v.color("skin", f.skin, "Face and hands.");
    v.color("hair", f.hair, "The head's top and back: hair, a cap or a kerchief.");
    v.color("top", f.top, "Blouse and sleeves.");
    v.color("bottom", f.bottom,
            "Skirt or legs. A small red or orange here or in the cap is the one lively colour "
            "of Corot's late pictures.");
    v.number("stroke_size", f.params.stroke_size, {0.02, 0.3}, "",
             "A touch's width over the height: 0.1 paints a woman in about two hundred "
             "touches, half of them facing away, each limb a few strokes of the brush.");
    v.number("touches", f.params.touches, {0.1, 4}, "",
             "Touches per square of a touch's width of body surface: how densely it is painted.");
    v.text("material", f.material_name,
           "Material whose stroke shader paints it, each touch in its part's colour at the "
           "lightness the material's palette gives it; empty: the \"figure\" material (the "
           "figure shader preset), added when the scene has none.");
}

template <class V>
void visit_group(TreeGroup& g, V& v) {
    ScatterParams& p = g.params;
    v.seed("seed", g.seed, "Seeds the placement and each tree's own seed.");
    v.vector2("center", p.center, "world units", "(x, z) of the disc the trees stand in.");
    v.number("radius", p.radius, {0, 1e7}, "world units", "Radius of that disc.");
    v.number("min_distance", p.min_distance, {1e-3, 1e7}, "world units",
             "Least distance between two trunks (Poisson-disk radius).");
    v.number("max_slope", p.max_slope, {0, 90}, "deg", "No tree on steeper ground.");
    v.number("scale_var", p.scale_var, {0, 1}, "", "Relative size variation (gaussian).");
    v.integer("max_trees", p.max_trees, {0, 100000}, "At most this many trees.");
}

template <class V>
void visit_clearing(Clearing& c, V& v) {
    v.require("from");
    v.vector2("from", c.from, "world units", "(x, z) where the clearing starts.");
    v.vector2("to", c.to, "world units", "(x, z) where it ends; absent: `from` (a round glade).");
    v.number("radius", c.radius, {0, 1e7}, "world units",
             "No trunk stands within this distance of the segment from `from` to `to`.");
}

const std::pair<TrackInterpolation, const char*> kInterpolations[] = {
    {TrackInterpolation::kCatmullRom, interpolation_name(TrackInterpolation::kCatmullRom)},
    {TrackInterpolation::kLinear, interpolation_name(TrackInterpolation::kLinear)},
};

template <class V>
void visit_camera_key(CameraKey& k, V& v) {
    v.require("time");
    v.number("time", k.time, {0, 1e6}, "s",
             "When the camera is here; keys in increasing time (frame F is at (F - 1) / fps).");
    v.require("position");
    v.vector("position", k.position, "world units", "Where the camera stands.");
    v.require("look_at");
    v.vector("look_at", k.look_at, "world units",
             "The point it looks at (not the position); interpolated like the position.");
    v.vector("up", k.up, "", "Up direction; absent: /camera/up. Interpolated, then normalised.");
    v.number("fov", k.fov, {1e-3, 179}, "deg",
             "Vertical field of view; absent: /camera/fov. Interpolated by a monotone cubic in "
             "time, never beyond the two keys it lies between.");
    v.number("ease_in", k.ease_in, {0, 1}, "",
             "Slows the approach to this key: 1 arrives at rest, 0 runs through at the spline's "
             "speed (no velocity jump at the key), values between blend.");
    v.number("ease_out", k.ease_out, {0, 1}, "", "Slows the departure from this key, likewise.");
    v.number("leaf_near", k.leaf_near, {0, 1e9}, "world units",
             "Level-of-detail circle of the leaves, near side; 0: not set. A circle is set on "
             "every key or none, and is interpolated like the fov.");
    v.number("leaf_far", k.leaf_far, {0, 1e9}, "world units",
             "The leaves' far circle; 0: not set; >= leaf_near.");
    v.number("trunk_near", k.trunk_near, {0, 1e9}, "world units",
             "Level-of-detail circle of trunks and branches, near side; 0: not set.");
    v.number("trunk_far", k.trunk_far, {0, 1e9}, "world units",
             "Their far circle; 0: not set; >= trunk_near.");
    v.number("near_field", k.near_field, {0, 1e9}, "world units",
             "The innermost circle, where foliage opens into separate strokes; 0: not set.");
}

// The still camera's circles, which a track's keys override circle by circle.
template <class V>
void visit_circles(DistanceCircles& c, V& v) {
    v.number("leaf_near", c.leaf_near, {0, 1e9}, "world units",
             "Level of detail (IV.6): leaves and surface detail strokes nearer than this, along "
             "the view axis, have full detail.");
    v.number("leaf_far", c.leaf_far, {0, 1e9}, "world units",
             "Beyond this they have the least (a tree keeps its inner leaves, grown to keep its "
             "silhouette); 0: no level of detail for leaves. >= leaf_near.");
    v.number("trunk_near", c.trunk_near, {0, 1e9}, "world units",
             "Trunks and branches nearer than this show every limb's bark strokes.");
    v.number("trunk_far", c.trunk_far, {0, 1e9}, "world units",
             "Beyond this only the low-detail model's (trunk and first branches), cross-faded "
             "between; 0: no level of detail for trunks. >= trunk_near.");
    v.number("near_field", c.near_field, {0, 1e9}, "world units",
             "Nearer than this the foliage opens into separate strokes: interior leaves thin "
             "out and strokes shrink apart (V.3); 0: off.");
}

template <class V>
void visit_sun_key(SunKey& k, V& v) {
    v.require("time");
    v.number("time", k.time, {0, 1e6}, "s", "When the sun is here; keys in increasing time.");
    v.require("direction");
    v.vector("direction", k.direction, "",
             "Direction towards the sun; between keys, along the great circle (slerp).");
}

template <class V>
void visit_wind_key(WindKey& k, V& v) {
    v.require("time");
    v.number("time", k.time, {0, 1e6}, "s", "When the wind is this; keys in increasing time.");
    v.require("strength");
    v.number("strength", k.strength, {0, 60}, "m/s", "Its mean speed then; linear between keys.");
    v.vector("direction", k.direction, "",
             "Where it blows to then (its level part); between keys, along the level arc. "
             "Absent: /wind/direction.");
}

template <class V>
void visit_wind(WindDesc& w, V& v) {
    v.claim("track");
    v.number("strength", w.strength, {0, 60}, "m/s",
             "Mean wind speed: 2-5 a breeze that stirs the leaves, 8-12 a wind that sways limbs "
             "and trunks; bends grow with its square, divided by the tree's /stiffness.");
    v.vector("direction", w.direction, "",
             "Where the wind blows to; its level part (x, z) is used.");
    v.number("gustiness", w.gustiness, {0, 1}, "",
             "Gusts over the mean: 0 steady; 1 from half the mean to twice it.");
    v.number("gust_period", w.gust_period, {0.1, 600}, "s",
             "Time between one gust's value and the next (the gust field's cell in time).");
    v.number("turbulence", w.turbulence, {0.01, 1e6}, "world units",
             "Width across the wind over which gusts are one; downwind they travel at the mean "
             "speed, reaching one tree after another.");
    v.seed("seed", w.seed, "Seeds the gusts and, with each tree's number, its limbs' phases.");
}

const std::pair<ShadowMode, const char*> kShadowModes[] = {
    {ShadowMode::kTransmissive, "transmissive"}, {ShadowMode::kThreshold, "threshold"}};
const std::pair<GraftalRaster, const char*> kGraftalRasters[] = {
    {GraftalRaster::kCairo, "cairo"}, {GraftalRaster::kScanline, "scanline"}};
const std::pair<ShadowSamples, const char*> kShadowSamples[] = {
    {ShadowSamples::kParticle, "particle"}, {ShadowSamples::kFragment, "fragment"}};

template <class V>
void visit_scene(SceneDesc& s, V& v) {
    v.text("description", s.description, "One line on what the scene shows.");
    v.number("fps", s.fps, {1e-3, 1000}, "frames/s",
             "Frames per second of an animated scene (one with a camera, a sun or a wind track): "
             "frame N, counted from 1, is at (N - 1) / fps seconds.");
    CameraParams& c = s.camera_params;
    v.object("camera", "The perspective camera", [&] {
        v.vector("position", c.position, "world units", "Where the camera stands.");
        v.vector("look_at", c.look_at, "world units",
                 "The point it looks at; its distance is the depth where strokes keep their "
                 "size.");
        v.vector("up", c.up, "", "Up direction; if parallel to the view, +z or -x stands in.");
        v.number("fov", c.fov, {1e-3, 179}, "deg", "Vertical field of view.");
        v.integer("width", c.width, {1, 16384}, "Image width in pixels.");
        v.integer("height", c.height, {1, 16384}, "Image height in pixels.");
        visit_circles(s.circles, v);
        v.claim("track");
        v.choice("interpolation", s.camera_track.interpolation, kInterpolations,
                 "How the track runs through its keys: centripetal Catmull-Rom (no loops or "
                 "overshoot at uneven spacing, no velocity jump at a key) or straight lines.");
        v.boolean("constant_speed", s.camera_track.constant_speed,
                  "The camera moves at one speed along the whole track's path, from the first "
                  "key's time to the last's: interior keys are passed through, not at their "
                  "times, and only the first key's ease_out and the last's ease_in apply.");
        v.object("gltf",
                 "The camera and its animation from a glTF file (a shot laid out in Blender and "
                 "exported with its camera): instead of position, look_at, up, fov and track",
                 [&] {
                     GltfCameraDesc& g = s.camera_gltf;
                     g.present = true;
                     v.require("file");
                     v.text("file", g.file,
                            "A .glb or .gltf file, relative to the scene's folder. Frame 1 is its "
                            "first animation sample; at its camera's aspect ratio the frame is "
                            "Blender's, at another the vertical field of view is kept.");
                     v.text("camera", g.camera,
                            "Name of the camera's node; empty: the first node with a camera.");
                     v.number("focus_distance", g.focus_distance, {1e-3, 1e6}, "world units",
                              "How far ahead the camera looks: the depth where strokes keep "
                              "their size (glTF cameras carry none).");
                 });
    });
    v.object("sun", "The one light (IV.4.1)", [&] {
        v.claim("track");
        v.vector("direction", s.sun_direction, "", "Direction towards the sun; normalised.");
        v.boolean("casts_shadows", s.sun_casts_shadows,
                  "Trace shadow rays: trunks, terrain, rocks and the leaf strokes themselves "
                  "cast shadows as brush strokes (IV.4.2). Off: no shadow geometry is built.");
        v.object("clouds",
                 "The shadows of clouds on the land: large patches of light and shade over the "
                 "ground, the trees and the water, standing still over a shot as a painter fixes "
                 "the light on a meadow (issue 52 section 3). Needs no shadow rays; absent: none",
                 [&] {
                     CloudShadowParams& c = s.clouds;
                     v.real("cover", c.cover, {0, 1}, "",
                            "Share of the land in a cloud's shadow; 0: none.");
                     v.real("size", c.size, {1, 1e5}, "world units",
                            "A patch of light or shade's typical width.");
                     v.real("softness", c.softness, {0.001, 1}, "",
                            "Share of the land in a shadow's fading edge: 0.02 a sharp edge, "
                            "0.3 a long penumbra.");
                     v.real("light", c.light, {0, 1}, "",
                            "The sun's light left deep in a shadow, as a cast shadow's: the "
                            "shader's shadow remap keeps it from black.");
                     v.seed("seed", c.seed, "Draws where the patches fall.");
                 });
    });
    v.object("wind",
             "Wind that bends the trees frame by frame, a pure function of time (absent: still "
             "air)",
             [&] {
                 s.wind.present = true;
                 visit_wind(s.wind, v);
             });
    Background& b = s.background;
    v.object("background", "What shows where no stroke covers the canvas", [&] {
        v.color("sky_zenith", b.sky_zenith, "Sky straight up.");
        v.color("sky_horizon", b.sky_horizon, "Sky at the horizon.");
        v.color("ground_horizon", b.ground_horizon, "Ground at the horizon.");
        v.color("ground_near", b.ground_near, "Ground straight down.");
        v.real("horizon_softness", b.horizon_softness, {0, 1}, "sine of elevation",
               "Band over which sky and ground blend.");
        v.real("texture", b.texture, {0, 1}, "", "Slow noise on the background's lightness.");
        v.boolean("canvas", b.canvas, "Paint one canvas colour instead of sky and ground.");
        v.color("canvas_color", b.canvas_color, "The canvas colour.");
    });
    v.object("sky", "A painted sky of brushed strokes over the background; absent: none", [&] {
        s.sky.present = true;
        visit_sky(s.sky, v);
    });
    ContactDesc& ct = s.contact;
    v.object("contact", "Ground touches about each tree's foot, so it stands in the ground", [&] {
        v.integer("touches", ct.touches, {0, 256},
                  "Strokes of the ground about a tree of scale 1 (a tree of scale s takes s^2 "
                  "times as many), laid in a disc about its trunk's base, thinning towards the "
                  "rim; some stand in front of the trunk's foot and cover it, as a painter "
                  "sets a tree in the grass (issue 52); 0: none, the trunk ends on the ground "
                  "as its mesh does.");
        v.number("radius", ct.radius, {0.05, 100}, "world units",
                 "Radius of the disc about a tree of scale 1 (times the tree's scale).");
        v.real("size", ct.size, {0.05, 4}, "",
               "The touches' size over their material's sprite_size: smaller than the ground's "
               "own strokes, as the touches at a tree's foot are.");
        v.real("shade", ct.shade, {0, 1}, "",
               "Share of their lightness the touches at the trunk lose (the crown's and the "
               "trunk's shade at its foot), fading to none at the rim: a dark accent from the "
               "palette's darks, never black.");
        v.text("material", ct.material_name,
               "Material of the touches; empty: the terrain's own at each touch, or without "
               "terrain the scene's \"grass\" material, or else a \"ground\" material of the "
               "grass shader preset.");
    });
    v.object("atmosphere", "Atmospheric perspective (IV.6); absent: none", [&] {
        s.has_atmosphere = true;
        v.real("near", s.atmosphere.near_distance, {0, 1e9}, "world units",
               "View depth where the effect starts.");
        v.real("far", s.atmosphere.far_distance, {0, 1e9}, "world units",
               "View depth where it is full.");
        v.real("value", s.atmosphere.value, {0, 100}, "L*",
               "The distance's one value (Corot's greyish middle distance): what value_pull "
               "takes every far touch's lightness towards, whatever its material or light.");
        v.real("value_near", s.atmosphere.value_near, {0, 1e9}, "world units",
               "View depth where the distance's value starts to take the touches.");
        v.real("value_far", s.atmosphere.value_far, {0, 1e9}, "world units",
               "View depth past which it takes them fully (by value_pull); a smooth step "
               "between, so a touch's value moves continuously as the eye moves.");
        v.real("value_pull", s.atmosphere.value_pull, {0, 1}, "",
               "Share of the way a touch past value_far goes to the distance's value, keeping "
               "its hue: 1 lays the distance in as one flat value, 0 (default) leaves each "
               "touch's own. The values of the whole frame, squinted at, then part into a few "
               "masses instead of a ramp from the near dark to the sky.");
    });
    v.object("terrain", "The ground: hills and noise, painted as strokes (IV.7); absent: none",
             [&] {
                 s.terrain.present = true;
                 visit_terrain(s.terrain, v);
                 v.claim("hills");
                 v.claim("regions");
                 visit_strokes(s.terrain.strokes, v);
             });
    v.object("water", "Still water in the terrain's hollows; absent: none", [&] {
        s.water.present = true;
        visit_water(s.water, v);
        visit_strokes(s.water.strokes, v);
    });
    RenderSettings& r = s.render;
    v.object("render", "Painter settings", [&] {
        v.real("stroke_perspective", r.stroke_perspective, {0, 1}, "",
               "How strokes shrink with distance: 0 keeps their screen size, 1 is true "
               "perspective (thesis ch. I: brush strokes must not shrink like geometry).");
        v.real("min_stroke_px", r.min_stroke_px, {0, 1000}, "px", "Smallest stroke drawn.");
        v.integer("samples", r.samples, {1, 16}, "Stroke-mask samples per pixel: 1, 4 or 16.");
        v.real("one_sample_px", r.one_sample_px, {0, 1000}, "px",
               "Strokes whose narrower half-width on screen is at least this (so at least twice "
               "this across), leaves, bark, ground, rocks and water, take one stroke-mask "
               "sample a pixel, the feather filtered by the pixel's footprint: "
               "their noise's features span several pixels, so the filter stands in for the "
               "samples (BENCHMARKS.md, \"Large strokes at one sample\"); 0: every stroke "
               "takes `samples`.");
        v.real("sky_one_sample_px", r.sky_one_sample_px, {0, 1000}, "px",
               "Painted sky strokes at least this wide on screen (their narrower half-width) "
               "take one stroke-mask sample a pixel, the feather filtered by the pixel's "
               "footprint: large and soft, they need no more (BENCHMARKS.md, \"The sky's large "
               "strokes at one sample\"); 0: every sky stroke takes `samples`.");
        v.integer("octaves", r.octaves, {1, 8}, "Octaves of the stroke noise.");
        v.boolean("palette_lut", r.palette_lut,
                  "Tabulate each sprite's colours (palette, tint, atmosphere) against its "
                  "sub-stroke noise at 17 points instead of evaluating them per fragment.");
        v.boolean("filter_strokes", r.filter_strokes,
                  "At 1 sample per pixel, widen each stroke's feather by the pixel's footprint "
                  "in noise space (RenderMan's filterwidth) against aliasing.");
        v.boolean("edge_lut", r.edge_lut,
                  "Read the stroke edge mask from a 256-entry table instead of sin and pow.");
        v.real("bark_coverage", s.build.bark_coverage, {0, 100}, "",
               "Bark strokes' total area over the area of the limbs' render mesh.");
        v.choice("graftal_raster", r.graftal_raster, kGraftalRasters,
                 "Who draws graftals into their patches: \"scanline\" (pleinair's signed-area "
                 "coverage) or \"cairo\" (the library, the reference: frames 1.3-1.5x slower; "
                 "BENCHMARKS.md, \"Graftals\").");
        v.choice("shadows", r.shadows, kShadowModes,
                 "How leaf strokes shadow: \"transmissive\" (light dimmed by every stroke crossed) "
                 "or \"threshold\" (a stroke blocks where its mask is over one half).");
        v.choice("shadow_samples", r.shadow_samples, kShadowSamples,
                 "Where shadow rays start: \"particle\" (one per particle, the whole stroke shares "
                 "it) or \"fragment\" (a 4 x 4 grid over each sprite, interpolated per fragment, "
                 "16 times the rays; colours then come from the palette per fragment).");
        v.real("underpaint_scale", r.underpaint_scale, {0.05, 1}, "",
               "Resolution of the underpainting (flat colour under the strokes) over the "
               "image's.");
        v.color("underpaint_tone", r.underpaint_tone,
                "Colour of the lay-in under the strokes (sRGB): Corot's warm, translucent "
                "brown underpaint over everything but the sky, which shows where the touches "
                "leave the ground open and through their thin edges (issue 52).");
        v.real("underpaint_tone_amount", r.underpaint_tone_amount, {0, 1}, "",
               "How far the underpainting's flat colour of each surface (its palette's middle "
               "value in its light) is taken towards underpaint_tone, before the atmosphere, so "
               "a far surface's lay-in still goes into the haze; still water keeps its mirror. "
               "0: the surfaces' own colours.");
        v.real("coverage_cutoff", r.coverage_cutoff, {0, 0.1}, "",
               "Strokes are composited nearest first; once less than this much light is left at "
               "a pixel, the strokes behind are skipped there (each changes it by less than "
               "this, in linear colour). 0 paints every stroke.");
        v.boolean("level_of_detail", r.level_of_detail,
                  "Follow the camera's distance circles (IV.6); false paints every tree at full "
                  "detail whatever the circles, to compare.");
        v.real("fade_gain", r.fade_gain, {0.01, 0.99}, "",
               "Perlin gain on each leaf's and stroke's level-of-detail fade: above 0.5 it eases "
               "in and out (the thesis's \"slight gain\"), 0.5 is linear.");
        v.real("max_leaf_growth", r.max_leaf_growth, {1, 10}, "",
               "Most a surviving leaf stroke grows (linear size) to keep its tree's coverage "
               "as outer leaves fade.");
        v.real("thin_below_px", r.thin_below_px, {0, 1000}, "px",
               "With the level of detail: strokes drawn narrower than this on screen are thinned "
               "out at random (each by its own draw, fading in as it grows) and the survivors "
               "grown to keep the area they all covered (Cook et al. 2007's stochastic "
               "pruning): fewer, larger strokes for a small or preview frame, cheaper to make "
               "and paint (BENCHMARKS.md, \"Frames that cost what they show\"); 0 thins none. "
               "The default, twice min_stroke_px's, keeps about a third of the smallest strokes.");
        v.real("thin_max_growth", r.thin_max_growth, {1, 10}, "",
               "Most a thinned stroke's survivor grows (linear size); past it strokes thin "
               "without keeping all their area (growth past about 2x reads as balloon leaves).");
        v.real("order_blend_frames", r.order_blend_frames, {0, 48}, "",
               "Strokes are painted in order of distance from the eye. When the camera moves and "
               "two overlapping strokes' distances cross, they blend from one order to the other "
               "over this many frames instead of swapping in one (a pop, thesis V.3); 0 swaps at "
               "once. A still camera is unaffected.");
        v.integer("occlusion_frames", r.occlusion_frames, {1, 8},
                  "A stroke partly or wholly behind an opaque surface (a crest, a trunk) is drawn "
                  "by the share of rays towards the eye that reach it (where the frame plan "
                  "draws occlusion maps, each camera's map answers first, a ray a stroke only "
                  "where it is unsure). When the camera moves, the "
                  "rays go to where the eye is over this many frames around the frame's time, so "
                  "a stroke a silhouette uncovers or hides appears or disappears over that many "
                  "frames instead of in one (each frame changes it by at most 1 / this); 1 casts "
                  "them at the frame's time only. A still camera is unaffected.");
        v.integer("reflection_frames", r.reflection_frames, {1, 16},
                  "While the camera moves, a water stroke traces its mirror (/water/mirror_rays "
                  "rays) from where the eye is every this many frames, each stroke at its own "
                  "frames, and takes the colour in between linearly: a frame traces this share "
                  "of the mirrors, and a reflection cannot jump from one frame to the next. 1 "
                  "traces every stroke from the frame's own eye. A still camera, or a moving "
                  "sun, traces every frame.");
        v.boolean("pigment_mixing", r.pigment_mixing,
                  "Mix overlapping strokes as paint (Kubelka-Munk pigments in a latent space, "
                  "after Sochorova and Jamriska 2021): a thin yellow over a blue turns green "
                  "where alpha blending in linear RGB turns it grey. Costs a table of about a "
                  "second per process and more per fragment (BENCHMARKS.md, \"Pigment\").");
        v.real("canvas_weave", r.canvas_weave, {0, 1}, "",
               "A canvas weave in the picture plane that shows through where paint is thin and "
               "catches the strokes' soft edges; its strength, 0: none.");
        v.real("canvas_thread_px", r.canvas_thread_px, {3, 64}, "px",
               "Width of one canvas thread (3 at least: a thread needs its crown and two sides).");
        v.real("surface_density", s.build.surface_density, {0.05, 16}, "",
               "Surface particles per cluster, relative to the scene's; sprites shrink so the "
               "covered area stays the same.");
    });
}

uint64_t read_seed(const json& v, const std::string& ptr, std::vector<Problem>& problems) {
    if (!v.is_number_integer() && !v.is_number_unsigned()) {
        problems.push_back({ptr, "expected a whole number >= 0, got " + describe(v)});
        return 0;
    }
    if (v.is_number_integer() && !v.is_number_unsigned() && v.get<int64_t>() < 0) {
        problems.push_back({ptr, "expected a whole number >= 0, got " + describe(v)});
        return 0;
    }
    return v.get<uint64_t>();
}

// Loads a preset named at the scene's key `ptr`. A problem inside the preset file becomes a
// problem of that key whose message names the file and its own key, so one line says both.
template <class Fn>
void load_into(std::vector<Problem>& problems, const std::string& source, const std::string& ptr,
               Fn&& fn) {
    try {
        fn();
    } catch (const InputError& e) {
        for (const auto& p : e.problems()) {
            if (e.source() == source)
                problems.push_back(p);
            else
                problems.push_back({ptr, e.source() + (p.pointer.empty() ? "" : ": " + p.pointer) +
                                             ": " + p.message});
        }
    }
}

// A file named in a scene is relative to the scene's folder, as a user writing one expects;
// bare names are presets.
std::string near_scene(const std::string& name, const std::string& source) {
    bool is_file = name.find('/') != std::string::npos || name.ends_with(".json");
    std::filesystem::path p(name);
    if (!is_file || p.is_absolute() || !source.ends_with(".json")) return name;
    return (std::filesystem::path(source).parent_path() / p).string();
}

// A data file a scene names (a particle file, a height map, a glTF file): relative to the
// scene's folder when the scene is a file.
fs::path beside_scene(const std::string& name, const std::string& source) {
    fs::path file(name);
    if (file.is_relative() && source.ends_with(".json"))
        file = fs::path(source).parent_path() / file;
    return file;
}

// A family's or material's style: "strokes" (null), or a graftal description by name or file.
std::shared_ptr<const GraftalDesc> load_style(const std::string& style, const std::string& source,
                                              const std::string& ptr,
                                              std::vector<Problem>& problems) {
    if (style == "strokes") return nullptr;
    std::shared_ptr<const GraftalDesc> out;
    load_into(problems, source, ptr, [&] {
        out = std::make_shared<const GraftalDesc>(
            load_graftal(near_scene(style, source), source, ptr));
    });
    return out;
}

// Graftal imposters on a family's limbs or a material's surfaces: none (""), or a description
// by name or file.
std::shared_ptr<const ImposterDesc> load_imposters(const std::string& name,
                                                   const std::string& source,
                                                   const std::string& ptr,
                                                   std::vector<Problem>& problems) {
    if (name.empty()) return nullptr;
    std::shared_ptr<const ImposterDesc> out;
    load_into(problems, source, ptr, [&] {
        out = std::make_shared<const ImposterDesc>(
            load_imposter(near_scene(name, source), source, ptr));
    });
    return out;
}

// Index of the material called `name`, or a problem at `ptr` naming those there are.
int32_t find_material(const SceneDesc& s, const std::string& name, const std::string& ptr,
                      std::vector<Problem>& problems) {
    for (size_t i = 0; i < s.materials.size(); ++i)
        if (s.materials[i].name == name) return static_cast<int32_t>(i);
    std::string names;
    for (const auto& m : s.materials) names += (names.empty() ? "" : ", ") + m.name;
    problems.push_back({ptr, "no material \"" + name + "\" in /materials (have: " +
                                 (names.empty() ? "none" : names) + ")"});
    return -1;
}

// A family's edits of its presets (`tree`, `leaf_shader_keys`, `bark_shader_keys`) and a
// material's of its shader (`shader_keys`): an object
// laid out as the preset file, turned into the preset's "POINTER=VALUE" overrides, one per
// value that is not an object (a gaussian parameter's {"base", "var"} is two).
void flatten_edits(const json& v, const std::string& ptr, std::vector<std::string>& out) {
    if (v.is_object() && !v.empty()) {
        for (const auto& [key, child] : v.items())
            flatten_edits(child, ptr + "/" + pointer_token(key), out);
        return;
    }
    out.push_back(ptr + "=" + v.dump());
}

// Reads the family's (or material's) edit object `key` (absent: none) into preset overrides.
std::vector<std::string> preset_edits(const json& f, const char* key, const std::string& ptr,
                                      std::vector<Problem>& problems) {
    std::vector<std::string> edits;
    const auto it = f.find(key);
    if (it == f.end()) return edits;
    if (!it->is_object()) {
        problems.push_back({ptr + "/" + key,
                            "expected an object of the preset's keys, laid out "
                            "as its file, got " +
                                describe(*it)});
        return edits;
    }
    for (const auto& [k, child] : it->items()) flatten_edits(child, "/" + pointer_token(k), edits);
    return edits;
}

// Runs fn (which loads a preset with `edits` as overrides). A problem at an edited key is the
// scene's own, at ptr + that key (the user wrote it here); any other is the preset file's,
// named at `file_ptr` as load_into names it.
template <class Fn>
void load_edited(std::vector<Problem>& problems, const std::string& source,
                 const std::string& file_ptr, const std::string& edit_ptr,
                 const std::vector<std::string>& edits, Fn&& fn) {
    try {
        fn();
    } catch (const InputError& e) {
        static const std::string kMark = " (set by --set)";
        for (const auto& p : e.problems()) {
            if (e.source() == source) {  // the scene's own key (a preset name not found)
                problems.push_back(p);
                continue;
            }
            bool edited = false;
            for (const auto& o : edits)
                edited = edited || p.pointer.starts_with(o.substr(0, o.find('=')));
            if (p.pointer.starts_with("--set")) edited = true;
            std::string message = p.message;
            if (message.ends_with(kMark)) message.resize(message.size() - kMark.size());
            if (edited)
                problems.push_back(
                    {edit_ptr + (p.pointer.starts_with("--set") ? "" : p.pointer), message});
            else
                problems.push_back(
                    {file_ptr,
                     e.source() + (p.pointer.empty() ? "" : ": " + p.pointer) + ": " + p.message});
        }
    }
}

// A shader preset read with a family's or material's edits of it (`edit_key`, laid out as the
// file), its problems named as load_edited names them; false (the problems added) if it could
// not be read.
bool load_edited_shader(std::vector<Problem>& problems, const std::string& source,
                        const std::string& name, const std::string& ptr,
                        const std::string& edit_ptr, const std::vector<std::string>& edits,
                        ShaderPreset& out) {
    bool loaded = false;
    load_edited(problems, source, ptr, edit_ptr, edits, [&] {
        out = load_shader_preset(near_scene(name, source), source, ptr, edits);
        loaded = true;
    });
    return loaded;
}

// Materials, terrain, water and rocks: the landscape under the trees (IV.7).
void parse_landscape(const json& doc, const std::string& source, SceneDesc& s,
                     std::vector<Problem>& problems, std::set<std::string>& plain) {
    if (auto it = doc.find("materials"); it != doc.end()) {
        if (!it->is_object()) {
            problems.push_back(
                {"/materials", "expected an object of materials, got " + describe(*it)});
        } else {
            for (const auto& [name, m] : it->items()) {
                std::string ptr = "/materials/" + pointer_token(name);
                if (!m.is_object()) {
                    problems.push_back({ptr, "expected an object, got " + describe(m)});
                    continue;
                }
                std::string shader, palette;
                Material mat;
                Reader r(m, problems, plain, ptr);
                r.check_ranges();
                r.text("shader", shader, "");
                r.text("palette", palette, "");
                r.text("style", mat.style, "");
                r.text("imposters", mat.imposters_name, "");
                r.claim("shader_keys");
                r.finish();
                // Edits of the shader preset laid out as its file, as a family's
                // leaf_shader_keys: one scene's haze or stroke size without a new preset.
                const std::vector<std::string> edits =
                    preset_edits(m, "shader_keys", ptr, problems);
                mat.name = name;
                mat.graftal = load_style(mat.style, source, ptr + "/style", problems);
                mat.imposters =
                    load_imposters(mat.imposters_name, source, ptr + "/imposters", problems);
                if (shader.empty()) {
                    problems.push_back({ptr + "/shader", "missing: a shader preset name or file"});
                    s.materials.push_back(std::move(mat));
                    continue;
                }
                load_into(problems, source, ptr + "/shader", [&] {
                    ShaderPreset sp;
                    if (!load_edited_shader(problems, source, shader, ptr + "/shader",
                                            ptr + "/shader_keys", edits, sp))
                        return;
                    if (!sp.has_surface)
                        throw InputError(source, ptr + "/shader",
                                         "shader \"" + shader +
                                             "\" has no \"surface\" section; surface materials "
                                             "need one");
                    mat.shader = sp.params;
                    mat.surface = sp.surface;
                    std::string pal = palette.empty() ? sp.palette : palette;
                    if (pal.empty())
                        throw InputError(source, ptr + "/palette",
                                         "the shader names no palette; give one here");
                    load_into(problems, source, ptr + "/palette", [&] {
                        mat.palette = shader_palette(
                            load_palette(near_scene(pal, source), source, ptr + "/palette"),
                            mat.shader);
                    });
                });
                s.materials.push_back(std::move(mat));
            }
        }
    }
    auto material = [&](const std::string& name, const std::string& ptr) {
        return static_cast<uint32_t>(std::max(0, find_material(s, name, ptr, problems)));
    };

    if (s.terrain.present) {
        TerrainDesc& t = s.terrain;
        for (int k = 0; k < 2; ++k)
            if (!(t.params.max[k] > t.params.min[k]))
                problems.push_back({"/terrain/max", std::string("must be greater than "
                                                                "/terrain/min in x and z; in ") +
                                                        (k == 0 ? "x" : "z") + " " +
                                                        format_number(t.params.max[k]) +
                                                        " is not > " +
                                                        format_number(t.params.min[k])});
        const json& tj = doc["terrain"];
        read_list(tj, "hills", "/terrain/hills", problems, plain,
                  [&](const json&, Reader& r, const std::string&) {
                      Hill hill;
                      visit_hill(hill, r);
                      t.params.hills.push_back(hill);
                  });
        read_list(tj, "regions", "/terrain/regions", problems, plain,
                  [&](const json&, Reader& r, const std::string& ptr) {
                      MaterialRegion region;
                      visit_region(region, r);
                      region.material = material(region.material_name, ptr + "/material");
                      t.regions.push_back(region);
                  });
        t.material = material(t.material_name, "/terrain/material");
        if (!t.second_material_name.empty())
            t.second_material =
                find_material(s, t.second_material_name, "/terrain/second_material", problems);
        if (!t.bank_material_name.empty())
            t.bank_material =
                find_material(s, t.bank_material_name, "/terrain/bank_material", problems);
    }
    if (s.water.present) {
        if (!s.terrain.present) problems.push_back({"/water", "water needs a /terrain to lie in"});
        s.water.material = material(s.water.material_name, "/water/material");
    }

    read_list(doc, "rocks", "/rocks", problems, plain,
              [&](const json&, Reader& r, const std::string& ptr) {
                  RockDesc rock;
                  rock.strokes.particle_spans_u = rock.strokes.particle_spans_v = 1;
                  rock.strokes.particles_per_cluster = 3;
                  visit_rock(rock, r);
                  visit_strokes(rock.strokes, r);
                  const glm::dvec3 sc = rock.params.scale;
                  if (!(sc.x > 0 && sc.y > 0 && sc.z > 0 && std::isfinite(sc.x + sc.y + sc.z)))
                      problems.push_back(
                          {ptr + "/scale", "expected three finite numbers > 0, got [" +
                                               format_number(sc.x) + ", " + format_number(sc.y) +
                                               ", " + format_number(sc.z) + "]"});
                  if (!(rock.params.radius > 0))
                      problems.push_back({ptr + "/radius",
                                          "must be > 0, got " + format_number(rock.params.radius)});
                  rock.material = material(rock.material_name, ptr + "/material");
                  s.rocks.push_back(rock);
              });

    read_list(doc, "figures", "/figures", problems, plain,
              [&](const json&, Reader& r, const std::string& ptr) {
                  FigureDesc f;
                  visit_figure(f, r);
                  if (!f.material_name.empty())
                      f.material = material(f.material_name, ptr + "/material");
                  s.figures.push_back(f);
              });

    read_list(doc, "meshes", "/meshes", problems, plain,
              [&](const json&, Reader& r, const std::string& ptr) {
                  MeshFileDesc m;
                  visit_mesh_file(m, r);
                  m.material = material(m.material_name, ptr + "/material");
                  s.meshes.push_back(m);
              });

    read_list(
        doc, "particles", "/particles", problems, plain,
        [&](const json&, Reader& r, const std::string& ptr) {
            ParticleFileDesc p;
            visit_particle_file(p, r);
            if (!p.material_name.empty()) p.material = material(p.material_name, ptr + "/material");
            if (!p.material_list.empty())
                for (const std::string& name : split_names(p.material_list))
                    p.materials.push_back(material(name, ptr + "/materials"));
            if (!p.material_by.empty() && p.materials.empty())
                problems.push_back({ptr + "/materials",
                                    "expected the materials material_by picks from, "
                                    "comma-separated"});
            if (p.material_by.empty() && p.material_name.empty())
                problems.push_back({ptr + "/material",
                                    "required (or material_by and materials, one per particle)"});
            // Property names: one for a size or a label, three for a normal or a colour.
            auto names = [&](const char* key, const std::string& v, size_t n) {
                if (v.empty() || v == "none") return;
                const size_t got = static_cast<size_t>(std::count(v.begin(), v.end(), ',')) + 1;
                if (got != n)
                    problems.push_back(
                        {ptr + "/" + key,
                         "expected " +
                             std::string(n == 1 ? "one property name"
                                                : "three property names, comma-separated") +
                             ", \"none\" or \"\", got \"" + v + "\""});
            };
            names("size", p.size, 1), names("label", p.label, 1);
            names("normal", p.normal, 3), names("color", p.color, 3);
            s.particles.push_back(p);
        });
}

// The glTF files read now: the meshes' triangles, and the camera's track.
void load_gltf_files(const std::string& source, SceneDesc& s, std::vector<Problem>& problems) {
    for (size_t i = 0; i < s.meshes.size(); ++i) {
        MeshFileDesc& m = s.meshes[i];
        const std::string ptr = "/meshes/" + std::to_string(i) + "/file";
        load_into(problems, source, ptr, [&] {
            const auto doc = load_gltf(beside_scene(m.file, source), source, ptr);
            std::vector<std::string> nodes;
            for (const std::string& n : split_names(m.nodes))
                if (!n.empty()) nodes.push_back(n);
            m.mesh = std::make_shared<const QuadMesh>(
                gltf_triangles(*doc, nodes, m.position, m.scale, source, ptr));
        });
    }
    const GltfCameraDesc& g = s.camera_gltf;
    if (!g.present) return;
    const std::string ptr = "/camera/gltf/file";
    load_into(problems, source, ptr, [&] {
        const auto doc = load_gltf(beside_scene(g.file, source), source, ptr);
        CameraTrack track = gltf_camera_track(*doc, g.camera, g.focus_distance, s.fps, source, ptr);
        if (track.keys.size() == 1) {
            // A camera that does not move is a still.
            const CameraKey& k = track.keys[0];
            s.camera_params.position = k.position, s.camera_params.look_at = k.look_at;
            s.camera_params.up = k.up, s.camera_params.fov = k.fov;
            return;
        }
        for (CameraKey& k : track.keys) {
            k.leaf_near = k.leaf_far = k.trunk_near = k.trunk_far = k.near_field = 0;
        }
        auto found = validate_track(track, ptr);
        if (!found.empty()) throw InputError(source, found);
        s.camera_track = std::move(track);
    });
}

// The terrain's height map read now, before anything stands on the ground.
void load_height_map(const std::string& source, SceneDesc& s, std::vector<Problem>& problems) {
    const HeightMapDesc& m = s.terrain.height_map;
    if (!s.terrain.present || !m.present) return;
    const fs::path file = beside_scene(m.file, source);
    load_into(problems, source, "/terrain/height_map/file", [&] {
        s.terrain.params.height_map = std::make_shared<const HeightMap>(
            read_height_map(file, m.low, m.high, source, "/terrain/height_map/file"));
    });
}

// Each particle file read and turned into strokes now, so a broken file is refused with the
// scene, before any work (the strokes are shared by every copy of the scene).
void load_particle_files(const std::string& source, SceneDesc& s, std::vector<Problem>& problems) {
    for (size_t i = 0; i < s.particles.size(); ++i) {
        ParticleFileDesc& p = s.particles[i];
        const std::string ptr = "/particles/" + std::to_string(i) + "/file";
        const fs::path file = beside_scene(p.file, source);
        load_into(problems, source, ptr, [&] {
            const std::string data = read_input_file(file, "particle_file_mb");
            ImportedParticles in =
                import_particles(data, file.string(), p, hash_keys(0x706c79, i),
                                 glm::vec3(s.sun_direction), kMaxWorldCoordinate);
            if (p.on_terrain && !s.terrain.present)
                throw InputError(source, "/particles/" + std::to_string(i) + "/on_terrain",
                                 "needs a /terrain to stand on");
            if (p.on_terrain)
                for (glm::vec3& q : in.strokes.position)
                    q.y += static_cast<float>(
                        terrain_height(s.terrain.params, s.terrain.seed, q.x, q.z));
            p.particles = std::make_shared<const ImportedParticles>(std::move(in));
        });
    }
}

// The camera's and the sun's tracks (`/camera/track`, `/sun/track`): lists of keys, each read
// by its key table; a track whose keys could all be read is then validated as a whole.
void parse_tracks(const json& doc, SceneDesc& s, std::vector<Problem>& problems,
                  std::set<std::string>& plain) {
    auto track_of = [&](const char* object) -> const json* {
        auto it = doc.find(object);
        if (it == doc.end() || !it->is_object()) return nullptr;
        auto track = it->find("track");
        return track == it->end() ? nullptr : &*track;
    };
    // Every element an object with its required keys: then the track's own checks make sense.
    auto complete = [](const json& list, std::initializer_list<const char*> required) {
        if (!list.is_array()) return false;
        for (const json& j : list) {
            if (!j.is_object()) return false;
            for (const char* key : required)
                if (!j.contains(key)) return false;
        }
        return true;
    };
    if (s.camera_gltf.present && track_of("camera"))
        problems.push_back({"/camera/track", "a camera from /camera/gltf brings its own track"});
    if (const json* list = track_of("camera")) {
        read_list(doc.at("camera"), "track", "/camera/track", problems, plain,
                  [&](const json&, Reader& r, const std::string&) {
                      CameraKey key;
                      key.up = s.camera_params.up;
                      key.fov = s.camera_params.fov;
                      visit_camera_key(key, r);
                      s.camera_track.keys.push_back(key);
                  });
        if (complete(*list, {"time", "position", "look_at"})) {
            auto found = validate_track(s.camera_track, "/camera/track");
            problems.insert(problems.end(), found.begin(), found.end());
            if (found.empty())
                for (CameraKey& k : s.camera_track.keys) k.up = glm::normalize(k.up);
        }
    }
    if (const json* list = track_of("wind")) {
        read_list(doc.at("wind"), "track", "/wind/track", problems, plain,
                  [&](const json& j, Reader& r, const std::string&) {
                      WindKey key;
                      key.direction = s.wind.direction;
                      key.own_direction = j.is_object() && j.contains("direction");
                      visit_wind_key(key, r);
                      s.wind.track.push_back(key);
                  });
        if (complete(*list, {"time", "strength"})) {
            auto found = validate_wind_track(s.wind.track, "/wind/track");
            problems.insert(problems.end(), found.begin(), found.end());
        }
    }
    if (const json* list = track_of("sun")) {
        read_list(doc.at("sun"), "track", "/sun/track", problems, plain,
                  [&](const json&, Reader& r, const std::string&) {
                      SunKey key;
                      visit_sun_key(key, r);
                      s.sun_track.push_back(key);
                  });
        if (complete(*list, {"time", "direction"})) {
            auto found = validate_sun_track(s.sun_track, "/sun/track");
            problems.insert(problems.end(), found.begin(), found.end());
            if (found.empty())
                for (SunKey& k : s.sun_track) k.direction = glm::normalize(k.direction);
        }
    }
}

// Groups scattered over the terrain; each names families with weights.
void parse_groups(const json& doc, SceneDesc& s, std::vector<Problem>& problems,
                  std::set<std::string>& plain) {
    if (doc.contains("groups") && !s.terrain.present)
        problems.push_back({"/groups", "tree groups need a /terrain"});
    read_list(doc, "groups", "/groups", problems, plain,
              [&](const json& j, Reader& r, const std::string& ptr) {
                  TreeGroup g;
                  g.params.weights.clear();
                  visit_group(g, r);
                  r.claim("families");
                  r.claim("clearings");
                  read_list(j, "clearings", ptr + "/clearings", problems, plain,
                            [&](const json& cj, Reader& cr, const std::string&) {
                                Clearing c;
                                visit_clearing(c, cr);
                                if (!cj.contains("to")) c.to = c.from;
                                g.params.clearings.push_back(c);
                            });
                  auto fam = j.find("families");
                  if (fam == j.end() || !fam->is_object() || fam->empty()) {
                      problems.push_back({ptr + "/families",
                                          "expected an object of family names to weights, e.g. "
                                          "{\"oak\": 2, \"poplar\": 1}"});
                      return;
                  }
                  for (const auto& [name, w] : fam->items()) {
                      std::string fptr = ptr + "/families/" + pointer_token(name);
                      if (!w.is_number() || !(w.get<double>() >= 0)) {
                          problems.push_back({fptr, "expected a weight >= 0, got " + describe(w)});
                          continue;
                      }
                      bool found = false;
                      for (size_t k = 0; k < s.families.size(); ++k)
                          if (s.families[k].name == name) {
                              g.families.push_back(static_cast<uint32_t>(k));
                              g.params.weights.push_back(w.get<double>());
                              found = true;
                          }
                      if (!found)
                          problems.push_back({fptr, "no family \"" + name + "\" in /families"});
                  }
                  const double cells = scatter_grid_cells(g.params);
                  if (!(cells <= kMaxScatterCells))
                      problems.push_back(
                          {ptr + "/min_distance",
                           "too small for the radius: the Poisson-disk grid would have " +
                               std::to_string(static_cast<uint64_t>(std::min(cells, 1e18))) +
                               " cells (the limit is " +
                               std::to_string(static_cast<uint64_t>(kMaxScatterCells)) +
                               "); raise min_distance or split the group"});
                  // No tree with its feet in the water.
                  if (s.water.present) g.params.water_level = s.water.level + 0.05;
                  if (!g.families.empty()) s.groups.push_back(std::move(g));
              });
}

// Families: an object of name -> {preset, leaf_shader, bark_shader, leaf_palette?, ...}.
void parse_families(const json& doc, const std::string& source, SceneDesc& s,
                    std::vector<Problem>& problems, std::set<std::string>& plain) {
    auto fam = doc.find("families");
    if (fam != doc.end() && !fam->is_object())
        problems.push_back({"/families", "expected an object of families, got " + describe(*fam)});
    if (fam != doc.end() && fam->is_object()) {
        for (const auto& [name, f] : fam->items()) {
            std::string ptr = "/families/" + pointer_token(name);
            if (!f.is_object()) {
                problems.push_back({ptr, "expected an object, got " + describe(f)});
                continue;
            }
            Family family;
            family.name = name;
            std::string leaf_shader = "corot-leaves", bark_shader = "corot-bark";
            std::string leaf_palette, bark_palette;
            Reader r(f, problems, plain, ptr);
            r.check_ranges();
            r.text("preset", family.preset, "");
            r.text("leaf_shader", leaf_shader, "");
            r.text("bark_shader", bark_shader, "");
            r.text("leaf_palette", leaf_palette, "");
            r.text("bark_palette", bark_palette, "");
            r.text("style", family.style, "");
            r.text("imposters", family.imposters_name, "");
            r.integer("members", family.members, {0, 1000000}, "");
            r.claim("tree");
            r.claim("leaf_shader_keys");
            r.claim("bark_shader_keys");
            r.finish();
            const std::vector<std::string> tree_edits = preset_edits(f, "tree", ptr, problems);
            const std::vector<std::string> leaf_edits =
                preset_edits(f, "leaf_shader_keys", ptr, problems);
            const std::vector<std::string> bark_edits =
                preset_edits(f, "bark_shader_keys", ptr, problems);
            family.graftal = load_style(family.style, source, ptr + "/style", problems);
            family.imposters =
                load_imposters(family.imposters_name, source, ptr + "/imposters", problems);
            if (family.preset.empty()) {
                problems.push_back({ptr + "/preset", "missing: a tree preset name or file"});
                continue;
            }
            std::string preset_file;  // where a problem of the species' bark is told
            load_into(problems, source, ptr + "/preset", [&] {
                preset_file = resolve_preset("trees", near_scene(family.preset, source), source,
                                             ptr + "/preset")
                                  .string();
                load_edited(problems, source, ptr + "/preset", ptr + "/tree", tree_edits,
                            [&] { family.params = load_tree_preset(preset_file, tree_edits); });
            });
            auto shader = [&](const std::string& shader_name, const std::string& palette_name,
                              const char* key, const char* pkey, StrokeShaderParams& params,
                              Palette& palette) {
                const std::vector<std::string>& edits =
                    std::string(key) == "leaf_shader" ? leaf_edits : bark_edits;
                load_into(problems, source, ptr + "/" + key, [&] {
                    ShaderPreset sp;
                    if (!load_edited_shader(problems, source, shader_name, ptr + "/" + key,
                                            ptr + "/" + key + "_keys", edits, sp))
                        return;
                    if (sp.has_surface)
                        throw InputError(source, ptr + "/" + key,
                                         "shader \"" + shader_name +
                                             "\" has a \"surface\" section, which only a "
                                             "material's strokes read; leaves and bark would "
                                             "ignore it");
                    params = sp.params;
                    // The scene's palette, else the species' bark (its tree preset's: a bad
                    // name is that file's key, told under the family's preset key), else the
                    // shader's.
                    std::string pal = palette_name, where = ptr + "/" + pkey, from = source,
                                key = where;
                    const bool species = pal.empty() && std::string(pkey) == "bark_palette" &&
                                         !family.params.bark_palette.empty();
                    if (species) {
                        pal = family.params.bark_palette;
                        where = ptr + "/preset", from = preset_file, key = "/bark_palette";
                    }
                    if (pal.empty()) pal = sp.palette;
                    if (pal.empty())
                        throw InputError(source, where,
                                         "the shader names no palette; give one here");
                    // A bad palette file is the palette key's problem, not the shader's.
                    load_into(problems, source, where, [&] {
                        palette =
                            shader_palette(load_palette(near_scene(pal, from), from, key), params);
                    });
                });
            };
            shader(leaf_shader, leaf_palette, "leaf_shader", "leaf_palette", family.leaf_shader,
                   family.leaf_palette);
            shader(bark_shader, bark_palette, "bark_shader", "bark_palette", family.bark_shader,
                   family.bark_palette);
            s.families.push_back(std::move(family));
        }
    }
}

// Trees placed by hand: a list of {family, seed, position, rotation, scale}.
void parse_trees(const json& doc, SceneDesc& s, std::vector<Problem>& problems,
                 std::set<std::string>& plain) {
    auto trees = doc.find("trees");
    if (trees != doc.end() && !trees->is_array())
        problems.push_back({"/trees", "expected a list of trees, got " + describe(*trees)});
    if (trees != doc.end() && trees->is_array()) {
        for (size_t i = 0; i < trees->size(); ++i) {
            const json& t = (*trees)[i];
            std::string ptr = "/trees/" + std::to_string(i);
            if (!t.is_object()) {
                problems.push_back({ptr, "expected an object, got " + describe(t)});
                continue;
            }
            PlacedTree placed;
            std::string family;
            Reader r(t, problems, plain, ptr);
            r.check_ranges();
            r.text("family", family, "");
            r.claim("seed");
            r.vector("position", placed.position, "", "");
            r.number("rotation", placed.rotation, {-1e6, 1e6}, "", "");
            // Ray queries place each tree's limbs by this scale: beyond 1e4 either way, rays
            // in the tree's own space stop being representable.
            r.number("scale", placed.scale, {1e-4, 1e4}, "", "");
            r.finish();
            if (auto it = t.find("seed"); it != t.end())
                placed.seed = read_seed(*it, ptr + "/seed", problems);
            bool found = false;
            for (size_t k = 0; k < s.families.size(); ++k)
                if (s.families[k].name == family)
                    placed.family = static_cast<uint32_t>(k), found = true;
            if (!found) {
                std::string names;
                for (const auto& f : s.families) names += (names.empty() ? "" : ", ") + f.name;
                problems.push_back({ptr + "/family", "no family \"" + family +
                                                         "\" in /families (have: " + names + ")"});
                continue;
            }
            s.trees.push_back(placed);
        }
    }
}

// With a terrain, an explicit tree's or rock's y is its height above the ground; groups are
// scattered over it after the explicit trees.
void place_on_ground(SceneDesc& s) {
    s.explicit_trees = s.trees.size();
    if (s.terrain.present) {
        auto ground = [&](double x, double z) {
            return terrain_height(s.terrain.params, s.terrain.seed, x, z);
        };
        for (auto& t : s.trees) t.position.y += ground(t.position.x, t.position.z);
        for (auto& r : s.rocks) r.position.y += ground(r.position.x, r.position.z);
        for (auto& f : s.figures) f.position.y += ground(f.position.x, f.position.z);
        for (size_t i = 0; i < s.groups.size(); ++i) {
            const TreeGroup& g = s.groups[i];
            for (const ScatteredTree& st :
                 scatter_trees(s.terrain.params, s.terrain.seed, g.params, g.seed, i)) {
                PlacedTree pt;
                pt.family = g.families[st.family];
                pt.seed = st.seed;
                pt.position = st.position;
                pt.rotation = st.rotation;
                pt.scale = st.scale;
                s.trees.push_back(pt);
            }
        }
    }
}

// A scene that names another in "extends" is that scene with its own keys merged over it (JSON
// merge patch, RFC 7386: objects merge key by key, anything else, lists too, replaces, null
// removes). The file must lie beside the extending one; chains of up to 8 are followed.
json resolve_extends(json doc, const std::string& source, int depth = 0) {
    auto it = doc.find("extends");
    if (it == doc.end()) return doc;
    if (!it->is_string())
        throw InputError(source, "/extends", "expected a scene file name, got " + describe(*it));
    if (depth >= 8)
        throw InputError(source, "/extends", "more than 8 scenes extend each other (a cycle?)");
    const std::string name = it->get<std::string>();
    // Beside this file: files the base names (shaders, palettes, presets) are looked up from
    // the extending file's folder, which is then the base's too.
    if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
        throw InputError(
            source, "/extends",
            "expected the name of a scene file in the same folder, got \"" + name + "\"");
    fs::path base = fs::path(source).parent_path() / name;
    if (!fs::exists(base) && base.extension().empty()) base += ".json";
    if (!fs::is_regular_file(base))
        throw InputError(source, "/extends", "no scene file " + base.string());
    std::vector<Problem> problems;
    std::set<std::string> unused;
    json base_doc = parse_document(read_input_file(base), base.string(), {}, problems, unused);
    if (!problems.empty()) throw InputError(base.string(), problems);
    base_doc = resolve_extends(std::move(base_doc), base.string(), depth + 1);
    doc.erase(it);
    base_doc.merge_patch(doc);
    return base_doc;
}

}  // namespace

namespace {

// Every coordinate the scene places, against kMaxWorldCoordinate (scene.h). Read after the
// keys, so each is finite already; extents (a rock's size, a group's disc) count with their
// centres.
void check_world_range(const SceneDesc& s, std::vector<Problem>& problems) {
    auto within = [](double v) { return std::abs(v) <= kMaxWorldCoordinate; };
    auto check = [&](const std::string& ptr, std::initializer_list<double> values) {
        for (double v : values)
            if (!within(v)) {
                problems.push_back({ptr,
                                    "beyond the world pleinair supports: every coordinate "
                                    "within +-" +
                                        format_number(kMaxWorldCoordinate) + ", got " +
                                        format_number(v)});
                return;
            }
    };
    auto vec3 = [&](const std::string& ptr, const glm::dvec3& v, double extent = 0) {
        const double e = std::abs(extent);
        check(ptr, {v.x - e, v.x + e, v.y - e, v.y + e, v.z - e, v.z + e});
    };
    if (s.camera_track.keys.empty()) {
        vec3("/camera/position", s.camera_params.position);
        vec3("/camera/look_at", s.camera_params.look_at);
    }
    for (size_t i = 0; i < s.camera_track.keys.size(); ++i) {
        const std::string ptr = "/camera/track/" + std::to_string(i);
        vec3(ptr + "/position", s.camera_track.keys[i].position);
        vec3(ptr + "/look_at", s.camera_track.keys[i].look_at);
    }
    for (size_t i = 0; i < s.trees.size(); ++i)  // the explicit ones: groups come later
        vec3("/trees/" + std::to_string(i) + "/position", s.trees[i].position);
    for (size_t i = 0; i < s.rocks.size(); ++i) {
        const RockDesc& r = s.rocks[i];
        const glm::dvec3 sc = r.params.scale;
        vec3("/rocks/" + std::to_string(i) + "/position", r.position,
             r.params.radius * std::max({sc.x, sc.y, sc.z}));
    }
    for (size_t i = 0; i < s.figures.size(); ++i)
        vec3("/figures/" + std::to_string(i) + "/position", s.figures[i].position,
             s.figures[i].params.height);
    if (s.terrain.present) {
        const TerrainParams& t = s.terrain.params;
        check("/terrain/min", {t.min.x, t.min.y});
        check("/terrain/max", {t.max.x, t.max.y});
        check("/terrain/base_height", {t.base_height});
        for (size_t i = 0; i < t.hills.size(); ++i)
            check("/terrain/hills/" + std::to_string(i),
                  {t.hills[i].center.x, t.hills[i].center.y, t.base_height + t.hills[i].height});
    }
    if (s.water.present) check("/water/level", {s.water.level});
    for (size_t i = 0; i < s.groups.size(); ++i) {
        const ScatterParams& g = s.groups[i].params;
        check("/groups/" + std::to_string(i) + "/center",
              {g.center.x - g.radius, g.center.x + g.radius, g.center.y - g.radius,
               g.center.y + g.radius});
    }
}

// A material named `name` added to the scene from a shader preset and its palette, for the
// materials pleinair adds itself (the trees' ground, the figures'); its index. A preset that
// fails to load is refused at `pointer`.
uint32_t add_preset_material(SceneDesc& s, const std::string& name, const std::string& preset,
                             const std::string& source, const std::string& pointer) {
    Material m;
    m.name = name;
    const ShaderPreset sp = load_shader_preset(preset, source, pointer);
    m.shader = sp.params;
    m.surface = sp.surface;
    m.palette = shader_palette(load_palette(sp.palette, source, pointer), m.shader);
    s.materials.push_back(std::move(m));
    return static_cast<uint32_t>(s.materials.size() - 1);
}

// The contact touches' material (ContactDesc::material): the named one, the terrain's own at
// each touch, or the ground material for a scene of trees without terrain. Throws InputError.
void resolve_contact(const std::string& source, SceneDesc& s) {
    ContactDesc& c = s.contact;
    c.material = -1;
    if (c.touches <= 0 || s.trees.empty()) return;
    if (!c.material_name.empty()) {
        std::vector<Problem> problems;
        c.material = find_material(s, c.material_name, "/contact/material", problems);
        if (!problems.empty()) throw InputError(source, problems);
        return;
    }
    if (!s.terrain.present) c.material = static_cast<int32_t>(add_ground_material(s, source));
}

// A figure without a named material takes the scene's "figure" material, added from the figure
// shader preset the first time one is needed.
void resolve_figures(const std::string& source, SceneDesc& s) {
    int32_t figure = -1;
    for (FigureDesc& f : s.figures) {
        if (f.material >= 0) continue;
        if (figure < 0) {
            for (size_t i = 0; i < s.materials.size() && figure < 0; ++i)
                if (s.materials[i].name == "figure") figure = static_cast<int32_t>(i);
        }
        if (figure < 0)
            figure = static_cast<int32_t>(
                add_preset_material(s, "figure", "figure", source, "/figures"));
        f.material = figure;
    }
}

}  // namespace

uint32_t add_ground_material(SceneDesc& s, const std::string& source) {
    for (size_t i = 0; i < s.materials.size(); ++i)
        if (s.materials[i].name == "grass" || s.materials[i].name == "ground")
            return static_cast<uint32_t>(i);
    return add_preset_material(s, "ground", "grass", source, "/contact/material");
}

SceneDesc parse_scene(const std::string& text, const std::string& source,
                      const std::vector<std::string>& overrides) {
    std::vector<Problem> problems;
    std::set<std::string> overridden;
    json doc = resolve_extends(parse_document(text, source, {}, problems, overridden), source);
    apply_overrides(doc, overrides, problems, overridden);
    SceneDesc s;
    std::set<std::string> plain;
    Reader reader(doc, problems, plain);
    reader.check_ranges();
    visit_scene(s, reader);
    for (const char* key :
         {"families", "trees", "materials", "rocks", "meshes", "groups", "particles", "figures"})
        reader.claim(key);
    reader.finish();
    parse_tracks(doc, s, problems, plain);
    // A circle the reader already refused (out of range) is not reported twice.
    const bool camera_read = std::none_of(problems.begin(), problems.end(), [](const Problem& p) {
        return p.pointer.rfind("/camera/", 0) == 0 && p.pointer.rfind("/camera/track", 0) != 0;
    });
    if (camera_read)
        for (Problem& p : validate_circles(s.circles, "/camera")) problems.push_back(std::move(p));
    parse_landscape(doc, source, s, problems, plain);
    if (s.sky.present)
        load_into(problems, source, "/sky/shader", [&] {
            const ShaderPreset sp =
                load_shader_preset(near_scene(s.sky.shader_name, source), source, "/sky/shader");
            s.sky.shader = sp.params;
            const std::string pal = s.sky.palette_name.empty() ? sp.palette : s.sky.palette_name;
            if (pal.empty())
                throw InputError(source, "/sky/palette",
                                 "the shader names no palette; give one here");
            load_into(problems, source, "/sky/palette", [&] {
                s.sky.palette = shader_palette(
                    load_palette(near_scene(pal, source), source, "/sky/palette"), s.sky.shader);
            });
        });

    if (std::string why = make_camera(s.camera_params, s.camera); !why.empty())
        problems.push_back({"/camera", why});
    double sl = glm::length(s.sun_direction);
    if (!(sl > 0) || !std::isfinite(sl))
        problems.push_back({"/sun/direction", "must be a non-zero direction"});
    else
        s.sun_direction /= sl;
    const glm::dvec3 wd = s.wind.direction;
    if (s.wind.present &&
        !(std::isfinite(wd.x) && std::isfinite(wd.z) && wd.x * wd.x + wd.z * wd.z > 1e-12))
        problems.push_back(
            {"/wind/direction", "must be a finite direction with a level part (x or z)"});
    if (s.has_atmosphere && s.atmosphere.far_distance < s.atmosphere.near_distance)
        problems.push_back(
            {"/atmosphere/far", "must be >= near (" + format_number(s.atmosphere.near_distance) +
                                    "), got " + format_number(s.atmosphere.far_distance)});
    if (s.has_atmosphere && s.atmosphere.value_far < s.atmosphere.value_near)
        problems.push_back({"/atmosphere/value_far",
                            "must be >= value_near (" + format_number(s.atmosphere.value_near) +
                                "), got " + format_number(s.atmosphere.value_far)});
    if (s.render.samples != 1 && s.render.samples != 4 && s.render.samples != 16)
        problems.push_back(
            {"/render/samples", "must be 1, 4 or 16, got " + std::to_string(s.render.samples)});

    parse_families(doc, source, s, problems, plain);
    parse_trees(doc, s, problems, plain);
    parse_groups(doc, s, problems, plain);
    check_world_range(s, problems);
    // The files last, and only for a scene otherwise sound: a broken scene is not kept waiting.
    if (problems.empty()) load_height_map(source, s, problems);
    if (problems.empty()) load_gltf_files(source, s, problems);
    if (problems.empty()) load_particle_files(source, s, problems);
    mark_overrides(problems, overridden);
    if (!problems.empty()) throw InputError(source, problems);

    place_on_ground(s);
    resolve_contact(source, s);
    resolve_figures(source, s);
    // Counted once the groups are scattered, before a tree is grown (each holds megabytes).
    if (s.trees.size() > limits().trees) {
        const bool placed = s.explicit_trees > limits().trees;
        const std::string what =
            s.explicit_trees == s.trees.size()
                ? "the scene lists " + std::to_string(s.trees.size()) + " trees"
                : "the scene places " + std::to_string(s.trees.size()) + " trees (" +
                      std::to_string(s.explicit_trees) + " listed, the rest scattered)";
        throw InputError(source, placed ? "/trees" : "/groups",
                         what + ", over the limit of " + std::to_string(limits().trees) + "; " +
                             how_to_raise("trees"));
    }
    return s;
}

SceneDesc load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
    return parse_scene(read_input_file(file), file.string(), overrides);
}

std::string wind_key_catalog(const WindDesc& wind) {
    Cataloguer c;
    WindDesc w = wind;
    c.object("wind", "Wind that bends the trees frame by frame", [&] { visit_wind(w, c); });
    return c.rows.dump();
}

std::string scene_reference() {
    Documenter d;
    d.out << "| key | default | range | unit | meaning |\n|---|---|---|---|---|\n";
    d.out << "| `/extends` |  |  |  | Another scene file (beside this one; `.json` may be left "
             "out) that this one starts from: its keys are merged over it, objects key by key, "
             "anything else (lists too) replaced, `null` removing a key. |\n";
    SceneDesc defaults;
    visit_scene(defaults, d);
    d.object("camera/track/N",
             "One key of the camera track, a list of at least two (absent: a still)", [&] {
                 CameraKey k;
                 k.up = defaults.camera_params.up;
                 k.fov = defaults.camera_params.fov;
                 visit_camera_key(k, d);
             });
    d.object("sun/track/N",
             "One key of the sun's track, a list of at least two (absent: a sun "
             "that stays at /sun/direction)",
             [&] {
                 SunKey k;
                 visit_sun_key(k, d);
             });
    d.object("wind/track/N",
             "One key of the wind's track, a list of at least two (absent: the wind keeps "
             "/wind/strength and /wind/direction)",
             [&] {
                 WindKey k;
                 visit_wind_key(k, d);
             });
    d.object("terrain/hills/N", "One hill of the terrain's list", [&] {
        Hill h;
        visit_hill(h, d);
    });
    d.object("terrain/regions/N",
             "A disc of the terrain painted with its own material (later regions win; the bank "
             "wins over all)",
             [&] {
                 MaterialRegion r;
                 visit_region(r, d);
             });
    d.object("rocks/N", "One rock of the list: a displaced mesh painted with strokes", [&] {
        RockDesc r;
        r.strokes.particle_spans_u = r.strokes.particle_spans_v = 1;
        r.strokes.particles_per_cluster = 3;
        visit_rock(r, d);
        visit_strokes(r.strokes, d);
    });
    d.object("meshes/N",
             "Surfaces from a glTF file, painted with a material's strokes; they cast and "
             "receive shadows and hide what lies behind them, as rocks do",
             [&] {
                 MeshFileDesc m;
                 visit_mesh_file(m, d);
             });
    d.object("particles/N",
             "A file of particles made by another tool, painted as strokes with a material "
             "(they cast and receive the sun's shadows and never fade with distance)",
             [&] {
                 ParticleFileDesc p;
                 visit_particle_file(p, d);
             });
    d.object("figures/N",
             "A small figure (staffage) painted in a few touches at its place in the world, "
             "as Corot set a woman gathering or a child at a tree's foot: the picture's scale "
             "and its warm accent",
             [&] {
                 FigureDesc f;
                 visit_figure(f, d);
             });
    d.object("groups/N", "One group of trees scattered over the terrain (Poisson disk)", [&] {
        TreeGroup g;
        visit_group(g, d);
        d.note("families", "",
               "Family names to relative weights, e.g. {\"oak\": 2, \"poplar\": 1}.");
    });
    d.object("groups/N/clearings/M",
             "A stretch of the group kept free of trunks (a path through the wood, a glade)", [&] {
                 Clearing c;
                 visit_clearing(c, d);
             });
    return d.out.str();
}

}  // namespace pleinair
