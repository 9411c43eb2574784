// The studio's workspace and server: which level a change reaches, that a rebuilt level paints
// what a fresh build of the same overrides paints, that a superseded frame is abandoned, and
// that the server answers only its own page.
#include <gtest/gtest.h>
#include <httplib.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "pipeline/frame/frame_plan.h"
#include "pipeline/input/draft.h"
#include "pipeline/input/error.h"
#include "pipeline/studio/server.h"
#include "pipeline/studio/studio_request.h"
#include "pipeline/studio/workspace.h"
#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;

TEST(Studio, ChangeLevelsFollowTheKeyTables) {
    std::string family;
    EXPECT_EQ(change_level("/camera/position"), ChangeLevel::kFrame);
    EXPECT_EQ(change_level("/camera/fov"), ChangeLevel::kFrame);
    EXPECT_EQ(change_level("/camera/track/0/position"), ChangeLevel::kScene);
    EXPECT_EQ(change_level("/sun/direction"), ChangeLevel::kShot);
    EXPECT_EQ(change_level("/wind/strength"), ChangeLevel::kShot);
    EXPECT_EQ(change_level("/wind/track/1/strength"), ChangeLevel::kShot);
    EXPECT_EQ(change_level("/sky"), ChangeLevel::kShot);
    EXPECT_EQ(change_level("/render/samples"), ChangeLevel::kShot);
    EXPECT_EQ(change_level("/render/bark_coverage"), ChangeLevel::kScene);
    EXPECT_EQ(change_level("/render/surface_density"), ChangeLevel::kScene);
    EXPECT_EQ(change_level("/families/oak/leaf_shader_keys/sprite/sprite_size"),
              ChangeLevel::kShot);
    EXPECT_EQ(change_level("/families/oak/leaf_palette"), ChangeLevel::kShot);
    EXPECT_EQ(change_level("/families/oak/tree/trunk/taper/base", &family), ChangeLevel::kFamily);
    EXPECT_EQ(family, "oak");
    EXPECT_EQ(change_level("/families/a~1b/preset", &family), ChangeLevel::kFamily);
    EXPECT_EQ(family, "a/b");
    EXPECT_EQ(change_level("/families/oak/bark_shader_keys/sprite/sprite_size"),
              ChangeLevel::kFamily);
    EXPECT_EQ(change_level("/families/oak"), ChangeLevel::kScene);
    EXPECT_EQ(change_level("/families/oak/leaf_shaderx"), ChangeLevel::kScene);
    EXPECT_EQ(change_level("/terrain/height"), ChangeLevel::kScene);
    EXPECT_EQ(change_level("/trees/0/seed"), ChangeLevel::kScene);
    EXPECT_EQ(change_level("/cameras"), ChangeLevel::kScene);
}

// Two families, three trees: a change to one family regrows it alone.
fs::path two_family_scene() {
    const fs::path file = fs::temp_directory_path() / "pleinair-studio-two-families.json";
    std::ofstream(file) << R"({
  "camera": {"position": [0, 5, 34], "look_at": [0, 5, 0], "width": 320, "height": 180},
  "sun": {"direction": [-0.6, 0.7, 0.45], "casts_shadows": true},
  "families": {"oak": {"preset": "oak"}, "birch": {"preset": "birch"}},
  "trees": [{"family": "oak", "seed": 1, "position": [-7, 0, 0]},
            {"family": "birch", "seed": 2, "position": [6, 0, 0]},
            {"family": "birch", "seed": 3, "position": [10, 0, -6]}]
})";
    return file;
}

// What a workspace built afresh from the same overrides paints.
Frame fresh(const Workspace& ws, bool preview) {
    Workspace again(ws.scene_file().string(), ws.override_args());
    return again.paint(std::nullopt, preview).frame;
}

