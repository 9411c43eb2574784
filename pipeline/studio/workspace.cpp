// The studio's workspace: overrides in, the shot rebuilt as deep as they reach, frames out.
#include "pipeline/studio/workspace.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "generators/quad_mesh.h"
#include "generators/terrain.h"
#include "pipeline/frame/frame_plan.h"
#include "pipeline/frame/frame_view.h"
#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/draft.h"
#include "pipeline/input/error.h"
#include "pipeline/input/json_params.h"
#include "pipeline/input/presets.h"
#include "pipeline/input/shader_io.h"
#include "pipeline/output/contact_sheet.h"
#include "pipeline/output/write_file.h"
#include "pipeline/shot/built_trees.h"
#include "pipeline/shot/family.h"
#include "pipeline/shot/landscape.h"
#include "pipeline/shot/shot.h"
#include "shading/portable_math.h"

namespace pleinair {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The first token of `pointer` after `prefix` ("/families/oak/tree/x" -> "oak"), or "".
std::string token_after(const std::string& pointer, const std::string& prefix) {
    if (pointer.rfind(prefix, 0) != 0) return "";
    const size_t end = pointer.find('/', prefix.size());
    return pointer.substr(prefix.size(), end == std::string::npos ? end : end - prefix.size());
}

bool under(const std::string& pointer, const std::string& key) {
    return pointer == key || pointer.rfind(key + "/", 0) == 0;
}

// A JSON pointer token unescaped (~1 is "/", ~0 is "~").
std::string unescape_token(const std::string& t) {
    std::string out;
    for (size_t i = 0; i < t.size(); ++i) {
        if (t[i] == '~' && i + 1 < t.size()) {
            out += t[i + 1] == '1' ? '/' : '~';
            ++i;
        } else {
            out += t[i];
        }
    }
    return out;
}

std::string escape_token(const std::string& t) {
    std::string out;
    for (char c : t) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    return out;
}

// One shell word: bare when it holds only safe characters, else in single quotes.
std::string shell_quote(const std::string& s) {
    const bool bare = !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) ||
               std::string("-_./=,:+@%").find(c) != std::string::npos;
    });
    if (bare) return s;
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

const Family* find_family(const SceneDesc& scene, const std::string& name) {
    for (const Family& f : scene.families)
        if (f.name == name) return &f;
    return nullptr;
}

// The trees and families a change below the shot level may keep: the same trees, in the same
// families, at the same places (a family's preset cannot move a tree).
bool same_placement(const SceneDesc& a, const SceneDesc& b) {
    if (a.trees.size() != b.trees.size() || a.families.size() != b.families.size()) return false;
    for (size_t i = 0; i < a.families.size(); ++i)
        if (a.families[i].name != b.families[i].name) return false;
    for (size_t i = 0; i < a.trees.size(); ++i) {
        const PlacedTree &s = a.trees[i], &t = b.trees[i];
        if (s.family != t.family || s.seed != t.seed || s.position != t.position ||
            s.rotation != t.rotation || s.scale != t.scale)
            return false;
    }
    return a.build.bark_coverage == b.build.bark_coverage;
}

ShotOptions studio_shot_options() {
    // As animate: every particle's light from a still sun is traced once, in the shot, so a
    // camera that moves repaints without shadow rays. The same bytes as render's light traced
    // per frame for the particles in view (held by the same-pixels tests).
    ShotOptions o;
    o.cache_sun_light = true;
    return o;
}

}  // namespace

const char* change_level_name(ChangeLevel level) {
    switch (level) {
        case ChangeLevel::kFrame:
            return "frame";
        case ChangeLevel::kShot:
            return "shot";
        case ChangeLevel::kFamily:
            return "family";
        case ChangeLevel::kScene:
            return "scene";
    }
    return "?";
}

