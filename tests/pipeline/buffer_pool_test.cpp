// Buffers kept from frame to frame (buffer_pool.h): what the pool hands back, and frames
// painted in buffers another frame left dirty, byte for byte those painted in new ones.
#include "pipeline/frame/buffer_pool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "pipeline/frame/paint_frame.h"
#include "pipeline/frame/sprites.h"
#include "pipeline/input/scene.h"
#include "pipeline/shot/shot.h"
#include "tests/test_util.h"

namespace pleinair {
namespace {

bool all_equal(const std::vector<float>& v, float x) {
    return std::all_of(v.begin(), v.end(), [x](float y) { return y == x; });
}

TEST(BufferPool, HandsBackTheSmallestKeptBufferThatFitsFilledAsAsked) {
    BufferPool pool;
    std::vector<float> small(1000, 7.0f), large(5000, 8.0f);
    const float *small_at = small.data(), *large_at = large.data();
    pool.give(std::move(small));
    pool.give(std::move(large));
    std::vector<float> a = pool.take(900, 1.0f);
    EXPECT_EQ(a.data(), small_at);
    EXPECT_EQ(a.size(), 900u);
    EXPECT_TRUE(all_equal(a, 1.0f));
    std::vector<float> b = pool.take(4000, 0.0f);
    EXPECT_EQ(b.data(), large_at);
    EXPECT_EQ(b.size(), 4000u);
    EXPECT_TRUE(all_equal(b, 0.0f));
    // Nothing kept fits: a new one.
    std::vector<float> c = pool.take(6000, 2.0f);
    EXPECT_NE(c.data(), small_at);
    EXPECT_NE(c.data(), large_at);
    EXPECT_TRUE(all_equal(c, 2.0f));
    EXPECT_EQ(pooled(nullptr, 3, 4.0f), std::vector<float>(3, 4.0f));
}

TEST(BufferPool, KeepsTheEightLargest) {
    BufferPool pool;
    for (size_t k = 1; k <= 10; ++k) pool.give(std::vector<float>(100 * k));
    pool.give(std::vector<float>());  // nothing to keep
    // Smallest first: 300 .. 1000 came back, 100 and 200 were let go.
    for (size_t k = 3; k <= 10; ++k) EXPECT_EQ(pool.take(1, 0.0f).capacity(), 100 * k);
    EXPECT_EQ(pool.take(1, 0.0f).capacity(), 1u);
}

// forest-edge-walk's shot at 192x108.
Shot small_walk() {
    SceneDesc scene =
        load_scene(test::source_dir() / "presets" / "scenes" / "forest-edge-walk.json");
    scene.camera_params.width = 192;
    scene.camera_params.height = 108;
    return build_shot(std::move(scene));
}

// A walk's frame painted after another frame left the pool its image and stroke layers,
// against the same frame painted in new buffers.
TEST(BufferPool, FramesPaintedInKeptBuffersAreTheSameBytes) {
    const Shot shot = small_walk();
    const FrameSettings fresh = scene_frame_settings(shot.scene);
    FrameSettings kept = fresh;
    BufferPool pool;
    kept.buffers = &pool;
    auto view = [&](int f) { return view_at(shot.scene, frame_time(f, shot.scene.fps)); };
    Frame before = paint_frame(shot, view(10), kept);
    const float* image_at = before.rgba.data();
    pool.give(std::move(before.rgba));
    const Frame a = paint_frame(shot, view(40), kept);
    const Frame b = paint_frame(shot, view(40), fresh);
    EXPECT_EQ(a.rgba.data(), image_at) << "the frame before's image was taken again";
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    EXPECT_EQ(std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)), 0);
}

// The sprites stage's list and each item's part come back empty with their memory, and a frame
// painted after them joins its sprites in the same list.
TEST(BufferPool, KeepsTheSpriteListAndItsPartsForTheNextFrame) {
    const Shot shot = small_walk();
    FrameSettings kept = scene_frame_settings(shot.scene);
    BufferPool pool;
    kept.buffers = &pool;
    EXPECT_EQ(pool.take_sprites().capacity(), 0u) << "nothing kept before a frame";
    const FrameView view = view_at(shot.scene, frame_time(40, shot.scene.fps));
    FrameReport rep;
    paint_frame(shot, view, kept, &rep);
    const uint64_t drawn = rep.leaf_sprites + rep.bark_sprites + rep.surface_sprites;
    ASSERT_GT(drawn, 1000u);
    std::vector<Sprite> list = pool.take_sprites();
    EXPECT_TRUE(list.empty());
    EXPECT_GE(list.capacity(), drawn);
    const Sprite* list_at = list.data();
    pool.give_sprites(std::move(list));
    std::vector<std::vector<Sprite>> parts = pool.take_sprite_parts();
    ASSERT_EQ(parts.size(), shot.item_count());
    size_t held = 0;
    for (const std::vector<Sprite>& p : parts) {
        EXPECT_TRUE(p.empty());
        held += p.capacity();
    }
    EXPECT_GE(held, drawn);
    pool.give_sprite_parts(std::move(parts));
    paint_frame(shot, view, kept);
    EXPECT_EQ(pool.take_sprites().data(), list_at) << "the same frame's sprites fit the kept list";
}

}  // namespace
}  // namespace pleinair
