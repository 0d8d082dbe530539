#include "physics_node/node/checkpoint_writer.hpp"

#include <spdlog/spdlog.h>

#include "common/atomic_file.hpp"

namespace vcockpit::physics_node {

CheckpointWriter::CheckpointWriter(std::string path, uint64_t scene_fingerprint)
    : path_(std::move(path)), fingerprint_(scene_fingerprint), thread_([this] { run(); }) {}

CheckpointWriter::~CheckpointWriter() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void CheckpointWriter::offer(physics_io::Checkpoint& checkpoint) {
  {
    std::lock_guard lock(mutex_);
    if (have_pending_) ++superseded_;
    std::swap(pending_, checkpoint);
    have_pending_ = true;
  }
  wake_.notify_one();
}

void CheckpointWriter::flush() {
  std::unique_lock lock(mutex_);
  done_.wait(lock, [this] { return !have_pending_ && !writing_; });
}

uint64_t CheckpointWriter::written() const {
  std::lock_guard lock(mutex_);
  return written_;
}
uint64_t CheckpointWriter::failed() const {
  std::lock_guard lock(mutex_);
  return failed_;
}
uint64_t CheckpointWriter::superseded() const {
  std::lock_guard lock(mutex_);
  return superseded_;
}

void CheckpointWriter::run() {
  physics_io::Checkpoint checkpoint;
  std::string bytes;
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return have_pending_ || stop_; });
    if (!have_pending_) break;  // stopping with nothing left to write
    std::swap(checkpoint, pending_);
    have_pending_ = false;
    writing_ = true;
    lock.unlock();
    std::string error;
    try {
      physics_io::encode_checkpoint(checkpoint, fingerprint_, bytes);
      physics_io::write_checkpoint_file(path_, bytes);
    } catch (const std::exception& e) {
      error = e.what();
    }
    lock.lock();
    writing_ = false;
    if (error.empty()) {
      ++written_;
    } else {
      ++failed_;
      if (error != last_error_) spdlog::error("checkpoint not written: {}", error);
      last_error_ = error;
    }
    done_.notify_all();
  }
  done_.notify_all();
}

}  // namespace vcockpit::physics_node