ChangeLevel change_level(const std::string& pointer, std::string* family) {
    // The camera's track moves the shot's anchor and the near field's strokes; its circles
    // and its still position (near field) are re-checked at rest (Workspace::rebuild).
    if (under(pointer, "/camera/track")) return ChangeLevel::kScene;
    if (under(pointer, "/camera")) return ChangeLevel::kFrame;
    for (const char* k : {"/sun", "/wind", "/sky", "/background", "/atmosphere", "/description"})
        if (under(pointer, k)) return ChangeLevel::kShot;
    if (under(pointer, "/render")) {
        // The two build settings: bark strokes on every tree, strokes on every surface.
        if (under(pointer, "/render/bark_coverage") || under(pointer, "/render/surface_density"))
            return ChangeLevel::kScene;
        return ChangeLevel::kShot;
    }
    const std::string name = token_after(pointer, "/families/");
    if (!name.empty()) {
        const std::string rest = pointer.substr(std::string("/families/").size() + name.size());
        for (const char* k :
             {"/leaf_shader", "/leaf_palette", "/leaf_shader_keys", "/style", "/imposters"})
            if (under(rest, k)) return ChangeLevel::kShot;
        for (const char* k :
             {"/preset", "/tree", "/bark_shader", "/bark_palette", "/bark_shader_keys"})
            if (under(rest, k)) {
                if (family) *family = unescape_token(name);
                return ChangeLevel::kFamily;
            }
    }
    return ChangeLevel::kScene;
}

Workspace::Workspace(const std::string& scene, const std::vector<std::string>& sets)
    : scene_arg_(scene) {
    file_ = resolve_preset("scenes", scene, "SCENE");
    for (const std::string& s : sets) {
        const size_t eq = s.find('=');
        if (eq == std::string::npos) throw InputError("--set", s, "expected POINTER=VALUE");
        std::string p = s.substr(0, eq), v = s.substr(eq + 1);
        auto it = std::find_if(sets_.begin(), sets_.end(), [&](auto& e) { return e.first == p; });
        if (it != sets_.end())
            it->second = v;
        else
            sets_.emplace_back(p, v);
    }
    scene_ = load(sets_);
}

Workspace::~Workspace() = default;

SceneDesc Workspace::load(const std::vector<std::pair<std::string, std::string>>& sets) const {
    std::vector<std::string> args;
    for (const auto& [p, v] : sets) args.push_back(p + "=" + v);
    SceneDesc s = load_scene(file_, args);
    // A camera that degenerates on the track is bad input here, as render reports it.
    try {
        (void)view_at(s, animation_span(s).first);
    } catch (const std::runtime_error& e) {
        throw InputError(file_.string(), "/camera/track", e.what());
    }
    return s;
}

std::vector<std::string> Workspace::override_args() const {
    std::vector<std::string> out;
    for (const auto& [p, v] : sets_) out.push_back(p + "=" + v);
    return out;
}

bool Workspace::animated() const { return scene_.animated(); }

ChangeLevel Workspace::set(const std::string& pointer, const std::string& value) {
    return set_all({{pointer, value}});
}

ChangeLevel Workspace::set_all(const std::vector<std::pair<std::string, std::string>>& changes) {
    auto sets = sets_;
    ChangeLevel level = ChangeLevel::kFrame;
    std::vector<std::string> families;
    for (const auto& change : changes) {
        // Named, not a structured binding: clang 14 (the sanitized build) cannot capture those.
        const std::string &p = change.first, &v = change.second;
        if (p.empty() || p[0] != '/')
            throw InputError(file_.string(), p, "expected a JSON pointer starting with /");
        auto it = std::find_if(sets.begin(), sets.end(), [&](auto& e) { return e.first == p; });
        if (it != sets.end())
            it->second = v;
        else
            sets.emplace_back(p, v);
        std::string family;
        level = std::max(level, change_level(p, &family));
        if (!family.empty()) families.push_back(family);
    }
    return apply(std::move(sets), level, families);
}

ChangeLevel Workspace::unset(const std::string& pointer) {
    auto sets = sets_;
    sets.erase(
        std::remove_if(sets.begin(), sets.end(), [&](auto& e) { return e.first == pointer; }),
        sets.end());
    std::string family;
    const ChangeLevel level = change_level(pointer, &family);
    return apply(std::move(sets), level,
                 family.empty() ? std::vector<std::string>{} : std::vector<std::string>{family});
}

