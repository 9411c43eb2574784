// The house's layout holds (DESIGN.md, issue 24 §4): pipeline/ is laid out by lifetime, input/
// < shot/ < frame/ < output/ < bench/ < cli/, and a folder includes only those before it; no
// include loop, counting a .cpp with its .h; generators/ and shading/ include nothing of
// pipeline/; no file name stands in two folders.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "test_util.h"

namespace pleinair {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kOrder = {"input", "shot",   "frame", "output",
                                         "bench", "studio", "cli"};

// Each source file of `dir` (relative to the source root) with the quoted includes it names.
std::map<std::string, std::vector<std::string>> includes_under(const std::string& dir) {
    std::map<std::string, std::vector<std::string>> out;
    const fs::path root = test::source_dir();
    for (const auto& e : fs::recursive_directory_iterator(root / dir)) {
        const std::string ext = e.path().extension().string();
        if (ext != ".h" && ext != ".cpp") continue;
        const std::string name = fs::relative(e.path(), root).string();
        std::ifstream in(e.path());
        std::vector<std::string>& inc = out[name];
        for (std::string line; std::getline(in, line);) {
            const std::string head = "#include \"";
            if (line.rfind(head, 0) != 0) continue;
            const size_t end = line.find('"', head.size());
            if (end != std::string::npos)
                inc.push_back(line.substr(head.size(), end - head.size()));
        }
    }
    return out;
}

// pipeline/FOLDER/...: its place in kOrder; -1 outside.
int rank_of(const std::string& path) {
    for (size_t i = 0; i < kOrder.size(); ++i)
        if (path.rfind("pipeline/" + kOrder[i] + "/", 0) == 0) return static_cast<int>(i);
    return -1;
}

std::string node_of(const std::string& path) { return path.substr(0, path.rfind('.')); }

TEST(Layout, EachFolderIncludesOnlyThoseBeforeIt) {
    const auto files = includes_under("pipeline");
    ASSERT_GT(files.size(), 100u);
    for (const auto& [file, incs] : files) {
        const int from = rank_of(file);
        if (file.rfind("pipeline/farm/", 0) == 0) continue;
        EXPECT_GE(from, 0) << file << " lies outside "
                           << "input/ shot/ frame/ output/ bench/ cli/";
        for (const std::string& inc : incs) {
            if (inc.rfind("pipeline/", 0) != 0) continue;
            EXPECT_LE(rank_of(inc), from) << file << " includes " << inc << ", a later folder";
        }
    }
    for (const char* dir : {"generators", "shading"})
        for (const auto& [file, incs] : includes_under(dir))
            for (const std::string& inc : incs)
                EXPECT_NE(inc.rfind("pipeline/", 0), 0u) << file << " includes " << inc;
}

TEST(Layout, NoIncludeLoopCountingACppWithItsHeader) {
    std::map<std::string, std::set<std::string>> edges;
    for (const auto& [file, incs] : includes_under("pipeline"))
        for (const std::string& inc : incs)
            if (inc.rfind("pipeline/", 0) == 0 && node_of(inc) != node_of(file))
                edges[node_of(file)].insert(node_of(inc));
    // Depth-first, colouring nodes; a grey node met again closes a loop, printed whole.
    std::map<std::string, int> colour;
    std::vector<std::string> stack;
    std::string loop;
    std::function<void(const std::string&)> visit = [&](const std::string& n) {
        colour[n] = 1;
        stack.push_back(n);
        for (const std::string& m : edges[n]) {
            if (!loop.empty()) break;
            if (colour[m] == 1) {
                for (auto it = std::find(stack.begin(), stack.end(), m); it != stack.end(); ++it)
                    loop += *it + " -> ";
                loop += m;
            } else if (colour[m] == 0) {
                visit(m);
            }
        }
        stack.pop_back();
        colour[n] = 2;
    };
    for (const auto& [n, _] : edges)
        if (colour[n] == 0 && loop.empty()) visit(n);
    EXPECT_EQ(loop, "") << "an include loop";
}

TEST(Layout, NoFileNameInTwoFolders) {
    std::map<std::string, std::string> seen;
    for (const char* dir : {"pipeline", "generators", "shading"})
        for (const auto& [file, _] : includes_under(dir)) {
            const std::string name = fs::path(file).filename().string();
            const auto [it, fresh] = seen.emplace(name, file);
            EXPECT_TRUE(fresh) << name << " stands in " << it->second << " and " << file;
        }
}

}  // namespace
}  // namespace pleinair
