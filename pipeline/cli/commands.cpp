// The tree, family and presets commands.
#include "pipeline/cli/commands.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <glm/common.hpp>
#include <iostream>
#include <nlohmann/json.hpp>

#include "generators/wind.h"
#include "pipeline/input/draft.h"
#include "pipeline/input/error.h"
#include "pipeline/input/graftal_io.h"
#include "pipeline/input/imposter_io.h"
#include "pipeline/input/json_params.h"
#include "pipeline/input/limits.h"
#include "pipeline/input/presets.h"
#include "pipeline/input/scene.h"
#include "pipeline/input/shader_io.h"
#include "pipeline/output/contact_sheet.h"
#include "pipeline/output/image_io.h"
#include "pipeline/output/tree_io.h"
#include "pipeline/output/write_file.h"
#include "pipeline/shot/family.h"

namespace pleinair {

namespace fs = std::filesystem;

namespace {

TreeParams load(const std::string& preset, const std::vector<std::string>& set, std::string& name) {
    fs::path file = resolve_tree_preset(preset);
    TreeParams p = load_tree_preset(file, set);
    name = file.stem().string();
    return p;
}

// --save-preset FILE: the resolved parameters, its folder created as -o creates its own.
void save_preset(const std::string& file, const TreeParams& params) {
    if (file.empty()) return;
    if (fs::path parent = fs::path(file).parent_path(); !parent.empty())
        fs::create_directories(parent);
    write_file_atomic(file, save_tree_params(params));
}

// Refuses an output folder that is not ours to replace, before any work is done.
void check_out_dir(const std::string& out, const std::string& marker) {
    if (!out.empty()) check_output_folder(out, marker);
}

nlohmann::ordered_json mesh_counts(const QuadMesh& m) {
    return {{"vertices", m.positions.size()}, {"faces", m.quads.size()}};
}

// What a tree folder holds and how tree.glb looks: the Corot shaders and the species' bark, as
// the family's contact sheet paints them.
TreeOutput tree_output(const std::string& name, const std::string& preset, const TreeParams& params,
                       const std::string& format) {
    TreeOutput out;
    out.stiffness = params.stiffness;
    if (!parse_tree_format(format, out.format))
        throw InputError("--format", "", "\"" + format + "\": expected all, glb or obj-ply");
    const Family f = sheet_family(name, preset, params);
    out.look = {f.leaf_shader, f.leaf_palette, f.bark_palette, params.unit};
    return out;
}

}  // namespace

int run_tree(const TreeCommand& cmd) {
    std::string name;
    TreeParams params = load(cmd.preset, cmd.set, name);
    if (is_image_path(cmd.out) || is_other_image_path(cmd.out))
        throw InputError("-o", "",
                         "\"" + cmd.out +
                             "\": a tree is written as a folder of meshes and particles; give "
                             "a name without an image extension (family -o paints a sheet)");
    check_out_dir(cmd.out, "tree.json");
    if (!cmd.position.empty() && cmd.position.size() != 3)
        throw InputError("--position", "", "expected x,y,z");
    save_preset(cmd.save_preset, params);

    TreeOptions options;
    options.tree_id = cmd.id;
    options.lod = cmd.lod;
    if (cmd.position.size() == 3)
        options.origin = {cmd.position[0], cmd.position[1], cmd.position[2]};

    if (cmd.out.empty() && !cmd.stats) return 0;
    std::vector<double> ms;
    Tree tree;
    for (int i = 0; i < std::max(1, cmd.repeat); ++i) {
        auto t0 = std::chrono::steady_clock::now();
        tree = generate_tree(params, cmd.seed, options);
        auto t1 = std::chrono::steady_clock::now();
        ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
    if (!cmd.out.empty())
        write_tree(tree, name, cmd.out, tree_output(name, cmd.preset, params, cmd.format));
    if (cmd.stats) {
        std::sort(ms.begin(), ms.end());
        double median =
            ms.size() % 2 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
        Bounds b = bounds_of(tree.render.positions);
        Bounds lb = bounds_of(tree.leaves.position);
        if (!tree.leaves.position.empty()) {
            b.min = glm::min(b.min, lb.min);
            b.max = glm::max(b.max, lb.max);
        }
        auto world = [&](const glm::vec3& v) {
            glm::dvec3 w = tree.origin + glm::dvec3(v);
            return nlohmann::ordered_json::array({w.x, w.y, w.z});
        };
        nlohmann::ordered_json j;
        j["preset"] = name;
        j["seed"] = cmd.seed;
        j["control"] = mesh_counts(tree.control);
        j["render"] = mesh_counts(tree.render);
        j["lod"] = mesh_counts(tree.lod);
        j["leaves"] = tree.leaves.size();
        j["branches"] = tree.branches.size() - 1;
        j["bbox"] = {{"min", world(b.min)}, {"max", world(b.max)}};
        // What the wind moves (generators/wind.h): the parts' stiffness, the joints (every
        // limb's rings), and the particle attributes leaves.ply carries for it.
        const WindRig rig = build_wind_rig(tree, nullptr);
        j["wind"] = {
            {"stiffness",
             {{"trunk", params.stiffness.trunk},
              {"limbs", params.stiffness.limbs},
              {"leaves", params.stiffness.leaves}}},
            {"joints", rig.center.size()},
            {"reach", rig.reach},
            {"attributes", {"limb", "limb_level", "pivot_x", "pivot_y", "pivot_z", "stiffness"}}};
        j["time_ms"] = {{"median", median}, {"repeat", ms.size()}};
        std::cout << j.dump() << std::endl;
    }
    return 0;
}

namespace {

// `family -o sheet.png`: the members painted side by side.
int paint_sheet(const FamilyCommand& cmd, const TreeParams& params, const std::string& name) {
    using Clock = std::chrono::steady_clock;
    auto t0 = Clock::now();
    const Family family = sheet_family(name, cmd.preset, params, cmd.style);
    std::vector<Tree> trees = generate_family(params, cmd.seed, cmd.count);
    auto ms = [](Clock::time_point a) {
        return std::chrono::duration<double, std::milli>(Clock::now() - a).count();
    };
    double gen_ms = ms(t0);
    auto t1 = Clock::now();
    SheetOptions o;
    o.width = cmd.width;
    o.height = cmd.height;
    o.render.samples = cmd.samples;
    FrameReport rep;
    Frame sheet = paint_contact_sheet(family, trees, o, &rep);
    double paint_ms = ms(t1);
    auto t2 = Clock::now();
    if (fs::path parent = fs::path(cmd.out).parent_path(); !parent.empty())
        fs::create_directories(parent);
    write_frame(cmd.out, sheet);
    double write_ms = ms(t2);
    std::printf(
        "painted %u %s trees into %s (%dx%d) in %.2f s (generate %.0f ms, paint %.0f ms, "
        "write %.0f ms): %llu sprites, %llu fragments\n",
        cmd.count, name.c_str(), cmd.out.c_str(), o.width, o.height, ms(t0) / 1000.0, gen_ms,
        paint_ms, write_ms,
        static_cast<unsigned long long>(rep.leaf_sprites + rep.bark_sprites + rep.graftal_sprites),
        static_cast<unsigned long long>(rep.fragments));
    return 0;
}

}  // namespace

int run_family(const FamilyCommand& cmd) {
    // Every member is held in memory until written (about a megabyte for an oak).
    if (static_cast<uint64_t>(cmd.count) > limits().members)
        throw InputError("--count", "",
                         std::to_string(cmd.count) + " members, over the limit of " +
                             std::to_string(limits().members) + "; " + how_to_raise("members"));
    std::string name;
    TreeParams params = load(cmd.preset, cmd.set, name);
    if (is_other_image_path(cmd.out))
        throw InputError("-o", "",
                         "\"" + cmd.out +
                             "\": a contact sheet is written as .png, .tif, .tiff or .exr; a "
                             "folder of members needs a name without an image extension");
    if (is_image_path(cmd.out)) {
        save_preset(cmd.save_preset, params);
        return paint_sheet(cmd, params, name);
    }
    if (cmd.style != "strokes")
        throw InputError("--style", "",
                         "\"" + cmd.style +
                             "\": a style is for a painted contact sheet (-o NAME.png); a folder "
                             "of members holds meshes and particles, which have none");
    check_out_dir(cmd.out, "family.json");
    save_preset(cmd.save_preset, params);
    if (cmd.out.empty()) return 0;
    std::vector<Tree> trees = generate_family(params, cmd.seed, cmd.count);
    write_family(trees, name, cmd.seed, cmd.out, tree_output(name, cmd.preset, params, cmd.format));
    std::cout << "wrote " << trees.size() << " " << name << " trees to " << cmd.out << "\n";
    return 0;
}

int run_presets(const PresetsCommand& cmd) {
    if (!cmd.reference.empty()) {
        std::cout << (cmd.reference == "trees"       ? tree_params_reference()
                      : cmd.reference == "shaders"   ? stroke_shader_reference()
                      : cmd.reference == "graftals"  ? graftal_reference()
                      : cmd.reference == "imposters" ? imposter_reference()
                      : cmd.reference == "draft"     ? draft_reference()
                                                     : scene_reference());
        return 0;
    }
    for (const auto& p : list_tree_presets())
        std::printf("tree     %-22s %s\n", p.name.c_str(), p.description.c_str());
    for (const auto& name : preset_names("shaders"))
        std::printf("shader   %-22s %s\n", name.c_str(),
                    load_shader_preset(name).description.c_str());
    for (const auto& name : preset_names("palettes"))
        std::printf("palette  %-22s %s\n", name.c_str(), load_palette(name).description.c_str());
    for (const auto& name : preset_names("graftals"))
        std::printf("graftal  %-22s %s\n", name.c_str(), load_graftal(name).description.c_str());
    for (const auto& name : preset_names("imposters"))
        std::printf("imposter %-22s %s\n", name.c_str(), load_imposter(name).description.c_str());
    for (const auto& name : preset_names("scenes")) {
        auto file = resolve_preset("scenes", name, "presets");
        std::printf("scene    %-22s %s\n", name.c_str(), load_scene(file).description.c_str());
    }
    return 0;
}

}  // namespace pleinair