ChangeLevel Workspace::apply(std::vector<std::pair<std::string, std::string>> sets,
                             ChangeLevel level, const std::vector<std::string>& families) {
    SceneDesc next = load(sets);  // InputError: nothing changes
    // Below the scene level a change keeps every tree where it stands; if it did not (a family
    // renamed through its preset key, say), everything is rebuilt.
    if (level < ChangeLevel::kScene && !same_placement(scene_, next)) level = ChangeLevel::kScene;
    sets_ = std::move(sets);
    scene_ = std::move(next);
    forget_frames();
    if (level == ChangeLevel::kFrame) {
        camera_moved_ = true;
    } else {
        pending_ = std::max(pending_.value_or(level), level);
        if (level == ChangeLevel::kFamily)
            regrow_.insert(regrow_.end(), families.begin(), families.end());
    }
    return level;
}

void Workspace::forget_frames() {
    seen_ = SeenMemo{};
    mirrors_ = MirrorMemo{};
}

void Workspace::rebuild(bool for_preview, StudioFrame& out) {
    const auto t0 = std::chrono::steady_clock::now();
    std::optional<ChangeLevel> level = shot_ ? pending_ : std::optional(ChangeLevel::kScene);
    // At rest the shot must be the one render builds: its anchor is the still camera's eye,
    // and a still camera's near field chooses the ground's detail strokes.
    bool land_for_camera = false;
    if (camera_moved_ && !for_preview) {
        level = std::max(level.value_or(ChangeLevel::kShot), ChangeLevel::kShot);
        land_for_camera = scene_.camera_track.keys.empty() && scene_.circles.near_field > 0;
    }
    out.exact = !(camera_moved_ && !level);
    if (!level) return;
    const ShotOptions options = studio_shot_options();
    const bool bark = scene_.build.bark_coverage > 0;
    if (*level == ChangeLevel::kScene || !trees_) {
        trees_ = std::make_shared<const std::vector<BuiltTree>>(build_trees(scene_, bark));
        land_ = std::make_shared<const BuiltLandscape>(build_landscape(scene_));
    } else {
        if (*level == ChangeLevel::kFamily) {
            std::vector<bool> regrow(scene_.trees.size(), false);
            for (size_t i = 0; i < scene_.trees.size(); ++i)
                regrow[i] =
                    std::find(regrow_.begin(), regrow_.end(),
                              scene_.families[scene_.trees[i].family].name) != regrow_.end();
            trees_ = std::make_shared<const std::vector<BuiltTree>>(
                regrow_trees(scene_, bark, *trees_, regrow));
        }
        if (land_for_camera)
            land_ = std::make_shared<const BuiltLandscape>(build_landscape(scene_));
    }
    // The graftals and imposters of the shot before, where the trees and landscape are the same
    // (build_shot checks the styles too).
    ShotOptions carry = options;
    carry.carry_from = shot_.get();
    shot_ = std::make_unique<Shot>(build_shot(scene_, trees_, land_, carry));
    forget_frames();
    out.rebuilt = *level;
    out.rebuilt_any = true;
    out.built = shot_->passes;
    pending_.reset();
    regrow_.clear();
    camera_moved_ = false;
    out.build_ms = ms_since(t0);
}

StudioFrame Workspace::paint(std::optional<int> frame, bool preview,
                             const std::function<bool()>& abandon, bool draft) {
    StudioFrame out;
    if (frame && !scene_.animated()) throw InputError("frame", "", "a still has no frames");
    rebuild(preview, out);
    // The view from the scene as it is now: the camera may have moved since the shot.
    const double t = frame ? frame_time(*frame, scene_.fps) : animation_span(scene_).first;
    FrameView view;
    if (preview) {
        SceneDesc s = scene_;
        s.camera_params.width = std::max(1, s.camera_params.width / 2);
        s.camera_params.height = std::max(1, s.camera_params.height / 2);
        if (std::string why = make_camera(s.camera_params, s.camera); !why.empty())
            throw InputError(file_.string(), "/camera", why);
        view = view_at(s, t);
    } else {
        view = view_at(scene_, t);
    }
    FrameSettings settings = scene_frame_settings(shot_->scene);
    if (draft) {
        std::vector<std::string> sets;
        for (const auto& [p, v] : sets_) sets.push_back(p + "=" + v);
        apply_draft(settings.render, sets);
    }
    settings.abandon = abandon;
    settings.buffers = &buffers_;
    settings.seen_memo = &seen_;
    settings.mirror_memo = &mirrors_;
    const auto t0 = std::chrono::steady_clock::now();
    out.frame = paint_frame(*shot_, view, settings, &out.report);
    out.paint_ms = ms_since(t0);
    return out;
}

