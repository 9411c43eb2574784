// Partial outputs: their names, the registry the signal handlers clean from, commits into place.
#include "pipeline/output/partial_files.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <stdexcept>
#include <system_error>

namespace pleinair {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kTag = ".partial-";

// This machine's name as it stands in a partial name: letters, digits, '-' and '.', so that
// writers on several machines sharing a folder never take each other's temporaries.
const std::string& this_host() {
    static const std::string host = [] {
        char buf[256] = {};
        if (::gethostname(buf, sizeof buf - 1) != 0) return std::string("localhost");
        std::string h;
        for (const char* c = buf; *c; ++c)
            h += std::isalnum(static_cast<unsigned char>(*c)) || *c == '-' || *c == '.' ? *c : '_';
        return h.empty() ? std::string("localhost") : h;
    }();
    return host;
}

bool host_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' || c == '_';
}

// A target named with a trailing separator ("out/") names the folder itself.
fs::path named(const fs::path& target) {
    return target.has_filename() ? target : target.parent_path();
}

}  // namespace

fs::path partial_path(const fs::path& target) {
    fs::path t = named(target);
    std::string name = ".";
    name.append(t.filename().string())
        .append(kTag)
        .append(std::to_string(::getpid()))
        .append("@")
        .append(this_host());
    return t.parent_path() / name;
}

long partial_pid(const std::string& name) {
    if (name.size() < 2 || name[0] != '.') return 0;
    const size_t at = name.rfind(kTag);
    if (at == std::string::npos || at < 2) return 0;  // at least one character of NAME
    size_t i = at + kTag.size(), digits = 0;
    long pid = 0;
    for (; i < name.size() && name[i] >= '0' && name[i] <= '9'; ++i, ++digits) {
        if (digits == 9) return 0;  // Linux PIDs have at most 7 digits
        pid = 10 * pid + (name[i] - '0');
    }
    if (digits == 0 || pid == 0) return 0;
    if (i == name.size()) return pid;
    // "@HOST": the machine the writer ran on.
    if (name[i] == '@') {
        if (i + 1 == name.size()) return 0;
        for (++i; i < name.size(); ++i)
            if (!host_char(name[i])) return 0;
        return pid;
    }
    // The older image form ends in the image's extension: ".STEM.partial-PID.EXT".
    if (name[i] != '.' || i + 1 == name.size()) return 0;
    for (++i; i < name.size(); ++i)
        if (!std::isalnum(static_cast<unsigned char>(name[i]))) return 0;
    return pid;
}

bool is_partial_name(const std::string& name) { return partial_pid(name) != 0; }

std::string partial_host(const std::string& name) {
    if (partial_pid(name) == 0) return "";
    const size_t at = name.rfind('@');
    return at != std::string::npos && at > name.rfind(kTag) ? name.substr(at + 1) : "";
}

// The registry. The handlers may run at any instruction of any thread, so it is a fixed array of
// fixed buffers, no allocation, and each slot is guarded like a seqlock: a writer claims a free
// slot (state 0 -> 1), bumps its generation, copies the path and publishes it (state 2); the
// handler copies a published path and uses the copy only if state and generation did not change
// meanwhile. Enough slots for every thread of a large machine writing at once; when they are
// all taken a temporary goes unregistered (a signal then leaves it, recognisable by its name).
namespace {

constexpr int kSlots = 256;
constexpr size_t kPathMax = 4096;

struct Slot {
    std::atomic<int> state{0};
    std::atomic<unsigned> generation{0};
    char path[kPathMax];
};
Slot g_slots[kSlots];
std::atomic<bool> g_terminating{false};

int register_partial(const fs::path& tmp) {
    std::error_code ec;
    const std::string abs = fs::absolute(tmp, ec).string();
    if (ec || abs.size() >= kPathMax) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int free = 0;
        if (!g_slots[i].state.compare_exchange_strong(free, 1)) continue;
        g_slots[i].generation.fetch_add(1);
        std::memcpy(g_slots[i].path, abs.c_str(), abs.size() + 1);
        g_slots[i].state.store(2);
        return i;
    }
    return -1;
}

void unregister_partial(int slot) {
    if (slot >= 0) g_slots[slot].state.store(0);
}

// Removes `name` (relative to `dir_fd`) whatever it is, a folder with everything below it too,
// with async-signal-safe calls only: unlinkat, openat, getdents64 (a plain system call), close.
// Entries are removed while the folder is read, so it is read again until it reads empty.
void remove_at(int dir_fd, const char* name, int depth) {
    if (::unlinkat(dir_fd, name, 0) == 0 || errno == ENOENT) return;
    if (errno != EISDIR || depth > 16) return;
    const int fd = ::openat(dir_fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd >= 0) {
        alignas(8) char buf[4096];
        for (int pass = 0; pass < 8; ++pass) {
            bool any = false;
            ::lseek(fd, 0, SEEK_SET);
            ssize_t n;
            while ((n = ::getdents64(fd, buf, sizeof buf)) > 0) {
                for (ssize_t off = 0; off < n;) {
                    const auto* d = reinterpret_cast<const struct dirent64*>(buf + off);
                    off += d->d_reclen;
                    if (std::strcmp(d->d_name, ".") == 0 || std::strcmp(d->d_name, "..") == 0)
                        continue;
                    any = true;
                    remove_at(fd, d->d_name, depth + 1);
                }
            }
            if (!any) break;
        }
        ::close(fd);
    }
    ::unlinkat(dir_fd, name, AT_REMOVEDIR);
}

