// The pleinair commands as plain functions over plain option structs, so the command line
// (main.cpp, CLI11) and tests drive the same code.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace pleinair {

struct TreeCommand {
    std::string preset;
    uint64_t seed = 1;
    std::string out;               // directory; empty: write nothing
    bool stats = false;            // print one JSON line of counts and timing
    int repeat = 1;                // generations timed for --stats (median reported)
    std::vector<std::string> set;  // "POINTER=VALUE" overrides
    std::string save_preset;       // write the resolved parameters here
    std::vector<double> position;  // where the tree stands (x, y, z); empty: origin
    uint32_t id = 0;
    bool lod = true;
    std::string format = "all";  // tree_io.h's TreeFormat names
};

struct FamilyCommand {
    std::string preset;
    uint64_t seed = 1;  // base seed; member i gets member_seed(seed, i)
    uint32_t count = 6;
    std::string out;  // a directory for the members' files, or an image for a contact sheet
    int width = 1920, height = 1080;  // of the contact sheet
    int samples = 1;                  // stroke-mask samples per pixel of the contact sheet
    std::string style = "strokes";    // the contact sheet's crowns: strokes or a graftal
    std::vector<std::string> set;
    std::string save_preset;
    std::string format = "all";  // of each member's folder
};

struct RenderCommand {
    std::string scene;              // name in presets/scenes or a JSON file
    std::string out;                // image path: .png, .tif, .exr; empty with an export alone
    std::string export_height_map;  // the terrain's heights as an image
    std::string export_glb;         // the scene as glTF
    std::string export_instancing = "gpu";
    bool export_low_detail = false;
    bool explain = false;          // print the frame's plan, pass times and counts
    bool progress = false;         // report each stage and the paint's percent on stderr
    bool aovs = false;             // EXR depth, object id, alpha and lightness channels
    std::vector<std::string> set;  // "POINTER=VALUE" overrides of the scene
    std::optional<double> time;    // seconds into an animated scene
    std::optional<int> frame;      // or a frame of it (from 1, at the scene's fps)
    bool preview = false;          // half the resolution, as animate --preview
    bool draft = false;            // the draft's lighter settings under the --set ones
};

struct AnimateCommand {
    std::string scene;
    std::string frames;    // "A-B" or "A-BxSTEP"; empty: every frame of the track
    std::string out;       // frame files: a run of # (or %04d) is the frame number
    bool resume = false;   // keep the frames already complete, clear dead runs' temporaries
    std::string video;     // encode the frames into this .mp4 with ffmpeg
    bool preview = false;  // half resolution
    bool draft = false;    // the draft's lighter settings under the --set ones
    bool aovs = false;
    bool explain = false;  // the shot's passes, the first frame's plan and passes
    std::vector<std::string> set;
    // Progress: a bar on a terminal, else the lines render farms parse. Tests force either.
    enum class Progress { kAuto, kBar, kLog } progress = Progress::kAuto;
};

struct BenchCommand {
    std::string what;   // "accuracy", "coherence", "look" or "trees"
    std::string scene;  // trees: a tree preset, or "all"
    int repeat = 3;     // renders per setting; the median time is reported
    std::vector<std::string> set;
    std::string frames;        // coherence: A-B[xSTEP]; empty: the whole track
    bool preview = false;      // coherence: half the resolution
    bool draft = false;        // coherence: the draft's settings under the --set ones
    bool per_frame = false;    // coherence: a row per frame too
    std::optional<int> frame;  // look: the frame of an animated scene (default: its first)
    std::string save;          // coherence: a frame pattern; look: an image; empty: none
    int members = 6;           // trees: members measured per family
    uint64_t seed = 1;         // trees: the first member's seed
    int cell_width = 480, cell_height = 540;  // trees: the side view's size
};

struct StudioCommand {
    std::string scene;             // a scene name or file; or
    std::string preset;            // a tree preset, grown alone and framed
    std::vector<std::string> set;  // "POINTER=VALUE" overrides to start from
    std::string host = "127.0.0.1";
    int port = 8420;                  // 0: any free port
    std::string save_to = "presets";  // where "keep" writes
};

struct PresetsCommand {
    std::string reference;  // "trees", "shaders", "scenes", ..., "draft": print that reference
};

// Each returns the process exit code; InputError and std::runtime_error propagate to main.
int run_tree(const TreeCommand& cmd);
int run_family(const FamilyCommand& cmd);
int run_presets(const PresetsCommand& cmd);
int run_render(const RenderCommand& cmd);
int run_animate(const AnimateCommand& cmd);
int run_bench_accuracy(const BenchCommand& cmd);
int run_bench_coherence(const BenchCommand& cmd);
int run_bench_look(const BenchCommand& cmd);
int run_bench_trees(const BenchCommand& cmd);
int run_studio(const StudioCommand& cmd);

// `camera SCENE`: one JSON line per frame with the camera and where --point positions land.
struct CameraCommand {
    std::string scene;
    std::string frames;          // "A-B" or "A-BxSTEP"; empty: every frame of the track
    std::vector<double> points;  // x, y, z of each --point
    std::vector<std::string> set;
};
int run_camera(const CameraCommand& cmd);

struct SceneDesc;
// The time of the frame a command paints of `scene`: `time` or `frame` (not both; InputError
// past the track, or on a still), else an animated scene's first frame, else 0. One rule for
// render and bench look.
double frame_time_of(std::optional<double> time, std::optional<int> frame, const SceneDesc& scene,
                     const std::string& file);
// The frames of an animated scene that --frames TEXT names (all of its track's when empty);
// InputError for a bad range or one outside the track.
std::vector<int> frames_to_paint(const SceneDesc& scene, const std::string& text);
// --preview: the scene's camera at half its width and height (at least 1), as animate, render
// and bench coherence halve it alike.
void halve_for_preview(SceneDesc& scene, const std::string& file);
// InputError naming the first frame whose camera degenerates.
void check_views(const SceneDesc& scene, const std::vector<int>& frames, const std::string& file);
// InputError when `frames_at_once` frames of the scene's camera, written to `out`, are
// estimated to need more than --limit memory_mb; the line gives the estimate and its parts.
void check_job_memory(const SceneDesc& scene, bool aovs, const std::string& out, int frames_at_once,
                      const std::string& file);

}  // namespace pleinair
