// The renderer's read-back buffers (image_generator/render/frame_buffer_pool.hpp): a buffer a
// consumer holds is never written, one it dropped is reused, and the drop on another thread
// happens-before the next write (the ThreadSanitizer build checks that last one for real).

#include "image_generator/render/frame_buffer_pool.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <thread>

namespace vcockpit::render {
namespace {

TEST(FrameBufferPool, AHeldBufferIsNotWrittenAndADroppedOneIsReused) {
  FrameBufferPool pool(16);
  std::vector<uint8_t>* first = &pool.next();
  EXPECT_EQ(&pool.next(), first) << "nobody holds it: the same buffer again";
  auto held = pool.share_current();
  EXPECT_EQ(held.get(), first);
  std::vector<uint8_t>* second = &pool.next();
  EXPECT_NE(second, first);
  EXPECT_EQ(pool.buffer_count(), 2u);
  auto also_held = pool.share_current();
  EXPECT_NE(&pool.next(), second);
  EXPECT_EQ(pool.buffer_count(), 3u) << "every buffer held: one more";
  held.reset();
  also_held.reset();
  EXPECT_EQ(&pool.next(), first) << "dropped: reused";
  EXPECT_EQ(pool.buffer_count(), 3u);
}

TEST(FrameBufferPool, AConsumerOnAnotherThreadReadsEachFrameWholeWhileTheWriterGoesOn) {
  FrameBufferPool pool(4096);
  constexpr int kFrames = 200;
  std::vector<std::shared_ptr<const std::vector<uint8_t>>> queue;
  std::mutex mutex;
  std::atomic<bool> done{false};
  int torn = 0;
  std::thread consumer([&] {
    while (!done.load() || !queue.empty()) {
      std::shared_ptr<const std::vector<uint8_t>> frame;
      {
        std::lock_guard lock(mutex);
        if (!queue.empty()) {
          frame = queue.front();
          queue.erase(queue.begin());
        }
      }
      if (!frame) continue;
      for (uint8_t b : *frame) torn += b != frame->front() ? 1 : 0;  // one value per frame
    }
  });
  for (int i = 0; i < kFrames; ++i) {
    std::vector<uint8_t>& pixels = pool.next();
    std::fill(pixels.begin(), pixels.end(), static_cast<uint8_t>(i));
    std::lock_guard lock(mutex);
    if (queue.size() < 3) queue.push_back(pool.share_current());
  }
  done = true;
  consumer.join();
  EXPECT_EQ(torn, 0);
  EXPECT_LE(pool.buffer_count(), 5u) << "at most the queue's three, the current and one more";
}

}  // namespace
}  // namespace vcockpit::render
