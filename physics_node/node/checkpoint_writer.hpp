#pragma once
// Encodes and writes the world's checkpoints (physics_io::world_checkpoint) on a thread of its
// own, so the step loop never waits on the disk (an fsync takes milliseconds; a 1 kHz step has
// one) nor on encoding a third of a megabyte. The loop hands over a copy of the state; one still
// waiting when a newer comes is replaced (only the newest matters) and counted. A write that fails is logged once per kind of failure
// and counted; the node goes on simulating.

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "physics_node/io/world_checkpoint.hpp"

namespace vcockpit::physics_node {

class CheckpointWriter {
 public:
  CheckpointWriter(std::string path, uint64_t scene_fingerprint);
  ~CheckpointWriter();  // writes what is still waiting, then stops
  CheckpointWriter(const CheckpointWriter&) = delete;
  CheckpointWriter& operator=(const CheckpointWriter&) = delete;

  // Takes `checkpoint` (swapped: the caller gets back an older one whose buffers it can reuse,
  // so a steady loop allocates nothing).
  void offer(physics_io::Checkpoint& checkpoint);
  // Blocks until everything offered so far is written (or failed).
  void flush();

  const std::string& path() const { return path_; }
  uint64_t written() const;
  uint64_t failed() const;
  uint64_t superseded() const;

 private:
  void run();

  std::string path_;
  uint64_t fingerprint_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  physics_io::Checkpoint pending_;
  bool have_pending_ = false;
  bool writing_ = false;
  bool stop_ = false;
  uint64_t written_ = 0;
  uint64_t failed_ = 0;
  uint64_t superseded_ = 0;
  std::string last_error_;
  std::thread thread_;  // last: starts once the rest is set up
};

}  // namespace vcockpit::physics_node
