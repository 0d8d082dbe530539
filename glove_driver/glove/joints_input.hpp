#pragma once
// `--source joints`: a hand-joints log (hand/tracking/joints_log.hpp) retargeted to the driver's
// hand (hand/tracking/joints_replay.hpp) and replayed as a glove log is, with the same flags. One
// driver publishes one hand: the log's only hand, or the one asked for.

#include <Eigen/Core>

#include <optional>
#include <string>

#include "hand/glove_log.hpp"
#include "glove_driver/glove/sample_source.hpp"
#include "hand/hand_model.hpp"
#include "hand/tracking/joints_log.hpp"

namespace vcockpit::glove {

struct JointsInputOptions {
  std::optional<bool> left_hand;       // which of the log's hands; unset: its only one
  bool calibrate = false;              // measure the hand on the recording first
  Eigen::Vector3d palm_G = Eigen::Vector3d(0.36, -0.35, 0.84);  // the mean palm's place (m)
};

struct JointsInput {
  hand::GloveLog log;                  // the retargeted samples, as a replayed glove log
  std::vector<hand::tracking::JointsFrame> frames_G;  // each sample's frame, in G
  hand::HandModel hand;                // the hand they were retargeted on
  double tip_error_p50_m = -1.0;
  double tip_error_p99_m = -1.0;
  int unplaced_frames = 0;
};

// `right`: the hand file's model as a right hand. Throws hand::tracking::JointsLogError (a bad
// log, or no frame of the hand) and std::invalid_argument (the side is missing or ambiguous).
JointsInput joints_input(const std::string& path, const hand::HandModel& right,
                         const JointsInputOptions& options);

// The retargeted samples replayed (a ReplaySource), each with the tracker's joints it came from.
class JointsSource : public ReplaySource {
 public:
  JointsSource(JointsInput input, const ReplayOptions& options)
      : ReplaySource(std::move(input.log), options), frames_G_(std::move(input.frames_G)) {}
  bool has_tracked_joints() const override { return true; }
  const hand::tracking::JointsFrame* tracked_joints() const override {
    const std::size_t i = cursor().last_index();
    return i < frames_G_.size() ? &frames_G_[i] : nullptr;
  }

 private:
  std::vector<hand::tracking::JointsFrame> frames_G_;
};

}  // namespace vcockpit::glove
