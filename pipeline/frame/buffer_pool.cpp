// BufferPool: a short list of vectors under a mutex; taken and given a few times a frame.
#include "pipeline/frame/buffer_pool.h"

#include <algorithm>

#include "pipeline/frame/sprite.h"

namespace pleinair {

BufferPool::BufferPool() = default;
BufferPool::~BufferPool() = default;

std::vector<float> BufferPool::take(size_t n, float value) {
    std::vector<float> v;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        auto best = kept_.end();
        for (auto it = kept_.begin(); it != kept_.end(); ++it)
            if (it->capacity() >= n && (best == kept_.end() || it->capacity() < best->capacity()))
                best = it;
        if (best != kept_.end()) {
            v = std::move(*best);
            kept_.erase(best);
        }
    }
    v.assign(n, value);
    return v;
}

void BufferPool::give(std::vector<float>&& v) {
    if (v.capacity() == 0) return;
    std::lock_guard<std::mutex> lock(mutex_);
    kept_.push_back(std::move(v));
    if (kept_.size() > kKept) {
        auto smallest = std::min_element(
            kept_.begin(), kept_.end(),
            [](const auto& a, const auto& b) { return a.capacity() < b.capacity(); });
        kept_.erase(smallest);
    }
}

std::vector<Sprite> BufferPool::take_sprites() {
    std::vector<Sprite> v;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        v.swap(sprites_);
    }
    v.clear();
    return v;
}

void BufferPool::give_sprites(std::vector<Sprite>&& v) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (v.capacity() > sprites_.capacity()) sprites_ = std::move(v);
}

std::vector<std::vector<Sprite>> BufferPool::take_sprite_parts() {
    std::vector<std::vector<Sprite>> parts;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        parts.swap(parts_);
    }
    for (std::vector<Sprite>& p : parts) p.clear();
    return parts;
}

void BufferPool::give_sprite_parts(std::vector<std::vector<Sprite>>&& parts) {
    std::lock_guard<std::mutex> lock(mutex_);
    parts_ = std::move(parts);
}

std::vector<float> pooled(BufferPool* pool, size_t n, float value) {
    if (pool) return pool->take(n, value);
    return std::vector<float>(n, value);
}

}  // namespace pleinair
