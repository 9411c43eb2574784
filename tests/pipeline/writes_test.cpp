// Writes that never lie: temporaries' names, leftovers of killed runs, folders complete or absent,
// the same bytes from the same frame, a full disk (a real tmpfs) and runs stopped by a signal.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "pipeline/input/error.h"
#include "pipeline/output/image_io.h"
#include "pipeline/output/partial_files.h"
#include "pipeline/output/tree_io.h"
#include "pipeline/output/write_file.h"
#include "test_util.h"

extern char** environ;

namespace pleinair {
namespace {

namespace fs = std::filesystem;
using test::run_pleinair;

void write_text(const fs::path& p, const std::string& s) {
    std::ofstream(p, std::ios::binary) << s;
}

// Every name in `dir` and below that is a temporary.
std::vector<std::string> partials_in(const fs::path& dir) {
    std::vector<std::string> found;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (is_partial_name(e.path().filename().string())) found.push_back(e.path().string());
    return found;
}

// A PID that was a process a moment ago and is none now.
long dead_pid() {
    pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ::waitpid(child, nullptr, 0);
    return child;
}

TEST(PartialFiles, NamesAreRecognisedByOnePredicate) {
    const std::string pid = std::to_string(::getpid());
    const std::string at = "@" + partial_host(partial_path("x").filename().string());
    EXPECT_EQ(partial_path("out/frame.png"), fs::path("out/.frame.png.partial-" + pid + at));
    EXPECT_EQ(partial_path("out/tree/"), fs::path("out/.tree.partial-" + pid + at));
    EXPECT_TRUE(is_partial_name(partial_path("a/x.exr").filename().string()));
    EXPECT_TRUE(is_partial_name(".x.png.partial-12"));
    EXPECT_TRUE(is_partial_name(".x.partial-12.png"));  // the older image form
    EXPECT_TRUE(is_partial_name(".oak-001-seed-5.partial-7"));
    EXPECT_EQ(partial_pid(".x.png.partial-4321"), 4321);
    EXPECT_EQ(partial_pid(".x.png.partial-4321@node-7.farm"), 4321);
    EXPECT_EQ(partial_host(".x.png.partial-4321@node-7.farm"), "node-7.farm");
    EXPECT_EQ(partial_host(".x.png.partial-4321"), "");
    for (const char* real : {"x.png", ".x.png", "x.png.partial-12", ".partial-12", ".x.partial-",
                             ".x.partial-12a", ".x.partial-0", ".x.partial-12.", ".x.partial-1.p-g",
                             ".x.partial-12@", ".x.partial-12@a/b", ".x.partial-@host"})
        EXPECT_FALSE(is_partial_name(real)) << real;
}

// What a SIGKILL leaves: temporaries of a dead PID, files and folders. clear_partials removes
// those and nothing else.
TEST(PartialFiles, ClearPartialsRemovesDeadWritersLeftoversOnly) {
    auto dir = test::temp_dir("clear-partials");
    const std::string dead = std::to_string(dead_pid());
    const std::string live = std::to_string(::getpid());
    write_text(dir / (".x.png.partial-" + dead), "torn");
    write_text(dir / (".x.partial-" + dead + ".png"), "torn");  // an older build's leftover
    fs::create_directories(dir / (".tree.partial-" + dead) / "sub");
    write_text(dir / (".tree.partial-" + dead) / "sub" / "render.obj", "v");
    // This machine's own names carry its host.
    const std::string ours = partial_path(dir / "w.png").filename().string();
    const std::string host = partial_host(ours);
    ASSERT_FALSE(host.empty());
    EXPECT_EQ(partial_pid(ours), ::getpid());
    write_text(dir / (".w.png.partial-" + dead + "@" + host), "torn");
    const std::vector<std::string> kept = {
        "x.png",
        ".hidden",
        "notes.partial-" + dead,
        ".y.png.partial-" + live,
        ".z.partial-1",                                         // init
        ".v.png.partial-" + dead + "@" + host + "-elsewhere"};  // another machine's writer
    for (const auto& name : kept) write_text(dir / name, name);
    EXPECT_EQ(clear_partials(dir), 4u);
    std::vector<std::string> left;
    for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename());
    std::sort(left.begin(), left.end());
    std::vector<std::string> expect = kept;
    std::sort(expect.begin(), expect.end());
    EXPECT_EQ(left, expect);
    for (const auto& name : kept) EXPECT_EQ(test::read_file(dir / name), name);
    EXPECT_EQ(clear_partials(dir / "absent"), 0u);
    fs::remove_all(dir);
}

TEST(PartialFiles, FailedWriteLeavesNoTemporaryAndTheEarlierFile) {
    auto dir = test::temp_dir("failed-write");
    write_text(dir / "a.txt", "earlier");
    write_file_atomic(dir / "a.txt", "later");
    EXPECT_EQ(test::read_file(dir / "a.txt"), "later");
    // A folder where the file should go: the rename fails after every byte was written.
    fs::create_directories(dir / "b.txt" / "inside");
    try {
        write_file_atomic(dir / "b.txt", "bytes");
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find((dir / "b.txt").string()), std::string::npos)
            << e.what();
    }
    EXPECT_TRUE(fs::is_directory(dir / "b.txt" / "inside"));
    EXPECT_EQ(partials_in(dir), std::vector<std::string>{});
    fs::remove_all(dir);
}