TEST(Studio, EachLevelPaintsWhatAFreshBuildPaints) {
    Workspace ws(two_family_scene().string());
    const Frame first = ws.paint(std::nullopt, true).frame;

    EXPECT_EQ(ws.set("/families/birch/tree/trunk/taper/base", "0.8"), ChangeLevel::kFamily);
    StudioFrame f = ws.paint(std::nullopt, true);
    EXPECT_EQ(f.rebuilt, ChangeLevel::kFamily);
    EXPECT_TRUE(f.exact);
    EXPECT_NE(f.frame.rgba, first.rgba);
    EXPECT_EQ(f.frame.rgba, fresh(ws, true).rgba);

    EXPECT_EQ(ws.set("/families/oak/leaf_shader_keys/sprite/sprite_size", "0.5"),
              ChangeLevel::kShot);
    f = ws.paint(std::nullopt, true);
    EXPECT_EQ(f.rebuilt, ChangeLevel::kShot);
    EXPECT_EQ(f.frame.rgba, fresh(ws, true).rgba);

    EXPECT_EQ(ws.set("/sun/direction", "[0.5, 0.6, 0.3]"), ChangeLevel::kShot);
    f = ws.paint(std::nullopt, false);
    EXPECT_EQ(f.frame.rgba, fresh(ws, false).rgba);

    // Wind added to a scene that had none: the catalogue offers its keys, the shot is rebuilt
    // with the trees' rigs, and the still (time 0) is painted bent, as render paints it.
    EXPECT_NE(ws.catalog_json().find("\"/wind/strength\""), std::string::npos);
    const Frame calm = ws.paint(std::nullopt, false).frame;
    EXPECT_EQ(ws.set("/wind/strength", "9"), ChangeLevel::kShot);
    f = ws.paint(std::nullopt, false);
    EXPECT_NE(f.frame.rgba, calm.rgba);
    EXPECT_EQ(f.frame.rgba, fresh(ws, false).rgba);
}

TEST(Studio, AShotChangeCarriesTheGraftalsOverAndPaintsTheSame) {
    Workspace ws("truffula", {"/camera/width=320", "/camera/height=180"});
    const Frame first = ws.paint(std::nullopt, true).frame;
    EXPECT_EQ(ws.set("/sun/direction", "[0.3, 0.5, 0.6]"), ChangeLevel::kShot);
    const StudioFrame f = ws.paint(std::nullopt, true);
    EXPECT_EQ(f.rebuilt, ChangeLevel::kShot);
    bool carried = false;
    for (const PassReport& p : f.built)
        if (p.name == "graftals") carried = p.why.find("carried over") != std::string::npos;
    EXPECT_TRUE(carried);
    EXPECT_NE(f.frame.rgba, first.rgba);
    EXPECT_EQ(f.frame.rgba, fresh(ws, true).rgba);
    // A new style is placed again.
    ws.set("/families/truffula/style", "strokes");
    const StudioFrame g = ws.paint(std::nullopt, true);
    for (const PassReport& p : g.built) {
        if (p.name == "graftals") {
            EXPECT_EQ(p.why.find("carried over"), std::string::npos);
        }
    }
    EXPECT_EQ(g.frame.rgba, fresh(ws, true).rgba);
}

TEST(Studio, ACameraMovePreviewsFromTheLastShotThenPaintsExactlyAtRest) {
    Workspace ws(two_family_scene().string());
    (void)ws.paint(std::nullopt, true);
    EXPECT_EQ(ws.set("/camera/position", "[3, 6, 30]"), ChangeLevel::kFrame);
    const StudioFrame moving = ws.paint(std::nullopt, true);
    EXPECT_FALSE(moving.exact);
    EXPECT_FALSE(moving.rebuilt_any);
    const StudioFrame rest = ws.paint(std::nullopt, false);
    EXPECT_TRUE(rest.exact);
    EXPECT_TRUE(rest.rebuilt_any);
    EXPECT_EQ(rest.frame.rgba, fresh(ws, false).rgba);
}

