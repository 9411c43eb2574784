// OpenImageIO writers into a file in memory whose bytes write_file_atomic writes; the only file
// that includes OpenImageIO.
#include "pipeline/output/image_io.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "pipeline/input/error.h"
#include "pipeline/output/write_file.h"
#include "shading/color.h"

namespace pleinair {

namespace fs = std::filesystem;

std::string lower_ext(const fs::path& p) {
    std::string e = p.extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
    return e;
}

namespace {

// Linear premultiplied over an opaque background: the colour is the premultiplied value.
float channel(const Frame& f, size_t i, int c) {
    float v = f.rgba[4 * i + c];
    return std::isfinite(v) ? v : 0.0f;
}
}  // namespace

bool is_image_path(const fs::path& path) {
    std::string e = lower_ext(path);
    return e == ".png" || e == ".tif" || e == ".tiff" || e == ".exr";
}

bool is_other_image_path(const fs::path& path) {
    static const char* const kOthers[] = {".jpg", ".jpeg", ".bmp", ".gif",  ".webp", ".tga",
                                          ".hdr", ".jp2",  ".dpx", ".heic", ".avif", ".ppm",
                                          ".pnm", ".psd",  ".ico", ".jxl"};
    const std::string e = lower_ext(path);
    return std::find(std::begin(kOthers), std::end(kOthers), e) != std::end(kOthers);
}

namespace {

uint8_t srgb8_exact(float v) {
    return static_cast<uint8_t>(std::lround(255.0f * linear_to_srgb(v)));
}

// The smallest linear value that encodes to each 8-bit level, found once by bisection over the
// float bit patterns of [0, 1] (their order is the numbers' order). Encoding is then a search
// among 255 boundaries instead of a pow per channel, with the same result.
struct Srgb8Boundaries {
    std::array<float, 256> lo{};
    Srgb8Boundaries() {
        uint32_t one;
        float f1 = 1.0f;
        std::memcpy(&one, &f1, sizeof one);
        for (int level = 1; level < 256; ++level) {
            uint32_t a = 0, b = one;  // srgb8(a) < level <= srgb8(b)
            while (b - a > 1) {
                uint32_t m = a + (b - a) / 2;
                float x;
                std::memcpy(&x, &m, sizeof x);
                (srgb8_exact(x) >= level ? b : a) = m;
            }
            std::memcpy(&lo[level], &b, sizeof b);
        }
    }
};

// A first guess from 4096 buckets of the linear value, corrected against the boundaries.
struct Srgb8Table {
    Srgb8Boundaries b;
    std::array<uint8_t, 4097> guess{};
    Srgb8Table() {
        for (int i = 0; i <= 4096; ++i) {
            float v = static_cast<float>(i) / 4096.0f;
            guess[i] = static_cast<uint8_t>(std::upper_bound(b.lo.begin() + 1, b.lo.end(), v) -
                                            b.lo.begin() - 1);
        }
    }
};

uint8_t srgb8(float v) {
    static const Srgb8Table table;
    if (!(v > 0.0f)) return 0;
    if (v >= 1.0f) return 255;
    int level = table.guess[static_cast<int>(v * 4096.0f)];
    while (level < 255 && v >= table.b.lo[level + 1]) ++level;
    while (level > 0 && v < table.b.lo[level]) --level;
    return static_cast<uint8_t>(level);
}

// An anonymous file in memory (memfd), which a library opens by its /proc/self/fd name.
class MemoryFile {
  public:
    explicit MemoryFile(const fs::path& target)
        : fd_(::memfd_create("pleinair-image", MFD_CLOEXEC)) {
        if (fd_ < 0)
            throw std::runtime_error("cannot write " + target.string() +
                                     ": no file in memory: " + std::strerror(errno));
        target_ = target;
    }
    ~MemoryFile() { ::close(fd_); }
    MemoryFile(const MemoryFile&) = delete;
    MemoryFile& operator=(const MemoryFile&) = delete;

    std::string name() const { return "/proc/self/fd/" + std::to_string(fd_); }

