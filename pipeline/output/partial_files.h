// Temporaries: every output is written under `.NAME.partial-PID` beside its target, registered
// while it exists so SIGINT and SIGTERM remove it, and recognised by that name alone afterwards.
#pragma once

#include <filesystem>
#include <string>

namespace pleinair {

// `.NAME.partial-PID@HOST` beside `target` (NAME is its file name, extension included), PID
// this process's id and HOST this machine's name: two runs writing the same target, on one
// machine or on two that share the folder, never share a temporary.
std::filesystem::path partial_path(const std::filesystem::path& target);

// True for a file or folder name `.NAME.partial-PID` (PID decimal digits), and for the
// `.STEM.partial-PID.EXT` that image writes used before (their leftovers are temporaries too).
// Takes a name, not a path: "a/.x.png.partial-12" is not a name.
bool is_partial_name(const std::string& name);

// The PID in a partial name, 0 when the name is not partial.
long partial_pid(const std::string& name);
// The HOST in a partial name; empty for a name without one (an earlier build's, or not partial).
std::string partial_host(const std::string& name);

// One temporary file or folder being written for `target`. Registered for the signal handlers
// from construction to destruction; the destructor removes it unless commit() moved it into
// place, so every way out of a failed write (an exception, a return) removes the temporary.
// The temporary itself is not created: the writer creates it at path().
class PartialOutput {
  public:
    explicit PartialOutput(std::filesystem::path target);
    ~PartialOutput();
    PartialOutput(const PartialOutput&) = delete;
    PartialOutput& operator=(const PartialOutput&) = delete;

    const std::filesystem::path& path() const { return tmp_; }
    const std::filesystem::path& target() const { return target_; }

    // Moves the temporary into place. A file is renamed over the target. A folder replaces an
    // existing target folder by exchanging the two names in one step (renameat2 with
    // RENAME_EXCHANGE), then removes the old one, now under the temporary's name; where the file
    // system cannot exchange (NFS), the old folder is renamed aside to a partial name first, so
    // for a moment the target is absent, never half-written. Throws std::runtime_error naming
    // the target; the temporary is removed then (by the destructor).
    void commit();

  private:
    std::filesystem::path target_, tmp_;
    int slot_ = -1;  // in the signal handlers' registry; -1 when it was full
    bool committed_ = false;
};

// Installs SIGINT and SIGTERM handlers that remove every registered temporary (files, and
// folders with what they hold), then die by the same signal so the caller sees how the run
// ended (a shell reports 128 + signal). Only async-signal-safe calls run in the handler.
void install_partial_cleanup();

// Removes the temporaries in `dir` (not below it) whose writer is gone: a partial name of this
// machine (or without a machine) whose PID is no live process, as a SIGKILL or a power cut
// leaves. Another machine's temporaries are left to it: its writer may be alive. A temporary of a
// live process is another run's write in progress and stays (as does, rarely, a dead writer's whose
// PID has been reused: it is still never trusted as output). Returns how many were removed.
size_t clear_partials(const std::filesystem::path& dir);

}  // namespace pleinair