// A tree's folder is replaced as a whole; a folder that is not a tree's is never touched.
TEST(PartialFiles, TreeFolderReplacesAnEarlierOneWhole) {
    auto dir = test::temp_dir("tree-replace");
    Tree a = generate_tree(test::preset("shrub"), 1);
    TreeOptions no_lod;
    no_lod.lod = false;
    Tree b = generate_tree(test::preset("shrub"), 2, no_lod);
    write_tree(a, "shrub", dir / "t");
    ASSERT_TRUE(fs::exists(dir / "t" / "lod.obj"));
    write_tree(b, "shrub", dir / "t");
    EXPECT_FALSE(fs::exists(dir / "t" / "lod.obj"));  // nothing of the earlier tree is left
    EXPECT_EQ(test::read_file(dir / "t" / "tree.json"), tree_json(b, "shrub"));
    fs::create_directories(dir / "mine");
    write_text(dir / "mine" / "notes.txt", "keep");
    EXPECT_THROW(write_tree(a, "shrub", dir / "mine"), InputError);
    EXPECT_EQ(test::read_file(dir / "mine" / "notes.txt"), "keep");
    auto r = run_pleinair("tree --preset shrub -o " + (dir / "mine").string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(partials_in(dir), std::vector<std::string>{});
    fs::remove_all(dir);
}

// Same inputs, same bytes: no header carries the time the file was written.
TEST(Writes, AFrameHoldingANaNOrAnInfIsNeverWritten) {
    // The 8-bit path maps NaN to 0 and the 16-bit one to some level: neither may see one.
    const auto dir = test::temp_dir("writes-nan");
    Frame f;
    f.width = 4, f.height = 3;
    f.rgba.assign(4 * 12, 0.5f);
    for (float bad : {NAN, INFINITY, -INFINITY}) {
        for (const char* name : {"a.png", "a.tif", "a.exr"}) {
            Frame g = f;
            g.rgba[4 * 7 + 1] = bad;
            EXPECT_EQ(non_finite_values(g), 1u);
            try {
                write_frame(dir / name, g);
                ADD_FAILURE() << name << " written with " << bad;
            } catch (const std::runtime_error& e) {
                EXPECT_NE(std::string(e.what()).find("holds 1 values that are not finite"),
                          std::string::npos)
                    << e.what();
            }
            EXPECT_TRUE(fs::is_empty(dir)) << name;
        }
    }
    // In an AOV too.
    Frame h = f;
    h.has_aovs = true;
    h.depth.assign(12, 1.0f), h.object_id.assign(12, 0.0f), h.alpha.assign(12, 1.0f);
    h.lightness.assign(12, 0.5f);
    h.depth[5] = NAN;
    EXPECT_EQ(non_finite_values(h), 1u);
    EXPECT_THROW(write_frame(dir / "b.exr", h), std::runtime_error);
    EXPECT_EQ(non_finite_values(f), 0u);
}

TEST(Writes, SameFrameTwiceGivesIdenticalBytesInEveryFormat) {
    auto dir = test::temp_dir("same-bytes");
    for (const char* name : {"a.png", "a.tif", "a.exr"}) {
        std::string files[2];
        for (int i = 0; i < 2; ++i) {
            auto r = run_pleinair("render tests/golden/oak-study/scene.json -o " +
                                  (dir / name).string());
            ASSERT_EQ(r.exit_code, 0) << r.err;
            files[i] = test::read_file(dir / name);
            // The TIFF and EXR writers stamp the time to the second.
            if (i == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1100));
        }
        EXPECT_GT(files[0].size(), 1000u) << name;
        EXPECT_TRUE(files[0] == files[1]) << name << " differs between two runs";
    }
    fs::remove_all(dir);
}

