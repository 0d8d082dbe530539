#include "image_generator/render/frame_buffer_pool.hpp"

namespace vcockpit::render {

FrameBufferPool::FrameBufferPool(std::size_t bytes) { slots_.push_back(std::make_shared<Slot>(bytes)); }

std::vector<uint8_t>& FrameBufferPool::next() {
  std::size_t free = slots_.size();
  for (std::size_t i = 0; i < slots_.size() && free == slots_.size(); ++i)
    if (slots_[i]->holders.load(std::memory_order_acquire) == 0) free = i;
  if (free == slots_.size()) slots_.push_back(std::make_shared<Slot>(slots_.front()->pixels.size()));
  current_ = free;
  return slots_[current_]->pixels;
}

std::shared_ptr<const std::vector<uint8_t>> FrameBufferPool::share_current() {
  std::shared_ptr<Slot> slot = slots_[current_];
  slot->holders.fetch_add(1, std::memory_order_relaxed);  // on the writer's own thread
  const std::vector<uint8_t>* pixels = &slot->pixels;
  return std::shared_ptr<const std::vector<uint8_t>>(
      pixels, [slot = std::move(slot)](const std::vector<uint8_t>*) {
        slot->holders.fetch_sub(1, std::memory_order_release);
      });
}

}  // namespace vcockpit::render