extern "C" void remove_partials_and_die(int sig) {
    const int saved_errno = errno;
    g_terminating.store(true);
    // Other threads keep writing while this one cleans: a file they create inside a registered
    // folder after the first pass is caught by the second (new temporaries are refused once
    // g_terminating is set).
    for (int pass = 0; pass < 2; ++pass) {
        for (auto& slot : g_slots) {
            const unsigned gen = slot.generation.load();
            if (slot.state.load() != 2) continue;
            char path[kPathMax];
            std::memcpy(path, slot.path, kPathMax);
            path[kPathMax - 1] = '\0';
            if (slot.state.load() != 2 || slot.generation.load() != gen) continue;
            remove_at(AT_FDCWD, path, 0);
        }
        if (pass == 0) {
            struct timespec pause = {0, 20 * 1000 * 1000};
            ::nanosleep(&pause, nullptr);
        }
    }
    errno = saved_errno;
    // Die by the signal itself, so the parent sees how the run ended.
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    ::sigemptyset(&dfl.sa_mask);
    ::sigaction(sig, &dfl, nullptr);
    sigset_t unblock;
    ::sigemptyset(&unblock);
    ::sigaddset(&unblock, sig);
    ::sigprocmask(SIG_UNBLOCK, &unblock, nullptr);
    ::raise(sig);
    ::_exit(128 + sig);
}

}  // namespace

PartialOutput::PartialOutput(fs::path target) : target_(named(target)), tmp_(partial_path(target)) {
    if (g_terminating.load())
        throw std::runtime_error("cannot write " + target_.string() + ": interrupted");
    // A temporary of this name can only be left by a dead process that had this PID.
    std::error_code ignored;
    fs::remove_all(tmp_, ignored);
    slot_ = register_partial(tmp_);
}

PartialOutput::~PartialOutput() {
    if (!committed_) {
        std::error_code ignored;
        fs::remove_all(tmp_, ignored);
    }
    unregister_partial(slot_);
}

void PartialOutput::commit() {
    auto fail = [&](int err) {
        throw std::runtime_error("cannot write " + target_.string() + ": " + std::strerror(err));
    };
    struct stat st;
    if (::lstat(tmp_.c_str(), &st) != 0) fail(errno);
    if (!S_ISDIR(st.st_mode)) {
        if (::rename(tmp_.c_str(), target_.c_str()) != 0) fail(errno);
        committed_ = true;
        return;
    }
    // A folder: rename() itself replaces an absent or empty target folder in one step.
    if (::rename(tmp_.c_str(), target_.c_str()) == 0) {
        committed_ = true;
        return;
    }
    if (errno != ENOTEMPTY && errno != EEXIST) fail(errno);
    if (::lstat(target_.c_str(), &st) != 0) fail(errno);
    if (!S_ISDIR(st.st_mode)) fail(ENOTDIR);
    std::error_code ignored;
    if (::renameat2(AT_FDCWD, tmp_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) == 0) {
        // The old folder now has the temporary's name, still registered: gone on a signal, and
        // recognised as a leftover if this process dies before removing it.
        fs::remove_all(tmp_, ignored);
        committed_ = true;
        return;
    }
    if (errno != EINVAL && errno != ENOSYS && errno != EOPNOTSUPP) fail(errno);
    // No exchange on this file system: the old folder goes aside under a partial name, so the
    // target is absent for a moment, never mixed.
    fs::path aside = partial_path(target_.parent_path() / (target_.filename().string() + "~old"));
    if (::rename(target_.c_str(), aside.c_str()) != 0) fail(errno);
    if (::rename(tmp_.c_str(), target_.c_str()) != 0) {
        const int err = errno;
        ::rename(aside.c_str(), target_.c_str());
        fail(err);
    }
    committed_ = true;
    fs::remove_all(aside, ignored);
}

void install_partial_cleanup() {
    // A write past the file-size limit (ulimit -f, a farm's quota) then fails with EFBIG and is
    // reported like a full disk, its temporary removed, instead of the process dying by SIGXFSZ
    // and leaving the temporary behind.
    ::signal(SIGXFSZ, SIG_IGN);
    for (int sig : {SIGINT, SIGTERM}) {
        // A signal ignored when the process started (nohup, a background job of a
        // non-interactive shell) stays ignored, as a shell's users expect.
        struct sigaction old {};
        if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        struct sigaction sa {};
        sa.sa_handler = remove_partials_and_die;
        ::sigemptyset(&sa.sa_mask);
        ::sigaddset(&sa.sa_mask, SIGINT);
        ::sigaddset(&sa.sa_mask, SIGTERM);
        ::sigaction(sig, &sa, nullptr);
    }
}

size_t clear_partials(const fs::path& dir) {
    std::error_code ec;
    size_t removed = 0;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        const long pid = partial_pid(name);
        if (pid == 0) continue;
        // Another machine's writer cannot be asked whether it lives: left to its own machine.
        if (const std::string host = partial_host(name); !host.empty() && host != this_host())
            continue;
        // kill(pid, 0) fails with ESRCH only when no such process exists (EPERM: it exists).
        const bool alive =
            pid == ::getpid() || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH;
        if (alive) continue;
        std::error_code rm;
        if (fs::remove_all(it->path(), rm) > 0 && !rm) ++removed;
    }
    return removed;
}

}  // namespace pleinair
