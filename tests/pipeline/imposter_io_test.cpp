// Graftal imposter description files: the shipped ones load with their atlases, each broken file
// is refused with its key named, images are read relative to the file, and the reference
// documents every key.
#include "pipeline/input/imposter_io.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <fstream>

#include "pipeline/input/error.h"
#include "pipeline/input/presets.h"
#include "pipeline/shot/imposter_atlas.h"
#include "test_util.h"

namespace pleinair {
namespace {

std::string problem(const std::string& text, const std::string& source = "i.json") {
    try {
        parse_imposter(text, source);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

const std::string kAtlas =
    R"("atlas": {"graftals": ["fringe-blades"], "columns": 2, "cell_px": 16})";

TEST(ImposterFiles, TheShippedOnesLoadWithTheirAtlases) {
    const auto names = preset_names("imposters");
    for (const char* want : {"seuss-fringe", "grass-fringe"})
        EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
    for (const std::string& name : names) {
        SCOPED_TRACE(name);
        const ImposterDesc d = load_imposter(name);
        const ImposterAtlas atlas = imposter_atlas(d);
        EXPECT_EQ(atlas.rows, static_cast<int>(d.atlas_graftals.size()));
        EXPECT_FALSE(d.description.empty());
    }
    const ImposterDesc s = load_imposter("seuss-fringe");
    EXPECT_EQ(s.rows, (std::vector<int>{-1, 0, 0, 0, 1}));
    EXPECT_EQ(imposter_atlas(s).columns, 4);
}

TEST(ImposterFiles, BrokenFilesNameTheirKey) {
    EXPECT_EQ(problem("{" + kAtlas + "}"), "");
    EXPECT_NE(problem("{}").find("/atlas: missing"), std::string::npos) << problem("{}");
    EXPECT_NE(problem("{" + kAtlas + R"(, "heigth": 1})").find("/heigth"), std::string::npos);
    EXPECT_NE(problem("{" + kAtlas + R"(, "height": -1})").find("/height"), std::string::npos);
    EXPECT_NE(problem("{" + kAtlas + R"(, "uv": "sphere"})").find("/uv"), std::string::npos);
    EXPECT_NE(
        problem(R"({"atlas": {"graftals": ["fringe-blades"], "image": "a.png"}})").find("not both"),
        std::string::npos);
    EXPECT_NE(problem(R"({"atlas": {"graftals": []}})").find("/atlas/graftals"), std::string::npos);
    EXPECT_NE(problem(R"({"atlas": {"graftals": ["fringe-blades", "no-such-graftal"]}})")
                  .find("/atlas/graftals/1"),
              std::string::npos);
    // One row in the atlas: a control row of 1 does not exist.
    const std::string rows = problem("{" + kAtlas + R"(, "control": {"rows": [0, 1]}})");
    EXPECT_NE(rows.find("/control/rows/1"), std::string::npos) << rows;
    EXPECT_NE(problem("{" + kAtlas + R"(, "control": {"rows": [0.5]}})").find("/control/rows/0"),
              std::string::npos);
    EXPECT_NE(
        problem("{" + kAtlas + R"(, "direction": {"normal": 0, "up": 0}})").find("/direction"),
        std::string::npos);
    EXPECT_NE(problem("{" + kAtlas + R"(, "color": {"top": [2, 0, 0]}})").find("/color/top"),
              std::string::npos);
    // A missing image: the key that names it.
    const std::string img = problem(R"({"atlas": {"image": "nowhere.png", "columns": 2}})");
    EXPECT_NE(img.find("/atlas/image"), std::string::npos) << img;
    EXPECT_NE(img.find("nowhere.png"), std::string::npos) << img;
    EXPECT_NE(
        problem("{" + kAtlas + R"(, "control": {"image": "none.png"}})").find("/control/image"),
        std::string::npos);
}

TEST(ImposterFiles, ImagesAreReadNearTheFile) {
    const auto dir = test::temp_dir("imposter_io");
    // A 4 x 2 atlas image, two columns of 2 x 2 cells, straight alpha; a control image.
    auto write = [&](const char* name, int w, int h, const std::vector<float>& rgba) {
        auto out = OIIO::ImageOutput::create((dir / name).string());
        ASSERT_TRUE(out);
        ASSERT_TRUE(
            out->open((dir / name).string(), OIIO::ImageSpec(w, h, 4, OIIO::TypeDesc::UINT8)));
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgba.data()));
        out->close();
    };
    std::vector<float> atlas(4 * 2 * 4, 0.0f);
    for (size_t i = 0; i < atlas.size(); i += 4) atlas[i] = 1, atlas[i + 3] = 1;
    write("atlas.png", 4, 2, atlas);
    std::vector<float> control = {0, 1, 0, 1, 0, 1, 0, 1};
    write("control.png", 2, 1, control);
    std::ofstream(dir / "fur.json") << R"({"atlas": {"image": "atlas.png", "columns": 2},
        "control": {"image": "control.png"}})";
    const ImposterDesc d = load_imposter((dir / "fur.json").string());
    const ImposterAtlas drawn = imposter_atlas(d);
    EXPECT_EQ(drawn.columns, 2);
    EXPECT_EQ(drawn.cell_w, 2);
    EXPECT_EQ(drawn.cell_h, 2);
    EXPECT_EQ(d.control.width, 2);
    EXPECT_EQ(control_row(d, {0.5f, 0.5f}), 1);  // green: the second row
    // Cells that do not fit the image.
    std::ofstream(dir / "big.json") << R"({"atlas": {"image": "atlas.png", "columns": 8}})";
    try {
        load_imposter((dir / "big.json").string());
        ADD_FAILURE() << "8 columns of a 4-pixel image";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/atlas/image"), std::string::npos) << e.what();
    }
}

TEST(ImposterFiles, TheReferenceDocumentsEveryKey) {
    const std::string ref = imposter_reference();
    for (const char* key :
         {"`/height`", "`/width`", "`/mesh`", "`/uv`", "`/fade`", "`/min_edge_px`", "`/light`",
          "`/atlas/image`", "`/atlas/columns`", "`/atlas/graftals`", "`/control/rows`",
          "`/control/coverage`", "`/direction/normal`", "`/direction/up`", "`/color/bottom`"})
        EXPECT_NE(ref.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace pleinair
