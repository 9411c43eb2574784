// The studio's workspace: a scene as its files say plus the user's overrides (the pointers
// --set takes) and the shot built from them, rebuilt only as deep as a change reaches, and
// painted by paint_frame exactly as `pleinair render` with those --sets paints it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/frame/buffer_pool.h"
#include "pipeline/frame/frame_image.h"
#include "pipeline/frame/frame_report.h"
#include "pipeline/frame/mirror_memo.h"
#include "pipeline/frame/seen_memo.h"
#include "pipeline/input/scene.h"
#include "pipeline/shot/pass_report.h"

namespace pleinair {

struct BuiltTree;
struct BuiltLandscape;
struct Shot;

// How deep a change reaches, cheapest first.
enum class ChangeLevel {
    kFrame,   // the camera: paint again from the same shot
    kShot,    // leaf shaders and palettes, sun, sky, atmosphere, render keys: the shot built
              // again from the same trees and landscape
    kFamily,  // a family's preset, tree keys or bark: that family's trees regrown
    kScene    // anything else (terrain, water, rocks, placement, time base): everything
};
const char* change_level_name(ChangeLevel level);

// The level a change of `pointer` (as --set takes it) reaches; `family` gets the family's name
// for kFamily. Pure: the table in workspace.cpp is the whole rule.
ChangeLevel change_level(const std::string& pointer, std::string* family = nullptr);

// A painted frame and what it cost.
struct StudioFrame {
    Frame frame;
    FrameReport report;
    ChangeLevel rebuilt = ChangeLevel::kFrame;  // the deepest level redone for it
    bool rebuilt_any = false;                   // whether anything was rebuilt at all
    bool exact = true;  // what `command_line` paints; false: a preview from a shot built for
                        // an earlier camera (while the camera moves)
    double build_ms = 0, paint_ms = 0;
    std::vector<PassReport> built;  // the shot's passes, when it was rebuilt for this frame
};

class Workspace {
  public:
    // `scene`: a name in presets/scenes or a JSON file; `sets`: "POINTER=VALUE" overrides to
    // start from. Throws InputError (nothing built) on bad input.
    explicit Workspace(const std::string& scene, const std::vector<std::string>& sets = {});
    ~Workspace();
    Workspace(const Workspace&) = delete;
    Workspace& operator=(const Workspace&) = delete;

    // Sets `pointer` to `value` (parsed as JSON, else taken as a string, as --set does). On
    // bad input throws InputError with the message the command line gives, and nothing changes.
    ChangeLevel set(const std::string& pointer, const std::string& value);
    // Several at once, all or none (the tree steps, a framing).
    ChangeLevel set_all(const std::vector<std::pair<std::string, std::string>>& changes);
    // Back to the file's value.
    ChangeLevel unset(const std::string& pointer);

    const SceneDesc& scene() const { return scene_; }
    const std::filesystem::path& scene_file() const { return file_; }
    const std::string& scene_arg() const { return scene_arg_; }
    // The overrides in the order first made, each pointer once with its latest value.
    const std::vector<std::pair<std::string, std::string>>& overrides() const { return sets_; }
    std::vector<std::string> override_args() const;
    // Whether the scene has a camera, sun or wind track, and its frames.
    bool animated() const;

    // The command that paints exactly the picture `paint(frame, preview, {}, draft)` gives at
    // rest, quoted for a POSIX shell.
    std::string command_line(std::optional<int> frame, bool preview, const std::string& out,
                             bool draft = false) const;

    // Paints frame `frame` of a shot (nullopt: a still, or a shot's first frame) at full size
    // or, `preview`, at half (as render --preview). A preview while only the camera changed
    // paints from the shot already built (StudioFrame::exact false); anything else first
    // rebuilds what the changes since the last paint reached. `abandon` is asked between
    // stages (FrameAbandoned). `draft` paints it as render --draft does (draft.h), the
    // overrides' own keys kept.
    StudioFrame paint(std::optional<int> frame, bool preview,
                      const std::function<bool()>& abandon = {}, bool draft = false);
    // Empties what frames painted one after another share (done at every change): the next
    // frame is painted as if alone, the same bytes (benchmarks, for the ratio).
    void forget_frames();

    // Every control the page builds: the families' tree and shader keys (rows of the key
    // tables with their current values), palettes, the camera, the frames; JSON.
    std::string catalog_json() const;

    // Writes family `family`'s resolved preset (the --save-preset writer) as DIR/NAME.json,
    // NAME the first of PRESET-1, PRESET-2, ... not taken; returns the file.
    std::filesystem::path keep(const std::string& family, const std::filesystem::path& dir) const;

    // Family `family`'s contact sheet: `count` members from the seed of its first tree.
    Frame contact_sheet(const std::string& family, uint32_t count, int width, int height) const;

    // The distance circles the camera carries at frame `frame` (as paint takes it), each a
    // ring on the ground around the eye projected into the picture: JSON of {name, radius,
    // points: [[x, y], ...]} in pixels of the full-size (or preview) frame, the rings' parts
    // behind the camera left out.
    std::string circles_json(std::optional<int> frame, bool preview) const;

    // The camera overrides that frame the scene's trees whole from the front (for
    // `studio --preset`), from the trees as grown.
    std::vector<std::pair<std::string, std::string>> framing() const;

  private:
    SceneDesc load(const std::vector<std::pair<std::string, std::string>>& sets) const;
    ChangeLevel apply(std::vector<std::pair<std::string, std::string>> sets, ChangeLevel level,
                      const std::vector<std::string>& families);
    void rebuild(bool for_preview, StudioFrame& out);

    std::string scene_arg_;
    std::filesystem::path file_;
    std::vector<std::pair<std::string, std::string>> sets_;
    SceneDesc scene_;

    // What is built, and from which scene (shot_->scene).
    std::shared_ptr<const std::vector<BuiltTree>> trees_;
    std::shared_ptr<const BuiltLandscape> land_;
    std::unique_ptr<Shot> shot_;
    // Stroke layers' memory kept from one painted frame to the next (buffer_pool.h).
    BufferPool buffers_;
    // Frames of a walk painted one after another (stepping or playing through it) share their
    // occlusion maps and water mirrors, as animate's do (seen_memo.h, mirror_memo.h);
    // emptied at every change and every rebuilt shot, so none outlives what it was traced in.
    SeenMemo seen_;
    MirrorMemo mirrors_;
    // What the changes since the shot was built reach: the deepest level beyond the camera,
    // the families to regrow, and whether the camera moved.
    std::optional<ChangeLevel> pending_;
    std::vector<std::string> regrow_;
    bool camera_moved_ = false;
};

}  // namespace pleinair
