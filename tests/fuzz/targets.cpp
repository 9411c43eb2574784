// The fuzz targets' bodies (targets.h).
#include "targets.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "pipeline/frame/imposter_draw.h"
#include "pipeline/input/error.h"
#include "pipeline/input/gltf_import.h"
#include "pipeline/input/graftal_io.h"
#include "pipeline/input/imposter_io.h"
#include "pipeline/input/json_params.h"
#include "pipeline/input/particle_files.h"
#include "pipeline/input/presets.h"
#include "pipeline/input/scene.h"
#include "pipeline/input/shader_io.h"
#include "pipeline/shot/figures.h"
#include "pipeline/shot/graftal_lod.h"
#include "pipeline/studio/studio_request.h"

namespace pleinair::fuzz {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void finding(const char* what, const std::string& detail) {
    std::fprintf(stderr, "fuzz finding: %s: %s\n", what, detail.c_str());
    std::abort();
}

// Runs `fn`; a refusal must be an InputError of one line per problem, naming its source.
template <class Fn>
void refused_cleanly(const char* target, Fn&& fn) {
    try {
        fn();
    } catch (const InputError& e) {
        const std::string msg = e.what();
        if (e.problems().empty() || msg.empty()) finding(target, "an empty InputError");
        size_t lines = 1;
        for (char c : msg) lines += c == '\n';
        if (lines != e.problems().size()) finding(target, "a problem over several lines: " + msg);
    } catch (const std::exception& e) {
        finding(target, std::string("not an InputError: ") + e.what());
    }
}

std::string text(const uint8_t* data, size_t size) {
    return std::string(reinterpret_cast<const char*>(data), size);
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x + v.y + v.z); }

}  // namespace

int tree_preset(const uint8_t* data, size_t size) {
    refused_cleanly("tree_preset", [&] {
        const TreeParams p = parse_tree_params(text(data, size), "fuzz.json");
        // Accepted: it saves and reads back to the same values.
        const std::string saved = save_tree_params(p);
        if (save_tree_params(parse_tree_params(saved, "saved.json")) != saved)
            finding("tree_preset", "a preset that does not read back as saved");
    });
    return 0;
}

int shader_preset(const uint8_t* data, size_t size) {
    refused_cleanly("shader_preset", [&] {
        const ShaderPreset s = parse_shader_preset(text(data, size), "fuzz.json");
        if (!std::isfinite(s.params.sprite_size) || !std::isfinite(s.params.stroke_fullness))
            finding("shader_preset", "a non-finite parameter accepted");
    });
    return 0;
}

int palette(const uint8_t* data, size_t size) {
    refused_cleanly("palette", [&] {
        const PaletteFile f = parse_palette(text(data, size), "fuzz.json");
        // Accepted: every lookup, at any lightness, is a finite colour.
        for (float l = -0.5f; l <= 1.5f; l += 0.125f) {
            const Color c = palette_lookup(f.palette, l);
            if (!std::isfinite(c.x + c.y + c.z)) finding("palette", "a non-finite colour");
        }
    });
    return 0;
}

int scene(const uint8_t* data, size_t size) {
    refused_cleanly("scene", [&] {
        const SceneDesc s = parse_scene(text(data, size), "fuzz/scene.json");
        // Accepted: everything it places is finite and within the world.
        auto check = [](const glm::dvec3& v) {
            if (!finite(v) || std::abs(v.x) > 2 * kMaxWorldCoordinate ||
                std::abs(v.z) > 2 * kMaxWorldCoordinate)
                finding("scene", "a position outside the world accepted");
        };
        check(s.camera_params.position);
        for (const auto& k : s.camera_track.keys) check(k.position);
        for (const auto& t : s.trees) check(t.position);
        // A figure accepted is posed into finite touches about its place.
        for (const auto& f : s.figures) {
            check(f.position);
            for (const glm::vec3& q : figure_particles(f, glm::vec3(0, 1, 0)).strokes.position)
                if (!std::isfinite(q.x + q.y + q.z))
                    finding("scene", "a figure's touch not finite");
        }
    });
    return 0;
}

