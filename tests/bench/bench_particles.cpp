// Painting particles from another tool: a 200,000-particle PLY file (Houdini's attributes) at
// 1920 x 1080, 4 samples per pixel, on all cores: the file read and turned into strokes, the
// shot built, the frame painted, and the PNG written, each timed, and all four in a row; and
// all four with the sun casting shadows, the particles casting them on each other.
// Figures: BENCHMARKS.md ("Particles from other tools").
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>

#include "pipeline/frame/paint_frame.h"
#include "pipeline/input/scene.h"
#include "pipeline/output/image_io.h"
#include "ply_writer.h"

using namespace pleinair;

namespace {

namespace fs = std::filesystem;

// The scene and its file, written once into a temporary folder.
const fs::path& scene_file() {
    static const fs::path file = [] {
        const fs::path dir = fs::temp_directory_path() / "pleinair-bench-particles";
        fs::create_directories(dir);
        std::ofstream(dir / "field.ply", std::ios::binary)
            << test::write_ply(test::particle_field(200000), "binary_little_endian");
        for (const bool casts : {false, true})
            std::ofstream(dir / (casts ? "field-sun.json" : "field.json")) << R"({
          "camera": {"position": [0, 6, 14], "look_at": [0, 0, -10], "fov": 60,
                     "width": 1920, "height": 1080},
          "sun": {"direction": [-0.5, 0.7, 0.5], "casts_shadows": )" << (casts ? "true" : "false")
                                                                           << R"(},
          "render": {"samples": 4},
          "materials": {"grass": {"shader": "grass"}},
          "particles": [{"file": "field.ply", "material": "grass", "color_amount": 0.6}]})";
        return dir / "field.json";
    }();
    return file;
}

fs::path casting_scene_file() { return scene_file().parent_path() / "field-sun.json"; }

void BM_ParticlesRead(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(load_scene(scene_file()));
}

void BM_ParticlesShot(benchmark::State& state) {
    const SceneDesc scene = load_scene(scene_file());
    for (auto _ : state) benchmark::DoNotOptimize(build_shot(scene));
}

void BM_ParticlesFrame(benchmark::State& state) {
    const Shot shot = build_shot(load_scene(scene_file()));
    const FrameSettings settings = scene_frame_settings(shot.scene);
    for (auto _ : state)
        benchmark::DoNotOptimize(paint_frame(shot, still_view(shot.scene), settings));
}

void BM_ParticlesWritePng(benchmark::State& state) {
    const Frame frame = paint_still(load_scene(scene_file()));
    const fs::path out = scene_file().parent_path() / "field.png";
    for (auto _ : state) write_frame(out, frame);
}

// What `pleinair render field.json -o field.png` does after the process has started.
void BM_ParticlesWhole(benchmark::State& state) {
    const fs::path out = scene_file().parent_path() / "whole.png";
    for (auto _ : state) write_frame(out, paint_still(load_scene(scene_file())));
}

// The same with the sun casting shadows: the particles' casters in the sun's scene, a shadow
// ray for each particle drawn.
void BM_ParticlesWholeCasting(benchmark::State& state) {
    const fs::path out = scene_file().parent_path() / "whole-sun.png";
    for (auto _ : state) write_frame(out, paint_still(load_scene(casting_scene_file())));
}

}  // namespace

BENCHMARK(BM_ParticlesRead)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ParticlesShot)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ParticlesFrame)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ParticlesWritePng)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ParticlesWhole)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ParticlesWholeCasting)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
