#pragma once
// Writes the world's checkpoints (physics_io::world_checkpoint) on a thread of its own, so the
// step loop never waits on the disk (an fsync takes milliseconds; a 1 kHz step has one). The loop
// hands over the newest encoded checkpoint; one still waiting when a newer comes is replaced
// (only the newest matters) and counted. A write that fails is logged once per kind of failure
// and counted; the node goes on simulating.

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace vcockpit::physics_node {

class CheckpointWriter {
 public:
  explicit CheckpointWriter(std::string path);
  ~CheckpointWriter();  // writes what is still waiting, then stops
  CheckpointWriter(const CheckpointWriter&) = delete;
  CheckpointWriter& operator=(const CheckpointWriter&) = delete;

  // Takes `bytes` (swapped out: the caller gets back a buffer to reuse).
  void offer(std::string& bytes);
  // Blocks until everything offered so far is written (or failed).
  void flush();

  const std::string& path() const { return path_; }
  uint64_t written() const;
  uint64_t failed() const;
  uint64_t superseded() const;

 private:
  void run();

  std::string path_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  std::string pending_;
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