// A small scene that uses every section, for the targets that change one.
const std::string& small_scene() {
    static const std::string base = R"({
      "camera": {"position": [0, 2, 20], "look_at": [0, 2, 0], "width": 64, "height": 48,
                 "track": [{"time": 0, "position": [0, 2, 20], "look_at": [0, 2, 0]},
                           {"time": 1, "position": [2, 2, 18], "look_at": [0, 2, 0]}]},
      "sun": {"direction": [0, 1, 0.3]},
      "materials": {"grass": {"shader": "grass"}},
      "terrain": {"min": [-10, -10], "max": [10, 10], "resolution": 9, "material": "grass",
                  "hills": [{"center": [0, 0], "radius": 4, "height": 1}]},
      "families": {"oak": {"preset": "oak"}},
      "trees": [{"family": "oak", "seed": 1, "position": [0, 0, 0]}]})";
    return base;
}

int set_value(const uint8_t* data, size_t size) {
    // Each line is one --set POINTER=VALUE over the small scene.
    const std::string& base = small_scene();
    std::vector<std::string> overrides;
    std::string line;
    for (size_t i = 0; i <= size; ++i) {
        if (i == size || data[i] == '\n') {
            if (!line.empty()) overrides.push_back(line);
            line.clear();
        } else {
            line += static_cast<char>(data[i]);
        }
    }
    refused_cleanly("set_value", [&] { parse_scene(base, "fuzz/set.json", overrides); });
    return 0;
}

int studio_request(const uint8_t* data, size_t size) {
    // A change request from the studio's page: refused in one line, or accepted and applied to
    // the small scene as the --sets the command line shows.
    const fs::path presets = preset_root();
    StudioChange change;
    try {
        change = parse_studio_change(text(data, size), {presets}, presets / "scenes");
    } catch (const RequestRefused& e) {
        const std::string msg = e.what();
        if (msg.empty() || msg.find('\n') != std::string::npos)
            finding("studio_request", "a refusal that is not one line: " + msg);
        return 0;
    } catch (const std::exception& e) {
        finding("studio_request", std::string("not a refusal: ") + e.what());
    }
    std::vector<std::string> overrides;
    for (const auto& [p, v] : change.set) overrides.push_back(p + "=" + v);
    refused_cleanly("studio_request",
                    [&] { parse_scene(small_scene(), "fuzz/studio.json", overrides); });
    return 0;
}

int particle_file(const uint8_t* data, size_t size) {
    // The first byte picks the axes and which attributes are named, the rest is the file.
    if (size < 1) return 0;
    ParticleFileDesc d;
    d.up = data[0] & 1 ? UpAxis::kZ : UpAxis::kY;
    if (data[0] & 2) d.size = "none";
    if (data[0] & 4) d.color = "r,g,b";
    if (data[0] & 8) d.normal = "none";
    refused_cleanly("particle_file", [&] {
        const ImportedParticles p = import_particles(text(data + 1, size - 1), "fuzz.ply", d, 1,
                                                     glm::vec3(0, 1, 0), kMaxWorldCoordinate);
        const SurfaceParticles& s = p.strokes;
        for (size_t i = 0; i < s.size(); ++i) {
            const glm::vec3 q = s.position[i];
            if (!std::isfinite(q.x + q.y + q.z) || !(s.label[i] > 0 && s.label[i] < 1))
                finding("particle_file", "a non-finite position or a label outside (0, 1)");
            if (!p.width.empty() && !(p.width[i] > 0 && std::isfinite(p.width[i])))
                finding("particle_file", "a width not > 0");
            if (!p.color.empty() && !std::isfinite(p.color[i].x + p.color[i].y + p.color[i].z))
                finding("particle_file", "a non-finite colour");
        }
    });
    return 0;
}

