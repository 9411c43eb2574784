// Every committed fuzz input (the seed corpus and each minimised finding under
// tests/fuzz/regressions) replayed through its target on every test run: a finding fixed
// stays fixed. A target aborts on a finding, which fails the run.
#include <gtest/gtest.h>

#include <filesystem>

#include "targets.h"
#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;

TEST(Fuzz, CommittedInputsAreAcceptedOrRefusedCleanly) {
    const fs::path root = test::source_dir() / "tests" / "fuzz";
    for (const fuzz::Target& t : fuzz::kTargets) {
        size_t replayed = 0;
        for (const char* kind : {"corpus", "regressions"}) {
            const fs::path dir = root / kind / t.name;
            if (!fs::is_directory(dir)) continue;
            for (const auto& entry : fs::directory_iterator(dir)) {
                const std::string bytes = test::read_file(entry.path());
                t.run(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
                ++replayed;
            }
        }
        // Every target has a seed corpus to start from.
        EXPECT_GE(replayed, 3u) << t.name;
    }
}

}  // namespace
}  // namespace pleinair