    std::string bytes() const {
        struct stat st;
        if (::fstat(fd_, &st) != 0) fail(errno);
        // The memory file is a file: past the file-size limit (ulimit -f) its writes failed
        // with EFBIG, which the PNG writer notes and then reports success. A file that reached
        // the limit was cut there.
        struct rlimit fsize;
        if (::getrlimit(RLIMIT_FSIZE, &fsize) == 0 && fsize.rlim_cur != RLIM_INFINITY &&
            static_cast<rlim_t>(st.st_size) >= fsize.rlim_cur)
            fail(EFBIG);
        std::string b(static_cast<size_t>(st.st_size), '\0');
        for (size_t done = 0; done < b.size();) {
            ssize_t n = ::pread(fd_, b.data() + done, b.size() - done, static_cast<off_t>(done));
            if (n > 0)
                done += static_cast<size_t>(n);
            else if (n == 0 || errno != EINTR)
                fail(n == 0 ? EIO : errno);
        }
        return b;
    }

  private:
    [[noreturn]] void fail(int err) const {
        throw std::runtime_error("cannot write " + target_.string() + ": " + std::strerror(err));
    }
    int fd_;
    fs::path target_;
};

}  // namespace

size_t non_finite_values(const Frame& f) {
    auto count = [](const std::vector<float>& v) {
        return tbb::parallel_reduce(
            tbb::blocked_range<size_t>(0, v.size(), 1 << 16), size_t{0},
            [&](const auto& r, size_t n) {
                for (size_t i = r.begin(); i < r.end(); ++i) n += !std::isfinite(v[i]);
                return n;
            },
            std::plus<>());
    };
    return count(f.rgba) + count(f.depth) + count(f.object_id) + count(f.alpha) +
           count(f.lightness);
}

double output_bytes_per_pixel(const fs::path& path, bool aovs) {
    const std::string ext = lower_ext(path);
    if (ext == ".exr") return (aovs ? 8 : 4) * 6.0;  // float, then OpenImageIO's half copy
    return ext == ".png" ? 3.0 : 6.0;
}

std::vector<uint8_t> frame_srgb8(const Frame& f) {
    const size_t n = static_cast<size_t>(f.width) * f.height;
    std::vector<uint8_t> out(3 * n);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const auto& r) {
        for (size_t i = r.begin(); i < r.end(); ++i)
            for (int c = 0; c < 3; ++c) out[3 * i + c] = srgb8(channel(f, i, c));
    });
    return out;
}

namespace {

// Encodes with the writer the target's name picks, then writes the bytes whole or not at all.
void write_image_atomic(const fs::path& path, const OIIO::ImageSpec& spec, OIIO::TypeDesc in_type,
                        const void* data) {
    // OpenImageIO's writers cannot be trusted with the disk: the PNG writer notes a failed write
    // and reports success (a full disk gave exit 0 and a truncated image), the TIFF writer's
    // close "cannot fail" though it writes the directory then, and 2.4's TIFF writer corrupts
    // its file when given an IOProxy. So the writer writes into a file in memory, opened by name
    // like any file, and write_file_atomic writes its bytes, checking every write, the fsync
    // and the close. The bytes are those the writer gives a file on disk.
    MemoryFile memory(path);
    auto out = OIIO::ImageOutput::create(path.string());  // the format from the target's name
    bool ok =
        out && out->open(memory.name(), spec) && out->write_image(in_type, data) && out->close();
    // A writer that noted a failed write but returned true (the PNG writer, past a file-size
    // limit: the memory file is a file too) is a failure all the same.
    ok = ok && !out->has_error();
    if (!ok) {
        std::string err = out ? out->geterror() : OIIO::geterror();
        // One line: a writer may note a failure per block written.
        if (const size_t eol = err.find('\n'); eol != std::string::npos) err.resize(eol);
        while (!err.empty() && err.back() == ' ') err.pop_back();
        throw std::runtime_error("cannot write " + path.string() + ": " +
                                 (err.empty() ? "OpenImageIO cannot encode it" : err));
    }
    out.reset();
    write_file_atomic(path, memory.bytes());
}

}  // namespace

