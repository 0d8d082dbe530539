#pragma once
// A hand-joints recording as glove samples: placed in the cockpit, each hand retargeted
// (retarget.hpp) frame by frame, optionally on a hand calibrated from the recording itself. What
// the glove driver publishes for `--source joints`, and what hand_retarget writes as glove logs.

#include <Eigen/Geometry>

#include <array>
#include <optional>
#include <vector>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"
#include "hand/tracking/hand_calibration.hpp"
#include "hand/tracking/joints_log.hpp"
#include "hand/tracking/retarget.hpp"

namespace vcockpit::hand::tracking {

// Where a recording goes in the cockpit: the tracking space in G that puts the mean of its palm
// positions at `palm_G` (space xr: turned by R_G_xr; space cockpit: as recorded when `palm_G`
// is not given).
Eigen::Isometry3d placement(const std::vector<JointsFrame>& frames, JointsSpace space,
                            const std::optional<Eigen::Vector3d>& palm_G);

struct ReplayedHand {
  bool present = false;                // the recording has this hand
  HandModel model;                     // the hand it was retargeted on (calibrated or not)
  std::optional<HandCalibration> calibration;
  std::vector<GloveSample> samples;    // one per frame whose palm was placed
  std::vector<JointsFrame> frames_G;   // ... and that frame, in G
  int unplaced_frames = 0;             // frames whose palm could not be placed (left out)
  std::vector<double> tip_error_m;     // every tracked tip's error, sorted
  double tip_error_p50_m = -1.0;
  double tip_error_p99_m = -1.0;
};

struct JointsReplay {
  Eigen::Isometry3d X_GS = Eigen::Isometry3d::Identity();
  std::array<ReplayedHand, 2> hands;   // right, left
};

// `right`: the hand model (a right hand; the left is its mirror image). `calibrate`: measure each
// hand on the recording first (hand_calibration.hpp) and retarget on the calibrated hand.
JointsReplay replay_joints(const std::vector<JointsFrame>& frames, JointsSpace space,
                           const HandModel& right, bool calibrate,
                           const std::optional<Eigen::Vector3d>& palm_G = std::nullopt,
                           const RetargetOptions& options = {});

}  // namespace vcockpit::hand::tracking
