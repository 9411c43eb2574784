// Golden images: every tests/golden/<case>/scene.json painted and compared with the
// reference.png beside it, within the tolerance stated in tests/golden/README.md.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "pipeline/image_io.h"
#include "pipeline/paint.h"
#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;

TEST(GoldenImages, MatchTheirReferences) {
    fs::path root = test::source_dir() / "tests" / "golden";
    int cases = 0;
    for (const auto& entry : fs::directory_iterator(root)) {
        if (!entry.is_directory()) continue;
        const std::string name = entry.path().filename().string();
        SCOPED_TRACE(name);
        SceneDesc scene = load_scene(entry.path() / "scene.json");
        Frame frame = paint_still(scene);
        std::vector<uint8_t> got = frame_srgb8(frame);

        auto in = OIIO::ImageInput::open((entry.path() / "reference.png").string());
        ASSERT_TRUE(in) << "missing reference; see tests/golden/README.md";
        const OIIO::ImageSpec& spec = in->spec();
        ASSERT_EQ(spec.width, frame.width);
        ASSERT_EQ(spec.height, frame.height);
        ASSERT_EQ(spec.nchannels, 3);
        std::vector<uint8_t> want(got.size());
        ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, want.data()));
        in->close();

        double sq = 0;
        size_t far = 0;
        for (size_t i = 0; i < got.size(); ++i) {
            int d = int(got[i]) - int(want[i]);
            sq += d * d;
            far += std::abs(d) > 16;
        }
        double rmse = std::sqrt(sq / got.size());
        EXPECT_LE(rmse, 1.0) << "RMSE in 8-bit levels";
        EXPECT_LE(far, got.size() / 200) << "values off by more than 16 levels";
        ++cases;
    }
    EXPECT_GE(cases, 6);
}

}  // namespace
}  // namespace pleinair