// A failing write injected without root: the shell's file-size limit (RLIMIT_FSIZE, inherited
// by pleinair) makes every write past 16 KiB fail with EFBIG midway through the file. Each
// output fails naming its file, exit 1; the earlier file of that name is byte-identical and no
// temporary is left. Runs anywhere (FullDisk below needs root to mount a tmpfs).
TEST(Writes, AWriteFailingMidwayLeavesTheEarlierFileAndNoTemporary) {
    const fs::path dir = test::temp_dir("fsize-limit");
    const std::string scene = "tests/golden/oak-study/scene.json";
    for (const char* name : {"x.png", "x.tif", "x.exr"}) {
        SCOPED_TRACE(name);
        const fs::path out = dir / name;
        auto r = run_pleinair("render " + scene + " -o " + out.string() +
                              " --set /camera/width=16 --set /camera/height=16");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const std::string earlier = test::read_file(out);
        ASSERT_LT(earlier.size(), 16000u);
        // The same name again at full size, under the limit of 16 blocks of 1 KiB.
        const std::string cmd = "cd '" + test::source_dir().string() + "' && (ulimit -f 16; '" +
                                std::string(PLEINAIR_BIN) + "' render " + scene + " -o '" +
                                out.string() + "' > '" + (dir / "err").string() + "' 2>&1)";
        const int status = std::system(cmd.c_str());
        ASSERT_TRUE(WIFEXITED(status));
        EXPECT_EQ(WEXITSTATUS(status), 1) << test::read_file(dir / "err");
        const std::string err = test::read_file(dir / "err");
        EXPECT_NE(err.find(out.string()), std::string::npos) << err;
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << "one line: " << err;
        EXPECT_TRUE(test::read_file(out) == earlier) << "the earlier file was changed";
        fs::remove(dir / "err");
        EXPECT_EQ(partials_in(dir), std::vector<std::string>{});
    }
    fs::remove_all(dir);
}

