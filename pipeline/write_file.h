// Atomic file output: bytes go to a temporary name beside the target and are renamed into place,
// so a killed or failed run never leaves a truncated file.
#pragma once

#include <filesystem>
#include <string_view>

namespace pleinair {

// Throws std::runtime_error (a runtime failure, exit 1) naming the path if anything fails; the
// temporary file is removed then.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);

}  // namespace pleinair