void write_frame(const fs::path& path, const Frame& f) {
    const std::string ext = lower_ext(path);
    if (!is_image_path(path))
        throw InputError("-o", "",
                         "cannot write \"" + path.string() +
                             "\": the extension must be .png, .tif, .tiff or .exr");
    const size_t n = static_cast<size_t>(f.width) * f.height;
    // No NaN or Inf reaches an output: the 8-bit and 16-bit conversions would quietly turn one
    // into a colour, so a frame holding one is a bug reported, not an image written.
    const size_t bad = non_finite_values(f);
    if (bad > 0)
        throw std::runtime_error("the frame for " + path.string() + " holds " +
                                 std::to_string(bad) + " values that are not finite; not written");
    OIIO::ImageSpec spec;
    std::vector<float> linear;
    std::vector<uint16_t> u16;
    std::vector<uint8_t> u8;
    const void* data = nullptr;
    OIIO::TypeDesc in_type;
    if (ext == ".exr") {
        std::vector<std::string> names = {"R", "G", "B", "A"};
        if (f.has_aovs) names.insert(names.end(), {"Z", "object_id", "stroke_alpha", "lightness"});
        const int nc = static_cast<int>(names.size());
        spec = OIIO::ImageSpec(f.width, f.height, nc, OIIO::TypeDesc::HALF);
        spec.channelnames = names;
        spec.alpha_channel = 3;
        if (f.has_aovs) {
            spec.z_channel = 4;
            // Depth and ids in float: half holds whole numbers exactly only to 2048 and
            // overflows past 65504 (surface strokes' ids are 65536 + their material).
            const OIIO::TypeDesc h = OIIO::TypeDesc::HALF, f32 = OIIO::TypeDesc::FLOAT;
            spec.channelformats = {h, h, h, h, f32, f32, h, h};
        }
        spec.attribute("compression", "zip");
        linear.resize(n * nc);
        for (size_t i = 0; i < n; ++i) {
            for (int c = 0; c < 4; ++c) linear[i * nc + c] = channel(f, i, c);
            if (f.has_aovs) {
                linear[i * nc + 4] = f.depth[i];
                linear[i * nc + 5] = f.object_id[i];
                linear[i * nc + 6] = f.alpha[i];
                linear[i * nc + 7] = f.lightness[i];
            }
        }
        data = linear.data();
        in_type = OIIO::TypeDesc::FLOAT;
    } else if (ext == ".png") {
        spec = OIIO::ImageSpec(f.width, f.height, 3, OIIO::TypeDesc::UINT8);
        u8 = frame_srgb8(f);
        data = u8.data();
        in_type = OIIO::TypeDesc::UINT8;
        // zlib's level 6 default spends more time than painting; level 3 files are ~5% larger.
        spec.attribute("png:compressionLevel", 3);
    } else {
        spec = OIIO::ImageSpec(f.width, f.height, 3, OIIO::TypeDesc::UINT16);
        u16.resize(3 * n);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const auto& r) {
            for (size_t i = r.begin(); i < r.end(); ++i)
                for (int c = 0; c < 3; ++c)
                    u16[3 * i + c] = static_cast<uint16_t>(
                        std::lround(65535.0f * linear_to_srgb(channel(f, i, c))));
        });
        data = u16.data();
        in_type = OIIO::TypeDesc::UINT16;
        spec.attribute("compression", "zip");
    }
    if (ext != ".exr") spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("Software", "pleinair");
    // The TIFF and EXR writers stamp the current time unless a DateTime is given; an empty one
    // (EXR keeps it as an empty capDate, TIFF drops it) keeps the same inputs the same bytes.
    spec.attribute("DateTime", "");

    write_image_atomic(path, spec, in_type, data);
}

std::string encode_frame(const Frame& f, const std::string& ext, int jpeg_quality) {
    if (ext != ".png" && ext != ".jpg")
        throw std::runtime_error("encode_frame: .png or .jpg, not " + ext);
    if (const size_t bad = non_finite_values(f); bad > 0)
        throw std::runtime_error("the frame holds " + std::to_string(bad) +
                                 " values that are not finite; not encoded");
    OIIO::ImageSpec spec(f.width, f.height, 3, OIIO::TypeDesc::UINT8);
    const std::vector<uint8_t> u8 = frame_srgb8(f);
    spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("Software", "pleinair");
    if (ext == ".png") spec.attribute("png:compressionLevel", 3);
    if (ext == ".jpg") spec.attribute("Compression", "jpeg:" + std::to_string(jpeg_quality));
    const fs::path name = "frame" + ext;
    MemoryFile memory(name);
    auto out = OIIO::ImageOutput::create(name.string());
    const bool ok = out && out->open(memory.name(), spec) &&
                    out->write_image(OIIO::TypeDesc::UINT8, u8.data()) && out->close() &&
                    !out->has_error();
    if (!ok) {
        std::string err = out ? out->geterror() : OIIO::geterror();
        throw std::runtime_error("cannot encode the frame as " + ext + ": " + err);
    }
    return memory.bytes();
}

