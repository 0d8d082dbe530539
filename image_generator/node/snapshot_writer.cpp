#include "image_generator/node/snapshot_writer.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <cstring>

#include "image_generator/render/png_writer.hpp"

namespace vcockpit::image_generator {
namespace {
constexpr int kSlots = 2;
}

SnapshotWriter::SnapshotWriter(std::string out_dir, SnapshotLayout layout, int eye_width,
                               int height)
    : out_dir_(std::move(out_dir)), layout_(layout), eye_width_(eye_width), height_(height) {
  slots_.resize(kSlots);
  for (auto& s : slots_) s.pixels.resize(static_cast<std::size_t>(2 * eye_width * height * 4));
  worker_ = std::thread([this] { work(); });
}

SnapshotWriter::~SnapshotWriter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

bool SnapshotWriter::submit(uint64_t frame_seq, const uint8_t* side_by_side_rgba) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& slot : slots_) {
    if (slot.full) continue;
    std::memcpy(slot.pixels.data(), side_by_side_rgba, slot.pixels.size());
    slot.frame_seq = frame_seq;
    slot.full = true;
    wake_.notify_one();
    return true;
  }
  ++skipped_;
  return false;
}

uint64_t SnapshotWriter::written() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return written_;
}

uint64_t SnapshotWriter::failed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failed_;
}

void SnapshotWriter::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    Slot* next = nullptr;
    for (auto& slot : slots_) {
      if (slot.full && (!next || slot.frame_seq < next->frame_seq)) next = &slot;
    }
    if (!next) {
      if (stopping_) return;
      wake_.wait(lock);
      continue;
    }
    lock.unlock();
    bool ok = true;
    try {
      write(*next);
    } catch (const std::exception& e) {
      spdlog::error("snapshot: {}", e.what());
      ok = false;
    }
    lock.lock();
    next->full = false;
    (ok ? written_ : failed_)++;
  }
}

void SnapshotWriter::write(const Slot& slot) {
  char name[64];
  auto path = [&](const char* suffix) {
    std::snprintf(name, sizeof name, "/frame_%06llu%s.png",
                  static_cast<unsigned long long>(slot.frame_seq), suffix);
    return out_dir_ + name;
  };
  switch (layout_) {
    case SnapshotLayout::kSideBySide:
      render::write_png(path(""), slot.pixels.data(), 2 * eye_width_, height_);
      break;
    case SnapshotLayout::kLeft:
    case SnapshotLayout::kRight:
      render::copy_eye(slot.pixels.data(), eye_width_, height_,
                       layout_ == SnapshotLayout::kLeft ? render::Eye::kLeft : render::Eye::kRight,
                       eye_scratch_);
      render::write_png(path(layout_ == SnapshotLayout::kLeft ? "_left" : "_right"),
                        eye_scratch_.data(), eye_width_, height_);
      break;
    case SnapshotLayout::kBothSeparate:
      for (render::Eye eye : {render::Eye::kLeft, render::Eye::kRight}) {
        render::copy_eye(slot.pixels.data(), eye_width_, height_, eye, eye_scratch_);
        render::write_png(path(eye == render::Eye::kLeft ? "_left" : "_right"),
                          eye_scratch_.data(), eye_width_, height_);
      }
      break;
  }
}

}  // namespace vcockpit::image_generator