// Frames of a walk stepped through in turn paint what each painted alone paints, the later ones
// with a fraction of the mirrors traced; after a change too.
TEST(Studio, FramesSteppedThroughInTurnAreTheFramesPaintedAlone) {
    const std::vector<std::string> small = {"/camera/width=160", "/camera/height=90",
                                            "/render/occlusion_frames=2"};
    Workspace ws("mortefontaine-walk", small);
    auto alone = [&](int frame) {
        Workspace again(ws.scene_file().string(), ws.override_args());
        return again.paint(frame, false);
    };
    (void)ws.paint(30, false);
    (void)ws.paint(31, false);
    const StudioFrame third = ws.paint(32, false), third_alone = alone(32);
    EXPECT_EQ(third.frame.rgba, third_alone.frame.rgba);
    EXPECT_GT(third.report.reflection_rays, 0u);
    EXPECT_LT(third.report.reflection_rays * 2, third_alone.report.reflection_rays);
    (void)ws.set("/water/ripple", "0.05");
    EXPECT_EQ(ws.paint(33, false).frame.rgba, alone(33).frame.rgba) << "after a change";
}

TEST(Studio, ABadValueChangesNothing) {
    Workspace ws(two_family_scene().string());
    ws.set("/families/oak/tree/trunk/taper/base", "0.8");
    const Frame before = ws.paint(std::nullopt, true).frame;
    try {
        ws.set("/families/oak/tree/trunk/taper/base", "7");
        FAIL() << "a taper of 7 was accepted";
    } catch (const InputError& e) {
        const std::string line = format_problems(e.source(), e.problems());
        EXPECT_NE(line.find("/families/oak/tree/trunk/taper/base: must be in [0, 1], got 7"),
                  std::string::npos)
            << line;
    }
    ASSERT_EQ(ws.overrides().size(), 1u);
    EXPECT_EQ(ws.overrides()[0].second, "0.8");
    EXPECT_EQ(ws.paint(std::nullopt, true).frame.rgba, before.rgba);
    EXPECT_THROW(ws.set("no-slash", "1"), InputError);
}

TEST(Studio, ASupersededFrameIsAbandonedBetweenStages) {
    Workspace ws(two_family_scene().string());
    int asked = 0;
    // Superseded after the second stage has started.
    EXPECT_THROW(ws.paint(std::nullopt, true, [&] { return ++asked > 2; }), FrameAbandoned);
    EXPECT_EQ(asked, 3);
    // The workspace is whole: the next frame is the one a fresh build paints.
    EXPECT_EQ(ws.paint(std::nullopt, true).frame.rgba, fresh(ws, true).rgba);
}

// A draft preview is the frame the draft's settings paint as overrides, the user's own kept,
// and the command the page shows says --draft.
TEST(Studio, DraftPreviewsPaintTheDraftsSettingsUnderTheUsersOwn) {
    const std::string file = two_family_scene().string();
    std::vector<std::string> drafted;
    for (const DraftSetting& d : draft_settings())
        drafted.push_back(std::string(d.pointer) + "=" + d.value);
    Workspace ws(file);
    const Frame draft = ws.paint(std::nullopt, true, {}, true).frame;
    EXPECT_NE(draft.rgba, ws.paint(std::nullopt, true).frame.rgba);
    EXPECT_EQ(draft.rgba, Workspace(file, drafted).paint(std::nullopt, true).frame.rgba);
    EXPECT_EQ(ws.command_line(std::nullopt, true, "a.png", true),
              "pleinair render " + file + " --preview --draft -o a.png");
    ws.set("/render/samples", "4");
    drafted[0] = "/render/samples=4";
    EXPECT_EQ(ws.paint(std::nullopt, true, {}, true).frame.rgba,
              Workspace(file, drafted).paint(std::nullopt, true).frame.rgba);
}

TEST(Studio, TheCommandLineNamesEveryOverride) {
    Workspace ws("tree", {"/families/tree/preset=birch"});
    ws.set("/camera/fov", "35");
    ws.set("/families/tree/tree/name", "it's mine");
    EXPECT_EQ(ws.command_line(std::nullopt, true, "out/a b.png"),
              "pleinair render tree --set /families/tree/preset=birch --set /camera/fov=35 "
              "--set '/families/tree/tree/name=it'\\''s mine' --preview -o 'out/a b.png'");
}

