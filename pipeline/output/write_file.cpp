// write_file_atomic: POSIX open, a write loop, fsync and close, each checked, then rename.
#include "pipeline/output/write_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include "pipeline/output/partial_files.h"

namespace pleinair {

namespace fs = std::filesystem;

namespace {

// Writes `bytes` into a new file `file`; returns 0 or the errno of the first failure, with the
// file removed. fsync makes the file system report what a write may not have (a full disk on
// delayed allocation, a quota on a network file system) before the file is trusted.
int write_checked(const fs::path& file, std::string_view bytes) {
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) return errno;
    int err = 0;
    for (size_t done = 0; done < bytes.size() && !err;) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n > 0)
            done += static_cast<size_t>(n);
        else if (n == 0)
            err = EIO;  // a regular file never takes nothing; do not spin
        else if (errno != EINTR)
            err = errno;
    }
    while (!err && ::fsync(fd) != 0)
        if (errno != EINTR) err = errno;
    // Linux closes the descriptor even when close fails, so it is never retried; EINTR is not
    // a lost write.
    if (::close(fd) != 0 && !err && errno != EINTR) err = errno;
    if (err) ::unlink(file.c_str());
    return err;
}

[[noreturn]] void fail(const fs::path& path, int err) {
    throw std::runtime_error("cannot write " + path.string() + ": " + std::strerror(err));
}

}  // namespace

void write_file_atomic(const fs::path& path, std::string_view bytes) {
    PartialOutput tmp(path);
    if (int err = write_checked(tmp.path(), bytes)) fail(path, err);
    tmp.commit();
}

void write_new_file(const fs::path& path, std::string_view bytes, const fs::path& shown) {
    if (int err = write_checked(path, bytes)) fail(shown.empty() ? path : shown, err);
}

}  // namespace pleinair
