// Buffers kept from one frame for the next: a frame's image and stroke layers, and its sprite
// list, are tens of megabytes, which the allocator returns to the system when freed, so each new
// frame paid a page fault for every 4 KB it wrote (a quarter of a 480x270 frame's time on this
// machine's virtual memory, where a fault costs about 12 us). Frames painted in a row (animate,
// the studio) hand them back and take them again.
#pragma once

#include <cstddef>
#include <mutex>
#include <vector>

namespace pleinair {

struct Sprite;  // sprite.h

class BufferPool {
  public:
    BufferPool();
    ~BufferPool();

    // n floats, each `value`: a kept buffer holding at least n if there is one (the smallest
    // such), else a new one. Thread-safe.
    std::vector<float> take(size_t n, float value);
    // Keeps `v`'s memory for a later take (at most kKept buffers, the largest).
    void give(std::vector<float>&& v);

    // The sprites stage's vectors (sprites.h): the frame's sprite list, and each item's part
    // while the items are made in parallel. Taken empty, with the capacity they were given
    // back with (none at first). Thread-safe.
    std::vector<Sprite> take_sprites();
    void give_sprites(std::vector<Sprite>&& v);
    std::vector<std::vector<Sprite>> take_sprite_parts();
    void give_sprite_parts(std::vector<std::vector<Sprite>>&& parts);

  private:
    static constexpr size_t kKept = 8;
    std::mutex mutex_;
    std::vector<std::vector<float>> kept_;
    std::vector<Sprite> sprites_;
    std::vector<std::vector<Sprite>> parts_;
};

// From `pool` when there is one, else a new vector.
std::vector<float> pooled(BufferPool* pool, size_t n, float value);

}  // namespace pleinair
