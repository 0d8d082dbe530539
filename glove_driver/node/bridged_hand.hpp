#pragma once
// One hand of openxr_hand_bridge: each located frame (already in the cockpit's frame G) is
// retargeted (hand/tracking/retarget.hpp) and published as a hand sample, with the joints it came
// from on cockpit/tracked_joints. With a calibration time, the hand's first seconds of frames are
// measured first (hand_calibration.hpp) and the hand is retargeted on the calibrated model from
// then on; nothing is published meanwhile.

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "dds/dds_participant.hpp"
#include "glove_driver/node/sample_publisher.hpp"
#include "glove_driver/node/tracked_joints_publisher.hpp"
#include "hand/hand_model.hpp"
#include "hand/tracking/retarget.hpp"

namespace vcockpit::glove::xr {

// Fingertip errors in 0.1 mm bins up to 10 cm (beyond: the last bin), for p50 / p99 over a
// session of any length without keeping every value.
class TipErrorHistogram {
 public:
  void add(double error_m);
  // The error below which this share of them fall (m); -1 when there is none.
  double quantile_m(double share) const;
  uint64_t count() const { return count_; }

 private:
  static constexpr double kBin_m = 1e-4;
  std::array<uint64_t, 1000> bins_{};
  uint64_t count_ = 0;
};

struct BridgedHandOptions {
  uint32_t hand_id = 0;
  double calibrate_s = 0.0;  // 0: retarget on the model as given
  PublisherOptions publisher;
};

class BridgedHand {
 public:
  BridgedHand(DdsParticipant& participant, const hand::HandModel& model, const BridgedHandOptions& options);

  bool wait_for_readers() { return publisher_.wait_for_readers(); }
  // One located frame of this hand, in G; `t_ns` its sample time.
  void take(const hand::tracking::JointsFrame& frame_G);
  void tick(int64_t now_ns) { publisher_.tick(now_ns); }
  bool finish() { return publisher_.finish(); }

  const hand::HandModel& model() const { return *model_; }
  bool calibrating() const { return calibrating_; }
  uint64_t located() const { return located_; }
  uint64_t unplaced() const { return unplaced_; }
  uint64_t published() const { return publisher_.published(); }
  const TipErrorHistogram& tip_errors() const { return tip_errors_; }
  const SamplePublisher& publisher() const { return publisher_; }

 private:
  void start_retargeting();

  BridgedHandOptions options_;
  std::unique_ptr<hand::HandModel> model_;  // the retargeter keeps a reference to it
  std::unique_ptr<hand::tracking::Retargeter> retargeter_;
  SamplePublisher publisher_;
  TrackedJointsPublisher joints_publisher_;
  bool calibrating_ = false;
  std::vector<hand::tracking::JointsFrame> calibration_frames_G_;
  uint64_t located_ = 0;
  uint64_t unplaced_ = 0;
  TipErrorHistogram tip_errors_;
};

}  // namespace vcockpit::glove::xr