void write_channel_image(const fs::path& path, const std::vector<float>& values, int width,
                         int height) {
    const std::string ext = lower_ext(path);
    if (!is_image_path(path))
        throw InputError("-o", "",
                         "cannot write \"" + path.string() +
                             "\": the extension must be .png, .tif, .tiff or .exr");
    if (width < 1 || height < 1 || values.size() != size_t(width) * size_t(height))
        throw std::runtime_error("write_channel_image: the values do not fill the image");
    for (float v : values)
        if (!std::isfinite(v))
            throw std::runtime_error("the image for " + path.string() +
                                     " holds values that are not finite; not written");
    std::vector<uint16_t> u16;
    OIIO::ImageSpec spec;
    const void* data = values.data();
    OIIO::TypeDesc in_type = OIIO::TypeDesc::FLOAT;
    if (ext == ".exr") {
        spec = OIIO::ImageSpec(width, height, 1, OIIO::TypeDesc::FLOAT);
        spec.attribute("compression", "zip");
    } else {
        spec = OIIO::ImageSpec(width, height, 1, OIIO::TypeDesc::UINT16);
        u16.resize(values.size());
        for (size_t i = 0; i < values.size(); ++i)
            u16[i] =
                static_cast<uint16_t>(std::lround(65535.0f * std::clamp(values[i], 0.0f, 1.0f)));
        data = u16.data();
        in_type = OIIO::TypeDesc::UINT16;
        if (ext != ".png") spec.attribute("compression", "zip");
    }
    // Data, not colour nor coverage: OpenImageIO names a lone channel "A" otherwise.
    spec.channelnames = {"Y"};
    spec.alpha_channel = -1;
    // Exif's "uncalibrated" colour space, which data is. It also keeps OpenImageIO 2.4's TIFF
    // writer from failing on an Exif directory with nothing in it ("failed
    // TIFFWriteCustomDirectory() of the Exif data"), as it does for a spec without a colour space.
    spec.attribute("Exif:ColorSpace", 65535);
    spec.attribute("Software", "pleinair");
    spec.attribute("DateTime", "");
    write_image_atomic(path, spec, in_type, data);
}

std::string encode_png_rgba8(const std::vector<uint8_t>& rgba, int width, int height) {
    if (width <= 0 || height <= 0 || rgba.size() != size_t(width) * size_t(height) * 4)
        throw std::runtime_error("encode_png_rgba8: the pixels do not fill the image");
    OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
    spec.alpha_channel = 3;
    spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("oiio:UnassociatedAlpha", 1);  // colour is not premultiplied: glTF's rule
    spec.attribute("Software", "pleinair");
    spec.attribute("png:compressionLevel", 6);
    const fs::path name = "texture.png";
    MemoryFile memory(name);
    auto out = OIIO::ImageOutput::create(name.string());
    const bool ok = out && out->open(memory.name(), spec) &&
                    out->write_image(OIIO::TypeDesc::UINT8, rgba.data()) && out->close() &&
                    !out->has_error();
    if (!ok)
        throw std::runtime_error("cannot encode a texture as PNG: " +
                                 (out ? out->geterror() : OIIO::geterror()));
    return memory.bytes();
}

bool image_has_size(const fs::path& path, int width, int height) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return false;
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) {
        OIIO::geterror();  // clear OpenImageIO's error for this thread
        return false;
    }
    const bool same = in->spec().width == width && in->spec().height == height;
    in->close();
    return same;
}

ImageError compare_frames(const Frame& a, const Frame& ref) {
    if (a.width != ref.width || a.height != ref.height)
        throw std::runtime_error("compare_frames: sizes differ");
    auto to_buf = [](const Frame& f) {
        std::vector<uint8_t> bytes = frame_srgb8(f);
        OIIO::ImageBuf buf(OIIO::ImageSpec(f.width, f.height, 3, OIIO::TypeDesc::FLOAT));
        buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, bytes.data());
        return buf;
    };
    OIIO::ImageBuf A = to_buf(a), B = to_buf(ref);
    auto r = OIIO::ImageBufAlgo::compare(A, B, 1.0f, 1.0f);
    return {r.rms_error, r.PSNR, r.maxerror};
}

}  // namespace pleinair
