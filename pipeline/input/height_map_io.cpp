// Height map files through OpenImageIO, checked as any input is.
#include "pipeline/input/height_map_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <system_error>

#include "pipeline/input/error.h"

namespace pleinair {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxSide = 8193;  // the terrain's own grid limit

// Why a PNG file is cut short, or "" if its chunks run whole to IEND. libpng writes its own
// "libpng error:" line to stderr before OpenImageIO reports a truncated file, which would make
// one bad input two lines; a cut file is caught here first.
std::string png_cut_short(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    char sig[8];
    if (!in.read(sig, 8) || std::memcmp(sig, "\x89PNG\r\n\x1a\n", 8) != 0) return "";  // not PNG
    in.seekg(0, std::ios::end);
    const uint64_t size = static_cast<uint64_t>(in.tellg());
    uint64_t at = 8;
    while (at + 8 <= size) {
        unsigned char head[8];
        in.seekg(static_cast<std::streamoff>(at));
        if (!in.read(reinterpret_cast<char*>(head), 8)) break;
        const uint64_t length =
            (uint64_t(head[0]) << 24) | (head[1] << 16) | (head[2] << 8) | head[3];
        const std::string type(reinterpret_cast<char*>(head + 4), 4);
        if (at + 12 + length > size) return "it ends inside its " + type + " chunk (truncated)";
        if (type == "IEND") return "";
        at += 12 + length;
    }
    return "it ends before its IEND chunk (truncated)";
}

}  // namespace

HeightMap read_height_map(const fs::path& path, double low, double high, const std::string& source,
                          const std::string& pointer) {
    // Built in place: GCC 12 warns (-Wrestrict, a false alarm) on "\"" + a temporary + "\"".
    std::string shown = path.string();
    shown.insert(shown.begin(), '"');
    shown.push_back('"');
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw InputError(source, pointer, "no height map file " + shown);
    if (const std::string cut = png_cut_short(path); !cut.empty())
        throw InputError(source, pointer, "cannot read height map " + shown + ": " + cut);
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) {
        const std::string err = first_line(OIIO::geterror());
        throw InputError(source, pointer,
                         "cannot read height map " + shown + (err.empty() ? "" : ": " + err));
    }
    const OIIO::ImageSpec& spec = in->spec();
    const OIIO::TypeDesc type = spec.format;
    const bool integer16 = type == OIIO::TypeDesc::UINT16;
    const bool floating = type == OIIO::TypeDesc::HALF || type == OIIO::TypeDesc::FLOAT ||
                          type == OIIO::TypeDesc::DOUBLE;
    if (!integer16 && !floating)
        throw InputError(source, pointer,
                         "height map " + shown + " holds " + std::string(type.c_str()) +
                             " samples; expected 16-bit (PNG, TIFF) or float (EXR, TIFF): 8 "
                             "bits give 256 heights, which terrace the ground");
    if (spec.nchannels != 1)
        throw InputError(source, pointer,
                         "height map " + shown + " has " + std::to_string(spec.nchannels) +
                             " channels; expected one (greyscale)");
    if (spec.width < 2 || spec.height < 2 || spec.width > kMaxSide || spec.height > kMaxSide)
        throw InputError(source, pointer,
                         "height map " + shown + " is " + std::to_string(spec.width) + " x " +
                             std::to_string(spec.height) + "; expected 2 to " +
                             std::to_string(kMaxSide) + " samples a side");
    HeightMap map;
    map.width = spec.width, map.height = spec.height;
    map.heights.resize(size_t(map.width) * map.height);
    // OpenImageIO converts 16-bit integers to 0..1 floats and keeps floats as they are.
    if (!in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, map.heights.data()))
        throw InputError(source, pointer,
                         "cannot read height map " + shown + ": " + first_line(in->geterror()));
    in->close();
    for (size_t k = 0; k < map.heights.size(); ++k) {
        const double h = low + double(map.heights[k]) * (high - low);
        if (!std::isfinite(map.heights[k]) || !std::isfinite(h) || std::abs(h) > 1e9)
            throw InputError(source, pointer,
                             "height map " + shown + ": the sample at column " +
                                 std::to_string(k % map.width) + ", row " +
                                 std::to_string(k / map.width) +
                                 " is not a finite height within 1e9");
        map.heights[k] = static_cast<float>(h);
    }
    return map;
}

}  // namespace pleinair