// A 64 KiB tmpfs mounted for the test and filled to the brim: what a full disk does to every
// kind of output. Needs root (CI runs it as root); skips saying so otherwise.
class FullDisk : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = test::temp_dir("full-disk");
        if (::geteuid() != 0)
            GTEST_SKIP() << "skipped: mounting a tmpfs needs root (running as uid " << ::geteuid()
                         << "); CI runs this test as root";
        if (::mount("tmpfs", dir_.c_str(), "tmpfs", 0, "size=64k") != 0)
            GTEST_SKIP() << "skipped: cannot mount a tmpfs on " << dir_ << ": "
                         << std::strerror(errno) << " (a container without CAP_SYS_ADMIN?)";
        mounted_ = true;
    }
    void TearDown() override {
        if (mounted_ && ::umount(dir_.c_str()) != 0)
            ADD_FAILURE() << "cannot unmount " << dir_ << ": " << std::strerror(errno);
        fs::remove_all(dir_);
    }
    // Takes every free byte left.
    void fill() {
        const int fd = ::open((dir_ / "fill").c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        ASSERT_GE(fd, 0);
        const std::string chunk(512, 'x');
        while (::write(fd, chunk.data(), chunk.size()) > 0) {
        }
        ::close(fd);
    }
    // A failed run: exit 1, one line naming `target`, no temporary left.
    void expect_failed(const test::RunResult& r, const fs::path& target) {
        EXPECT_EQ(r.exit_code, 1) << r.err;
        EXPECT_NE(r.err.find(target.string()), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
        EXPECT_EQ(partials_in(dir_), std::vector<std::string>{});
    }
    fs::path dir_;
    bool mounted_ = false;
};

TEST_F(FullDisk, ImagesFailNamingTheFileAndLeaveTheEarlierOneByteIdentical) {
    const std::string small = " --set /camera/width=16 --set /camera/height=16";
    for (const char* name : {"x.png", "x.tif", "x.exr"}) {
        auto r = run_pleinair("render tests/golden/oak-study/scene.json -o " +
                              (dir_ / name).string() + small);
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    std::map<std::string, std::string> earlier;
    for (const char* name : {"x.png", "x.tif", "x.exr"})
        earlier[name] = test::read_file(dir_ / name);
    fill();
    for (const char* name : {"x.png", "x.tif", "x.exr"}) {
        auto r =
            run_pleinair("render tests/golden/oak-study/scene.json -o " + (dir_ / name).string());
        expect_failed(r, dir_ / name);
        EXPECT_TRUE(test::read_file(dir_ / name) == earlier[name]) << name << " was changed";
    }
    // A contact sheet over the earlier PNG.
    auto r = run_pleinair("family --preset oak --count 2 --width 320 --height 240 -o " +
                          (dir_ / "x.png").string());
    expect_failed(r, dir_ / "x.png");
    EXPECT_TRUE(test::read_file(dir_ / "x.png") == earlier["x.png"]);
}

TEST_F(FullDisk, TreeAndFamilyFoldersAreCompleteOrAbsent) {
    // An earlier tree folder (a stand-in small enough for the disk) survives a failed write.
    fs::create_directories(dir_ / "earlier");
    write_text(dir_ / "earlier" / "tree.json", "{\"earlier\": true}\n");
    fill();
    auto tree = run_pleinair("tree --preset shrub -o " + (dir_ / "tree").string());
    expect_failed(tree, dir_ / "tree");
    EXPECT_FALSE(fs::exists(dir_ / "tree"));
    tree = run_pleinair("tree --preset shrub -o " + (dir_ / "earlier").string());
    expect_failed(tree, dir_ / "earlier");
    EXPECT_EQ(test::read_file(dir_ / "earlier" / "tree.json"), "{\"earlier\": true}\n");
    auto family = run_pleinair("family --preset shrub --count 3 -o " + (dir_ / "fam").string());
    expect_failed(family, dir_ / "fam");
    EXPECT_FALSE(fs::exists(dir_ / "fam"));
}

// SIGTERM and SIGINT while a family is being written: the run ends by that signal and its
// temporary folder, with every member written so far, is gone.
TEST(Signals, SigtermAndSigintRemoveTheTemporaries) {
    for (int sig : {SIGTERM, SIGINT}) {
        auto dir = test::temp_dir("signal-" + std::to_string(sig));
        pid_t pid = test::spawn_pleinair(
            {"family", "--preset", "shrub", "--count", "400", "-o", (dir / "fam").string()});
        ASSERT_GT(pid, 0);
        // Members are written into the temporary folder for seconds; signal once it holds a few.
        const fs::path tmp = dir / (".fam.partial-" + std::to_string(pid) + "@" +
                                    partial_host(partial_path("x").filename().string()));
        bool writing = false;
        for (int i = 0; i < 600 && !writing; ++i) {
            std::error_code ec;
            writing = fs::exists(tmp) &&
                      std::distance(fs::directory_iterator(tmp, ec), fs::directory_iterator()) >= 3;
            if (!writing) std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
        EXPECT_TRUE(writing) << "no temporary folder appeared in 30 s";
        ::kill(pid, sig);
        int status = 0;
        ASSERT_EQ(::waitpid(pid, &status, 0), pid);
        const bool by_signal = WIFSIGNALED(status) && WTERMSIG(status) == sig;
        const bool by_code = WIFEXITED(status) && WEXITSTATUS(status) == 128 + sig;
        EXPECT_TRUE(by_signal || by_code) << "signal " << sig << ": status " << status;
        EXPECT_EQ(partials_in(dir), std::vector<std::string>{}) << "signal " << sig;
        EXPECT_FALSE(fs::exists(dir / "fam"));
        fs::remove_all(dir);
    }
}

}  // namespace
}  // namespace pleinair