TEST(Studio, KeepWritesThePresetTheTreeWasGrownFrom) {
    Workspace ws("tree", {"/families/tree/preset=oak", "/families/tree/tree/trunk/taper/base=0.8"});
    const fs::path dir = fs::temp_directory_path() / "pleinair-studio-keep";
    fs::remove_all(dir);
    const fs::path a = ws.keep("tree", dir), b = ws.keep("tree", dir);
    EXPECT_EQ(a.filename(), "oak-1.json");
    EXPECT_EQ(b.filename(), "oak-2.json");
    const std::string text = test::read_file(a);
    EXPECT_NE(text.find("\"base\": 0.8"), std::string::npos);
    EXPECT_THROW(ws.keep("nope", dir), InputError);
    fs::remove_all(dir);
}

TEST(Studio, RequestsFromElsewhereAreRefused) {
    const auto allowed = studio_allowed_hosts("127.0.0.1", 8420);
    EXPECT_TRUE(studio_request_allowed(allowed, "127.0.0.1:8420", "", ""));
    EXPECT_TRUE(studio_request_allowed(allowed, "localhost:8420", "http://localhost:8420", ""));
    EXPECT_TRUE(
        studio_request_allowed(allowed, "127.0.0.1:8420", "http://127.0.0.1:8420", "same-origin"));
    EXPECT_FALSE(studio_request_allowed(allowed, "evil.example:8420", "", ""));
    EXPECT_FALSE(studio_request_allowed(allowed, "127.0.0.1:8421", "", ""));
    EXPECT_FALSE(studio_request_allowed(allowed, "", "", ""));
    EXPECT_FALSE(studio_request_allowed(allowed, "127.0.0.1:8420", "http://evil.example", ""));
    EXPECT_FALSE(studio_request_allowed(allowed, "127.0.0.1:8420", "null", ""));
    EXPECT_FALSE(studio_request_allowed(allowed, "127.0.0.1:8420", "", "cross-site"));
    // An origin is the whole of it, not a prefix: a site whose name begins with ours, another
    // port, https, a user part, a path.
    for (const char* origin :
         {"http://127.0.0.1:8420.evil.example", "http://127.0.0.1:84201", "https://127.0.0.1:8420",
          "http://127.0.0.1:8420@evil.example", "http://127.0.0.1:8420/", "http://127.0.0.1",
          "http://127.0.0.1:842"}) {
        EXPECT_FALSE(studio_request_allowed(allowed, "127.0.0.1:8420", origin, "")) << origin;
    }
    // Nor is the host: a longer name that starts with an allowed one.
    EXPECT_FALSE(studio_request_allowed(allowed, "127.0.0.1:8420.evil.example", "", ""));
    EXPECT_FALSE(studio_request_allowed(allowed, "localhost:84200", "", ""));
}