std::string Workspace::command_line(std::optional<int> frame, bool preview, const std::string& out,
                                    bool draft) const {
    std::string cmd = "pleinair render " + shell_quote(scene_arg_);
    for (const auto& [p, v] : sets_) cmd += " --set " + shell_quote(p + "=" + v);
    if (frame) cmd += " --frame " + std::to_string(*frame);
    if (preview) cmd += " --preview";
    if (draft) cmd += " --draft";
    return cmd + " -o " + shell_quote(out);
}

std::string Workspace::catalog_json() const {
    json c;
    c["scene"] = scene_arg_;
    c["file"] = file_.string();
    c["description"] = scene_.description;
    c["animated"] = scene_.animated();
    if (scene_.animated()) {
        const FrameRange r = animation_frames(scene_);
        c["frames"] = {r.first, r.last};
        c["fps"] = scene_.fps;
    }
    const CameraParams& cp = scene_.camera_params;
    c["camera"] = {{"position", {cp.position.x, cp.position.y, cp.position.z}},
                   {"look_at", {cp.look_at.x, cp.look_at.y, cp.look_at.z}},
                   {"fov", cp.fov},
                   {"width", cp.width},
                   {"height", cp.height},
                   {"track", !scene_.camera_track.keys.empty()},
                   {"circles", scene_has_circles(scene_)}};
    json fams = json::array();
    for (const Family& f : scene_.families) {
        const std::string base = "/families/" + escape_token(f.name);
        json fam = {{"name", f.name},
                    {"pointer", base},
                    {"preset", f.preset},
                    {"style", f.style},
                    {"tree", json::parse(tree_key_catalog(f.params))},
                    {"leaf_shader", json::parse(shader_key_catalog(f.leaf_shader))},
                    {"bark_shader", json::parse(shader_key_catalog(f.bark_shader))}};
        json seeds = json::array();
        for (size_t i = 0; i < scene_.explicit_trees; ++i)
            if (scene_.families[scene_.trees[i].family].name == f.name)
                seeds.push_back({{"index", i}, {"seed", scene_.trees[i].seed}});
        fam["trees"] = seeds;
        fams.push_back(fam);
    }
    c["families"] = fams;
    // The wind's keys, whether the scene has a /wind or not: a change adds one.
    c["wind"] = json::parse(wind_key_catalog(scene_.wind));
    c["tree_presets"] = preset_names("trees");
    c["shaders"] = preset_names("shaders");
    c["palettes"] = preset_names("palettes");
    json ov = json::array();
    for (const auto& [p, v] : sets_) ov.push_back({{"pointer", p}, {"value", v}});
    c["overrides"] = ov;
    return c.dump();
}

fs::path Workspace::keep(const std::string& family, const fs::path& dir) const {
    const Family* f = find_family(scene_, family);
    if (!f) throw InputError("keep", family, "no family of that name in the scene");
    std::string stem = fs::path(f->preset).stem().string();
    if (stem.empty()) stem = "tree";
    fs::create_directories(dir);
    for (int i = 1; i < 100000; ++i) {
        const fs::path file = dir / (stem + "-" + std::to_string(i) + ".json");
        std::error_code ec;
        if (fs::exists(file, ec)) continue;
        write_file_atomic(file, save_tree_params(f->params));
        return file;
    }
    throw std::runtime_error("keep: no free name in " + dir.string());
}

