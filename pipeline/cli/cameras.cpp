// The `camera` command: where a scene's camera stands at each frame, and where given world
// points land in its image (to match a shot against the tool it was laid out in).
#include <cstdio>
#include <nlohmann/json.hpp>

#include "pipeline/cli/commands.h"
#include "pipeline/frame/frame_view.h"
#include "pipeline/input/error.h"
#include "pipeline/input/frame_range.h"
#include "pipeline/input/presets.h"

namespace pleinair {

int run_camera(const CameraCommand& cmd) {
    const std::filesystem::path file = resolve_preset("scenes", cmd.scene, "SCENE");
    const SceneDesc scene = load_scene(file, cmd.set);
    if (cmd.points.size() % 3 != 0)
        throw InputError("--point", "", "expected x,y,z for each point");
    const FrameRange all = animation_frames(scene);
    const FrameRange range = cmd.frames.empty() ? all : parse_frame_range(cmd.frames);
    if (scene.animated() && (range.first < all.first || range.last > all.last))
        throw InputError(
            "--frames", "",
            "the track has frames " + std::to_string(all.first) + "-" + std::to_string(all.last));
    auto vec = [](const glm::dvec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
    for (int f : range.frames()) {
        const double t = scene.animated() ? frame_time(f, scene.fps) : 0.0;
        const FrameView view = scene.animated() ? view_at(scene, t) : still_view(scene);
        const Camera& c = view.camera;
        nlohmann::json j;
        j["frame"] = f;
        j["time"] = t;
        j["eye"] = vec(c.eye);
        j["forward"] = vec(c.forward);
        j["up"] = vec(c.up);
        j["focal_px"] = c.focal_px;
        j["width"] = c.width, j["height"] = c.height;
        j["points"] = nlohmann::json::array();
        for (size_t i = 0; i + 2 < cmd.points.size(); i += 3) {
            const Projection p = project(c, {cmd.points[i], cmd.points[i + 1], cmd.points[i + 2]});
            j["points"].push_back({p.x, p.y, p.depth, p.in_front});
        }
        std::printf("%s\n", j.dump().c_str());
    }
    return 0;
}

}  // namespace pleinair
