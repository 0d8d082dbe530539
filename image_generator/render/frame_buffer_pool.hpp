#pragma once
// The renderer's read-back buffers: it reads each frame into one nobody holds, and a consumer
// (the video encoder's queue) may keep a frame while later ones are read into other buffers. A
// buffer a consumer held is written again only after its last copy is dropped, on whatever
// thread, and that release happens-before the renderer's next write into it (an acquire/release
// pair, which a bare shared_ptr::use_count() check does not give: it is a relaxed load, and
// ThreadSanitizer rightly reported the read-back racing the encoder's last read).

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace vcockpit::render {

class FrameBufferPool {
 public:
  explicit FrameBufferPool(std::size_t bytes);

  // Makes a buffer nobody holds current (one more when every one is held) and returns it for
  // writing. No allocation while a free buffer exists.
  std::vector<uint8_t>& next();
  const std::vector<uint8_t>& current() const { return slots_[current_]->pixels; }
  // The current buffer for a consumer to keep (one small allocation: the handle's control
  // block); not handed out by next() until every such handle is gone.
  std::shared_ptr<const std::vector<uint8_t>> share_current();
  std::size_t buffer_count() const { return slots_.size(); }

 private:
  struct Slot {
    explicit Slot(std::size_t bytes) : pixels(bytes, 0) {}
    std::vector<uint8_t> pixels;
    std::atomic<int> holders{0};
  };
  // shared: a handle kept past the pool's life keeps its buffer alive
  std::vector<std::shared_ptr<Slot>> slots_;
  std::size_t current_ = 0;
};

}  // namespace vcockpit::render