Frame Workspace::contact_sheet(const std::string& family, uint32_t count, int width,
                               int height) const {
    const Family* f = find_family(scene_, family);
    if (!f) throw InputError("contact", family, "no family of that name in the scene");
    uint64_t seed = 1;
    for (const PlacedTree& t : scene_.trees)
        if (scene_.families[t.family].name == family) {
            seed = t.seed;
            break;
        }
    SheetOptions o;
    o.width = width;
    o.height = height;
    o.build = scene_.build;
    o.render = scene_.render;
    return paint_contact_sheet(*f, generate_family(f->params, seed, count), o);
}

std::string Workspace::circles_json(std::optional<int> frame, bool preview) const {
    SceneDesc s = scene_;
    if (preview) {
        s.camera_params.width = std::max(1, s.camera_params.width / 2);
        s.camera_params.height = std::max(1, s.camera_params.height / 2);
        if (!make_camera(s.camera_params, s.camera).empty()) return "[]";
    }
    const double t = frame ? frame_time(*frame, s.fps) : animation_span(s).first;
    const FrameView view = view_at(s, t);
    const DistanceCircles& c = view.circles;
    json out = json::array();
    const std::pair<const char*, double> rings[] = {{"near field", c.near_field},
                                                    {"leaf near", c.leaf_near},
                                                    {"leaf far", c.leaf_far},
                                                    {"trunk near", c.trunk_near},
                                                    {"trunk far", c.trunk_far}};
    const glm::dvec3 eye = view.camera.eye;
    for (const auto& [name, radius] : rings) {
        if (!(radius > 0)) continue;
        json points = json::array();
        constexpr int kSteps = 180;
        for (int i = 0; i <= kSteps; ++i) {
            const double a = 2 * M_PI * i / kSteps;
            const double x = eye.x + radius * pmath::cos(a), z = eye.z + radius * pmath::sin(a);
            const double y =
                s.terrain.present ? terrain_height(s.terrain.params, s.terrain.seed, x, z) : 0.0;
            const Projection p = project(view.camera, {x, y, z});
            // A break (null) where the ring passes behind the camera.
            if (p.in_front && std::isfinite(p.x) && std::isfinite(p.y))
                points.push_back({std::round(p.x * 10) / 10, std::round(p.y * 10) / 10});
            else
                points.push_back(nullptr);
        }
        out.push_back({{"name", name}, {"radius", radius}, {"points", points}});
    }
    return out.dump();
}

std::vector<std::pair<std::string, std::string>> Workspace::framing() const {
    // The grown trees' extent: every leaf and the trunk's base, placed.
    glm::dvec3 lo(1e300), hi(-1e300);
    const std::vector<BuiltTree> trees = build_trees(scene_, false);
    for (const BuiltTree& b : trees) {
        const TreePlacement pl = placement(b);
        auto grow = [&](const glm::vec3& p) {
            const glm::dvec3 w = pl.place(p);
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        };
        grow(glm::vec3(0.0f));
        for (const glm::vec3& p : b.tree().leaves.position) grow(p);
        for (const glm::vec3& p : b.tree().control.positions) grow(p);
    }
    if (trees.empty()) return {};
    const CameraParams& cp = scene_.camera_params;
    const double height = std::max(hi.y - std::min(lo.y, 0.0), 1e-3);
    const double width = std::max(hi.x - lo.x, hi.z - lo.z);
    const double aspect = double(cp.width) / cp.height;
    const double half_fov = 0.5 * cp.fov * M_PI / 180.0;
    // Far enough that the whole height fits with a tenth to spare, and the width too.
    const double d = 1.1 * std::max(0.5 * height / pmath::tan(half_fov),
                                    0.5 * width / (pmath::tan(half_fov) * aspect)) +
                     0.5 * (hi.z - lo.z);
    const glm::dvec3 centre(0.5 * (lo.x + hi.x), std::min(lo.y, 0.0) + 0.5 * height,
                            0.5 * (lo.z + hi.z));
    auto num = [](double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.3f", v);
        return std::string(buf);
    };
    auto vec = [&](const glm::dvec3& v) {
        return "[" + num(v.x) + "," + num(v.y) + "," + num(v.z) + "]";
    };
    return {{"/camera/position", vec(centre + glm::dvec3(0, 0.08 * height, d))},
            {"/camera/look_at", vec(centre)}};
}

}  // namespace pleinair