int gltf(const uint8_t* data, size_t size) {
    // Bytes as a .glb or .gltf with no file around it: its triangles, then its camera's track.
    std::shared_ptr<const GltfDocument> doc;
    refused_cleanly("gltf", [&] { doc = parse_gltf(text(data, size), "fuzz.glb", "", "s", "/p"); });
    if (!doc) return 0;
    refused_cleanly("gltf", [&] {
        const QuadMesh m = gltf_triangles(*doc, {}, glm::dvec3(0.0), 1.0, "s", "/p");
        for (const glm::vec3& p : m.positions)
            if (!std::isfinite(p.x + p.y + p.z)) finding("gltf", "a vertex that is not finite");
        for (const glm::uvec4& q : m.quads)
            for (int c = 0; c < 4; ++c)
                if (q[c] >= m.positions.size()) finding("gltf", "an index past the vertices");
    });
    refused_cleanly("gltf", [&] {
        const CameraTrack t = gltf_camera_track(*doc, "", 10.0, 24.0, "s", "/p");
        for (const CameraKey& k : t.keys)
            if (!finite(k.position) || !finite(k.look_at) || !finite(k.up) ||
                !std::isfinite(k.time))
                finding("gltf", "a camera key that is not finite");
    });
    return 0;
}

int graftal(const uint8_t* data, size_t size) {
    refused_cleanly("graftal", [&] {
        const GraftalDesc g = parse_graftal(text(data, size), "fuzz.json");
        // Accepted: every primitive indexes its example's vertices, strokes have a width per
        // vertex, and the levels rise from 0.
        if (g.examples.empty() || g.tuft.levels.empty()) finding("graftal", "nothing to draw");
        for (const GraftalExample& e : g.examples)
            for (const GraftalPrimitive& p : e.primitives) {
                for (uint32_t v : p.vertices)
                    if (v >= e.vertices.size()) finding("graftal", "a vertex index past the end");
                if (p.type == PrimitiveType::kStroke && p.widths.size() != p.vertices.size())
                    finding("graftal", "a stroke without a width per vertex");
            }
        if (g.tuft.levels[0].lambda != 0) finding("graftal", "a first level above 0");
        for (size_t i = 1; i < g.tuft.levels.size(); ++i)
            if (!(g.tuft.levels[i].lambda > g.tuft.levels[i - 1].lambda))
                finding("graftal", "levels that do not rise");
        // Its tuft replayed over a second of a λ that sweeps every level: levels in range, τ in
        // [0, 1], the same state whether replayed or stepped.
        const float top = g.tuft.levels.back().lambda + 1.0f;
        auto lambda = [top](int f) { return top * static_cast<float>(f % 13) / 12.0f; };
        TuftState s;
        for (int f = 0; f < 24; ++f) {
            step_tuft(s, g.tuft, tuft_level(g.tuft.levels, lambda(f)), 1.0 / 24);
            if (s.level < 0 || s.level >= static_cast<int>(g.tuft.levels.size()))
                finding("graftal", "a tuft level out of range");
            for (float t : s.tau)
                if (!(t >= 0.0f && t <= 1.0f)) finding("graftal", "a τ outside [0, 1]");
        }
        if (replay_tuft(g.tuft, lambda, 23, 24).tau != s.tau)
            finding("graftal", "a replayed tuft that differs from the stepped one");
    });
    return 0;
}

int imposter(const uint8_t* data, size_t size) {
    refused_cleanly("imposter", [&] {
        const ImposterDesc d = parse_imposter(text(data, size), "fuzz.json");
        // Accepted: an atlas of whole cells, control rows it has, and one imposter of every
        // cell drawn without a crash.
        const ImposterAtlas a = imposter_atlas(d);
        if (a.levels.empty()) finding("imposter", "no atlas");
        if (a.levels[0].width != a.columns * a.cell_w || a.levels[0].height != a.rows * a.cell_h)
            finding("imposter", "an atlas of broken cells");
        for (int r : d.rows)
            if (r < -1 || r >= a.rows) finding("imposter", "a control row the atlas lacks");
        Camera cam;
        cam.eye = glm::dvec3(0, 0, 10);
        cam.width = cam.height = 32;
        cam.focal_px = 64;
        ImposterQuad q;
        q.v0 = {-1, -1, 0}, q.v1 = {1, -1, 0}, q.t0 = {-1, 1, 0}, q.t1 = {1, 1, 0};
        for (q.row = 0; q.row < a.rows; ++q.row)
            for (q.column = 0; q.column < a.columns; ++q.column)
                if (draw_imposter(a, q, cam).pixels.size() > 32u * 32u)
                    finding("imposter", "a patch larger than the frame");
    });
    return 0;
}

}  // namespace pleinair::fuzz
