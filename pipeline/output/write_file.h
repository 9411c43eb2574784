// Checked file output: every write, the fsync and the close are checked, and a file is written
// to a temporary beside its target and renamed into place, so a failed or killed run never
// leaves a truncated file nor touches an earlier file of the same name.
#pragma once

#include <filesystem>
#include <string_view>

namespace pleinair {

// Writes `bytes` to `.NAME.partial-PID` beside `path` (partial_files.h) and renames it over
// `path`. Throws std::runtime_error "cannot write PATH: REASON" (a runtime failure, exit 1) if
// anything fails; the temporary is removed then and an earlier `path` is untouched.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);

// Writes `bytes` to a new file `path` with no temporary of its own: for files inside a folder
// that is itself a temporary (a tree's folder). Same checks and error as write_file_atomic, the
// error naming `shown` when given (the file's final path, not its place in the temporary); a
// file begun is removed.
void write_new_file(const std::filesystem::path& path, std::string_view bytes,
                    const std::filesystem::path& shown = {});

}  // namespace pleinair
