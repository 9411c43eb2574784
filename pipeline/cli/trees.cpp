// `pleinair bench trees`: each tree family's form measured from the side, member by member
// (pipeline/bench/tree_form.h), a row a family.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/bench/tree_form.h"
#include "pipeline/cli/commands.h"
#include "pipeline/input/error.h"
#include "pipeline/input/presets.h"
#include "pipeline/output/contact_sheet.h"
#include "pipeline/shot/family.h"

namespace pleinair {

namespace {

// "median (least-most)" of `v`, with `digits` after the point.
std::string spread(std::vector<double> v, int digits) {
    std::sort(v.begin(), v.end());
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.*f (%.*f-%.*f)", digits, v[v.size() / 2], digits, v.front(),
                  digits, v.back());
    return buf;
}

}  // namespace

int run_bench_trees(const BenchCommand& cmd) {
    std::vector<std::string> names;
    if (cmd.scene == "all")
        for (const PresetInfo& p : list_tree_presets()) names.push_back(p.name);
    else
        names.push_back(cmd.scene);
    // Every preset read before a line is printed: a bad one leaves no half table.
    std::vector<std::pair<std::string, TreeParams>> presets;
    for (const std::string& preset : names) {
        const std::filesystem::path file = resolve_tree_preset(preset, "bench trees");
        presets.emplace_back(file.stem().string(), load_tree_preset(file, cmd.set));
    }
    std::printf(
        "Each family's first %d members (seeds from %llu), painted alone from the side "
        "at %dx%d, leaves then bark:\n\n",
        cmd.members, static_cast<unsigned long long>(cmd.seed), cmd.cell_width, cmd.cell_height);
    std::printf(
        "| family | spread / height | clear trunk / height | droop | sides' hem / height | "
        "clumps | sky in the crown | ms a member |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const auto& [name, params] : presets) {
        SceneDesc scene;
        scene.families = {sheet_family(name, name, params)};
        scene.has_atmosphere = false;
        const auto t0 = std::chrono::steady_clock::now();
        const std::vector<Tree> trees =
            generate_family(params, cmd.seed, static_cast<uint32_t>(cmd.members));
        std::vector<double> ratio, clear, droop, hem, clumps, holes;
        for (const Tree& t : trees) {
            BuiltTree b;
            b.tree() = t;
            b.id = t.id;
            b.position = t.origin;
            b.bark() = family_bark(scene.families[0], t, scene.build.bark_coverage, t.seed);
            const TreeForm f =
                measure_form(side_masks(scene, b, cmd.cell_width, cmd.cell_height), t);
            ratio.push_back(f.crown_ratio), clear.push_back(f.clear_trunk);
            droop.push_back(f.droop), hem.push_back(f.hem);
            clumps.push_back(f.clumps), holes.push_back(f.holes);
        }
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        std::printf("| %s | %s | %s | %s | %s | %s | %s | %.0f |\n", name.c_str(),
                    spread(ratio, 2).c_str(), spread(clear, 2).c_str(), spread(droop, 2).c_str(),
                    spread(hem, 2).c_str(), spread(clumps, 0).c_str(), spread(holes, 2).c_str(),
                    ms / trees.size());
    }
    return 0;
}

}  // namespace pleinair
