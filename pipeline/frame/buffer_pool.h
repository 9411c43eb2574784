// Buffers kept from one frame for the next: a frame's image and stroke layers are tens of
// megabytes, which the allocator returns to the system when freed, so each new frame paid a
// page fault for every 4 KB it wrote (a quarter of a 480x270 frame's time on this machine's
// virtual memory). Frames painted in a row (animate) hand them back and take them again.
#pragma once

#include <cstddef>
#include <mutex>
#include <vector>

namespace pleinair {

class BufferPool {
  public:
    // n floats, each `value`: a kept buffer holding at least n if there is one (the smallest
    // such), else a new one. Thread-safe.
    std::vector<float> take(size_t n, float value);
    // Keeps `v`'s memory for a later take (at most kKept buffers, the largest).
    void give(std::vector<float>&& v);

  private:
    static constexpr size_t kKept = 8;
    std::mutex mutex_;
    std::vector<std::vector<float>> kept_;
};

// From `pool` when there is one, else a new vector.
std::vector<float> pooled(BufferPool* pool, size_t n, float value);

}  // namespace pleinair
