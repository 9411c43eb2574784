// What a shot's build and a frame's passes report for --explain: which ran, why, how long.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace pleinair {

struct PassReport {
    std::string name;
    bool ran = false;
    std::string why;  // why it ran or was skipped
    double ms = 0;
    std::string counts;  // e.g. "12,345 sprites"
};

// Milliseconds since a start, for pass timings (reports only: never read by the painting).
class PassTimer {
  public:
    PassTimer() : t0_(std::chrono::steady_clock::now()) {}
    double ms() const {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_)
            .count();
    }

  private:
    std::chrono::steady_clock::time_point t0_;
};

}  // namespace pleinair
