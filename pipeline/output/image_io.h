// Frame output through OpenImageIO, format from the extension: PNG (8-bit sRGB), TIFF (16-bit
// sRGB), EXR (half float, linear, with AOV channels when the frame has them). Encoded in memory,
// written to a temporary beside the target and renamed when complete; headers carry no time, so
// the same frame gives the same bytes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/frame/frame_image.h"

namespace pleinair {

// The path's extension in lower case (".PNG" -> ".png").
std::string lower_ext(const std::filesystem::path& path);

// True for .png, .tif, .tiff and .exr (any case).
bool is_image_path(const std::filesystem::path& path);
// True for the extension of an image format pleinair does not write (.jpg, .bmp, .webp, ...):
// a path a user meant as an image, not as a folder.
bool is_other_image_path(const std::filesystem::path& path);

// Throws InputError for an unsupported extension (before anything is written) and
// std::runtime_error naming the file if encoding or any write fails; no partial file remains
// either way and an earlier file of the same name is untouched.
void write_frame(const std::filesystem::path& path, const Frame& frame);

// The frame's 8-bit sRGB image encoded in memory as `ext` (".png" as write_frame writes it, or
// ".jpg" at `jpeg_quality`), for a client that shows frames without files (the studio).
// Throws std::runtime_error for a frame with values that are not finite or a failed encode.
std::string encode_frame(const Frame& frame, const std::string& ext, int jpeg_quality = 90);

// One channel of data, not colour (a height map): 16-bit in PNG and TIFF (values 0..1 to
// 0..65535, clamped), 32-bit float in EXR (as given). Written as write_frame writes.
void write_channel_image(const std::filesystem::path& path, const std::vector<float>& values,
                         int width, int height);

// 8-bit RGBA (row by row, top row first, sRGB colour and linear alpha) encoded as PNG in
// memory, as write_frame encodes (a texture inside a glTF file). Throws std::runtime_error.
std::string encode_png_rgba8(const std::vector<uint8_t>& rgba, int width, int height);

// Whether `path` is an image OpenImageIO can open whose size is width x height (a frame a
// resumed run keeps).
bool image_has_size(const std::filesystem::path& path, int width, int height);

// 8-bit sRGB RGB bytes of the frame (what a PNG holds), for tests and contact sheets.
std::vector<uint8_t> frame_srgb8(const Frame& frame);

// How many values of the frame's buffers are NaN or infinite: write_frame refuses a frame
// with any (std::runtime_error, exit 1) rather than let a conversion turn one into a colour.
size_t non_finite_values(const Frame& frame);

// The bytes a pixel's converted copy takes while `path` is written (8-bit PNG, 16-bit TIFF,
// EXR in float and then half), for the memory a job is estimated to need.
double output_bytes_per_pixel(const std::filesystem::path& path, bool aovs);

// Error of a frame against a reference of the same size, over the 8-bit sRGB values a viewer
// sees (as 0..1 floats), through OpenImageIO's ImageBufAlgo::compare.
struct ImageError {
    double rmse = 0;
    double psnr = 0;  // dB; infinite when identical
    double max_error = 0;
};
ImageError compare_frames(const Frame& image, const Frame& reference);

}  // namespace pleinair
