#pragma once
// A small picture of the pilot's left-eye view on cockpit/preview_frame, a few a second, for
// instructor displays. Made off the render thread: the render thread copies the left eye into
// the one slot when the period has passed and the worker is idle (otherwise that frame is simply
// not previewed, never waited for); the worker scales it down, encodes a PNG and writes it.
// Nothing is made while no reader is matched.

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "dds/dds_participant.hpp"

namespace vcockpit::image_generator {

class PreviewPublisher {
 public:
  // rate_hz > 0; scale_down: integer box-filter factor (2: a 1280x720 eye as 640x360).
  PreviewPublisher(DdsParticipant& participant, int eye_width_px, int height_px, double rate_hz,
                   int scale_down = 2);
  ~PreviewPublisher();
  PreviewPublisher(const PreviewPublisher&) = delete;
  PreviewPublisher& operator=(const PreviewPublisher&) = delete;

  // Render thread: offers the finished side-by-side RGBA8 frame; true if it was taken.
  bool offer(const uint8_t* side_by_side_rgba, uint64_t frame_seq, int64_t sim_time_ns,
             int64_t now_ns);
  uint64_t published() const;
  uint64_t failed() const;  // encoding or writing failed (logged once)

 private:
  void work();

  Writer<cockpit::PreviewFrame> writer_;
  int eye_width_px_;
  int height_px_;
  int64_t period_ns_;
  int scale_down_;
  int64_t next_ns_ = 0;
  // the slot, and what the worker makes of it
  std::vector<uint8_t> eye_;
  uint64_t frame_seq_ = 0;
  int64_t sim_time_ns_ = 0;
  bool full_ = false;
  bool stopping_ = false;
  std::vector<uint8_t> scaled_;
  cockpit::PreviewFrame message_;
  uint64_t published_ = 0;
  uint64_t failed_ = 0;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::thread worker_;
};

}  // namespace vcockpit::image_generator
