#include "glove_driver/node/bridged_hand.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "hand/tracking/hand_calibration.hpp"

namespace vcockpit::glove::xr {

void TipErrorHistogram::add(double error_m) {
  if (!(error_m >= 0.0)) return;
  const auto bin = static_cast<std::size_t>(std::min(error_m / kBin_m, static_cast<double>(bins_.size() - 1)));
  ++bins_[bin];
  ++count_;
}

double TipErrorHistogram::quantile_m(double share) const {
  if (count_ == 0) return -1.0;
  const auto rank = static_cast<uint64_t>(std::ceil(share * static_cast<double>(count_)));
  uint64_t seen = 0;
  for (std::size_t i = 0; i < bins_.size(); ++i) {
    seen += bins_[i];
    if (seen >= std::max<uint64_t>(rank, 1)) return (static_cast<double>(i) + 0.5) * kBin_m;
  }
  return static_cast<double>(bins_.size()) * kBin_m;
}

BridgedHand::BridgedHand(DdsParticipant& participant, const hand::HandModel& model,
                         const BridgedHandOptions& options)
    : options_(options),
      model_(std::make_unique<hand::HandModel>(model)),
      publisher_(participant, *model_, options.publisher),  // model_ is made first
      joints_publisher_(participant, options.hand_id, options.publisher.lockstep),
      calibrating_(options.calibrate_s > 0.0) {
  if (!calibrating_) start_retargeting();
}

void BridgedHand::start_retargeting() {
  retargeter_ = std::make_unique<hand::tracking::Retargeter>(*model_);
}

void BridgedHand::take(const hand::tracking::JointsFrame& frame_G) {
  ++located_;
  if (calibrating_) {
    calibration_frames_G_.push_back(frame_G);
    const int64_t span_ns = frame_G.t_ns - calibration_frames_G_.front().t_ns;
    if (span_ns < std::llround(options_.calibrate_s * 1e9)) return;
    const hand::tracking::HandCalibration c = hand::tracking::estimate_hand(*model_, calibration_frames_G_);
    *model_ = hand::tracking::calibrated(*model_, c);
    if (c.steady_frames == 0)
      spdlog::warn("{} hand: no steady frame in its first {:.1f} s of tracking: the hand file's sizes are kept",
                   frame_G.left_hand ? "left" : "right", options_.calibrate_s);
    spdlog::info("{} hand calibrated on {} frames ({} steady): bones of {} fingers measured",
                 frame_G.left_hand ? "left" : "right", calibration_frames_G_.size(), c.steady_frames,
                 std::count(c.bones_measured.begin(), c.bones_measured.end(), true));
    calibration_frames_G_.clear();
    calibration_frames_G_.shrink_to_fit();
    calibrating_ = false;
    start_retargeting();
  }
  const hand::tracking::RetargetResult& r = retargeter_->fit(frame_G);
  if (!r.placed) {
    ++unplaced_;
    return;
  }
  for (double e : r.tip_error_m) tip_errors_.add(e);
  publisher_.publish(retargeter_->glove_sample(frame_G.t_ns));
  joints_publisher_.publish(frame_G, frame_G.t_ns);
}

}  // namespace vcockpit::glove::xr
