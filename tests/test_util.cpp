// Helpers shared by the tests.
#include "test_util.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "pipeline/input/presets.h"

extern char** environ;

namespace pleinair::test {

namespace fs = std::filesystem;

fs::path source_dir() { return PLEINAIR_SOURCE_DIR; }

TreeParams preset(const std::string& name) {
    return load_tree_preset(source_dir() / "presets" / "trees" / (name + ".json"));
}

std::vector<std::string> shipped_tree_presets() {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(source_dir() / "presets" / "trees"))
        if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

uint64_t hash_bytes(const void* data, size_t size, uint64_t h) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

template <class T>
static uint64_t hash_vec(const std::vector<T>& v, uint64_t h) {
    return hash_bytes(v.data(), v.size() * sizeof(T), hash_bytes(&h, sizeof h));
}

uint64_t hash_tree(const Tree& t) {
    uint64_t h = 1469598103934665603ull;
    for (const QuadMesh* m : {&t.control, &t.render, &t.lod}) {
        h = hash_vec(m->positions, h);
        h = hash_vec(m->quads, h);
    }
    const auto& l = t.leaves;
    h = hash_vec(l.position, h);
    h = hash_vec(l.normal, h);
    h = hash_vec(l.branch_distance, h);
    h = hash_vec(l.center_distance, h);
    h = hash_vec(l.label, h);
    h = hash_vec(l.tree_id, h);
    h = hash_vec(l.fade_begin, h);
    h = hash_vec(l.fade_end, h);
    h = hash_bytes(&t.center, sizeof t.center, h);
    for (const auto& b : t.branches) {
        h = hash_vec(b.ring_centers, h);
        h = hash_vec(b.ring_radii, h);
    }
    return h;
}

Ply parse_ply(const std::string& bytes) {
    Ply ply;
    std::istringstream in(bytes);
    std::string line, element;
    std::vector<std::pair<std::string, std::string>> props;  // (type, name) of the vertex element
    if (!std::getline(in, line) || line != "ply") throw std::runtime_error("not a PLY file");
    while (std::getline(in, line) && line != "end_header") {
        std::istringstream words(line);
        std::string w;
        words >> w;
        if (w == "format") {
            words >> ply.format;
        } else if (w == "element") {
            size_t n;
            words >> element >> n;
            (element == "vertex" ? ply.vertex_count : ply.face_count) = n;
        } else if (w == "property" && element == "vertex") {
            std::string type, name;
            words >> type >> name;
            props.emplace_back(type, name);
            ply.vertex_properties.push_back(name);
        }
    }
    if (ply.format != "binary_little_endian") return ply;
    size_t offset = static_cast<size_t>(in.tellg());
    for (size_t v = 0; v < ply.vertex_count; ++v)
        for (const auto& [type, name] : props) {
            double value;
            if (type == "float") {
                float f;
                std::memcpy(&f, bytes.data() + offset, 4);
                value = f, offset += 4;
            } else if (type == "uint" || type == "int") {
                uint32_t u;
                std::memcpy(&u, bytes.data() + offset, 4);
                value = type == "uint" ? double(u) : double(int32_t(u)), offset += 4;
            } else if (type == "double") {
                std::memcpy(&value, bytes.data() + offset, 8);
                offset += 8;
            } else {
                throw std::runtime_error("unexpected PLY property type " + type);
            }
            ply.columns[name].push_back(value);
        }
    return ply;
}

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

RunResult run_pleinair(const std::string& args) {
    static int counter = 0;
    fs::path dir = temp_dir("run-" + std::to_string(counter++));
    fs::path out = dir / "stdout", err = dir / "stderr";
    std::string cmd = "cd '" + source_dir().string() + "' && '" + std::string(PLEINAIR_BIN) + "' " +
                      args + " > '" + out.string() + "' 2> '" + err.string() + "' < /dev/null";
    int status = std::system(cmd.c_str());
    RunResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read_file(out);
    r.err = read_file(err);
    fs::remove_all(dir);
    return r;
}

fs::path temp_dir(const std::string& name) {
    fs::path dir =
        fs::temp_directory_path() / ("pleinair-test-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

int spawn_pleinair(const std::vector<std::string>& args) {
    std::vector<char*> argv;
    std::string bin = PLEINAIR_BIN;
    argv.push_back(bin.data());
    std::vector<std::string> copy = args;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = -1;
    if (posix_spawn(&pid, bin.c_str(), &actions, nullptr, argv.data(), environ) != 0) pid = -1;
    posix_spawn_file_actions_destroy(&actions);
    return pid;
}

QuadMesh unit_cube() {
    QuadMesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back(
            glm::vec3(i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f));
    m.quads = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    return m;
}

ByteDiff byte_diff(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    ByteDiff d;
    if (a.size() != b.size() || a.empty()) throw std::invalid_argument("byte_diff: sizes differ");
    double sum = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const double e = static_cast<double>(a[i]) - b[i];
        sum += e * e;
        d.differ += e != 0;
    }
    d.rms = std::sqrt(sum / static_cast<double>(a.size()));
    return d;
}

}  // namespace pleinair::test
