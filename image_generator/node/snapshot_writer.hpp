#pragma once
// PNG snapshots written off the render thread: a PNG costs about as much as a frame, so frames
// are copied (0.2 ms) into one of a few preallocated slots and a worker compresses them. When
// every slot is busy the snapshot is skipped and counted, never the frame.

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace vcockpit::image_generator {

enum class SnapshotLayout { kSideBySide, kLeft, kRight, kBothSeparate };

class SnapshotWriter {
 public:
  SnapshotWriter(std::string out_dir, SnapshotLayout layout, int eye_width, int height);
  ~SnapshotWriter();  // writes what is queued, then stops
  SnapshotWriter(const SnapshotWriter&) = delete;
  SnapshotWriter& operator=(const SnapshotWriter&) = delete;

  // Queues a copy of the side-by-side frame; false (and counted) if no slot was free.
  bool submit(uint64_t frame_seq, const uint8_t* side_by_side_rgba);
  uint64_t written() const;
  uint64_t skipped() const { return skipped_; }
  uint64_t failed() const;

 private:
  struct Slot {
    std::vector<uint8_t> pixels;
    uint64_t frame_seq = 0;
    bool full = false;
  };
  void work();
  void write(const Slot& slot);

  std::string out_dir_;
  SnapshotLayout layout_;
  int eye_width_;
  int height_;
  std::vector<Slot> slots_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  uint64_t written_ = 0;
  uint64_t failed_ = 0;
  uint64_t skipped_ = 0;
  std::vector<uint8_t> eye_scratch_;
  std::thread worker_;
};

}  // namespace vcockpit::image_generator
