#include "image_generator/node/preview_publisher.hpp"

#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cmath>
#include <stdexcept>

#include "image_generator/render/image_scale.hpp"
#include "image_generator/render/png_writer.hpp"

namespace vcockpit::image_generator {

PreviewPublisher::PreviewPublisher(DdsParticipant& participant, int eye_width_px, int height_px,
                                   double rate_hz, int scale_down)
    : writer_(participant.make_writer<cockpit::PreviewFrame>("preview")),
      eye_width_px_(eye_width_px),
      height_px_(height_px),
      period_ns_(std::llround(1e9 / rate_hz)),
      scale_down_(scale_down) {
  if (!(rate_hz > 0) || scale_down < 1 || eye_width_px / scale_down < 1 || height_px / scale_down < 1)
    throw std::invalid_argument("preview: the rate must be positive and the scaled size at least 1 px");
  eye_.resize(static_cast<std::size_t>(eye_width_px) * static_cast<std::size_t>(height_px) * 4);
  worker_ = std::thread([this] { work(); });
}

PreviewPublisher::~PreviewPublisher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  worker_.join();
}

bool PreviewPublisher::offer(const uint8_t* side_by_side_rgba, uint64_t frame_seq,
                             int64_t sim_time_ns, int64_t now_ns) {
  if (now_ns < next_ns_) return false;
  if (writer_.matched_count() == 0) return false;  // nobody looks: no picture made
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (full_) return false;  // the worker is still at the last one
    // the left eye: the first eye_width of every row
    const std::size_t row = static_cast<std::size_t>(eye_width_px_) * 4;
    for (int y = 0; y < height_px_; ++y)
      std::copy_n(side_by_side_rgba + static_cast<std::size_t>(y) * 2 * row, row,
                  eye_.data() + static_cast<std::size_t>(y) * row);
    frame_seq_ = frame_seq;
    sim_time_ns_ = sim_time_ns;
    full_ = true;
  }
  wake_.notify_one();
  next_ns_ = now_ns + period_ns_;
  return true;
}

void PreviewPublisher::work() {
  // below the render thread and the physics: a late picture costs nothing, a late frame does
  setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10);
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return full_ || stopping_; });
    if (stopping_) return;
    lock.unlock();  // the render thread never writes a full slot
    try {
      render::downscale_rgba(eye_.data(), eye_width_px_, height_px_, scale_down_, scaled_);
      const int w = eye_width_px_ / scale_down_;
      const int h = height_px_ / scale_down_;
      const std::vector<uint8_t> png = render::encode_png(scaled_.data(), w, h, 1);
      message_.frame_seq(frame_seq_);
      message_.sim_time_ns(sim_time_ns_);
      message_.width_px(static_cast<uint32_t>(w));
      message_.height_px(static_cast<uint32_t>(h));
      message_.png(png);
      if (!writer_.write(message_)) throw std::runtime_error("the middleware refused the sample");
      lock.lock();
      ++published_;
    } catch (const std::exception& e) {
      lock.lock();
      if (failed_++ == 0) spdlog::warn("preview picture not published: {} (further failures counted)", e.what());
    }
    full_ = false;
  }
}

uint64_t PreviewPublisher::published() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return published_;
}

uint64_t PreviewPublisher::failed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failed_;
}

}  // namespace vcockpit::image_generator