// A file is readable when it lies in a readable folder, path element by element: a folder
// beside it whose name begins with the same letters is elsewhere.
TEST(Studio, AFolderWhoseNameBeginsWithAReadableOnesIsNotReadable) {
    const fs::path dir = test::temp_dir("studio-within");
    fs::create_directories(dir / "presets" / "trees");
    fs::create_directories(dir / "presets-evil");
    fs::create_directories(dir / "scene");
    std::ofstream(dir / "presets" / "trees" / "a.json") << "{}";
    std::ofstream(dir / "presets-evil" / "b.json") << "{}";
    const std::vector<fs::path> readable = {dir / "presets"};
    auto refused = [&](const std::string& file) {
        try {
            parse_studio_change(R"({"set": {"/families/tree/preset": ")" + file + R"("}})",
                                readable, dir / "scene");
        } catch (const RequestRefused&) {
            return true;
        }
        return false;
    };
    EXPECT_FALSE(refused((dir / "presets" / "trees" / "a.json").string()));
    EXPECT_FALSE(refused("../presets/trees/a.json"));
    EXPECT_TRUE(refused((dir / "presets-evil" / "b.json").string()));
    EXPECT_TRUE(refused("../presets-evil/b.json"));
    EXPECT_TRUE(refused((dir / "presetsb.json").string()));
    EXPECT_TRUE(refused((dir / "presets" / ".." / "presets-evil" / "b.json").string()));
    // A readable folder named with a trailing separator is the same folder.
    const std::vector<fs::path> slash = {(dir / "presets").string() + "/"};
    EXPECT_THROW(parse_studio_change(R"({"set": {"/families/tree/preset": ")" +
                                         (dir / "presets-evil" / "b.json").string() + R"("}})",
                                     slash, dir / "scene"),
                 RequestRefused);
    EXPECT_NO_THROW(parse_studio_change(R"({"set": {"/families/tree/preset": ")" +
                                            (dir / "presets" / "trees" / "a.json").string() +
                                            R"("}})",
                                        slash, dir / "scene"));
    fs::remove_all(dir);
}

TEST(Studio, TheServerRoutesAndLimits) {
    StudioOptions o;
    o.preset = "birch";
    o.port = 0;
    o.save_to = fs::temp_directory_path() / "pleinair-studio-server";
    StudioServer server(o);
    const int port = server.bind();
    std::thread serving([&] { server.listen(); });
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(60, 0);
    auto page = c.Get("/");
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 200);
    EXPECT_NE(page->body.find("studio.js"), std::string::npos);
    EXPECT_EQ(c.Get("/studio.js")->status, 200);
    EXPECT_EQ(c.Get("/../CMakeLists.txt")->status, 404);
    EXPECT_EQ(c.Get("/api/catalog", {{"Origin", "http://evil.example"}})->status, 403);
    auto frame = c.Get("/api/frame?preview=1");
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->status, 200);
    EXPECT_EQ(frame->get_header_value("Content-Type"), "image/jpeg");
    auto bad = c.Post("/api/change", R"({"set": {"/families/tree/tree/trunk/taper/base": 7}})",
                      "application/json");
    EXPECT_EQ(bad->status, 400);
    EXPECT_NE(bad->body.find("must be in [0, 1], got 7"), std::string::npos);
    auto good = c.Post("/api/change", R"({"set": {"/families/tree/tree/trunk/taper/base": 0.8}})",
                       "application/json");
    EXPECT_EQ(good->status, 200);
    EXPECT_NE(good->body.find("\"level\":\"family\""), std::string::npos);
    EXPECT_EQ(c.Post("/api/change", std::string(100000, ' '), "application/json")->status, 413);
    EXPECT_EQ(c.Post("/api/change", "[1,2]", "application/json")->status, 400);
    // Files outside the preset folders, the scene's folder and --save-to are not read.
    for (const char* body : {R"({"set": {"/families/tree/preset": "/etc/passwd"}})",
                             R"({"set": {"/families/tree/preset": "../../../../etc/passwd"}})",
                             R"({"set": {"/particles": [{"file": "/etc/hosts.ply"}]}})"}) {
        auto refused = c.Post("/api/change", body, "application/json");
        EXPECT_EQ(refused->status, 400) << body;
        EXPECT_NE(refused->body.find("reads files only from"), std::string::npos) << body;
    }
    EXPECT_EQ(c.Post("/api/change", R"({"set": {"/families/tree/preset": "../trees/oak.json"}})",
                     "application/json")
                  ->status,
              200);
    auto full = c.Get("/api/frame");
    EXPECT_EQ(full->get_header_value("Content-Type"), "image/png");
    EXPECT_NE(full->get_header_value("X-Pleinair-Command").find("taper/base=0.8"),
              std::string::npos);
    server.stop();
    serving.join();
    fs::remove_all(o.save_to);
}

}  // namespace
}  // namespace pleinair
