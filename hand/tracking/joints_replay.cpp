#include "hand/tracking/joints_replay.hpp"

#include <algorithm>

namespace vcockpit::hand::tracking {

Eigen::Isometry3d placement(const std::vector<JointsFrame>& frames, JointsSpace space,
                            const std::optional<Eigen::Vector3d>& palm_G) {
  Eigen::Isometry3d X_GS = Eigen::Isometry3d::Identity();
  if (space == JointsSpace::kXr) X_GS.linear() = R_G_xr();
  if (!palm_G) return X_GS;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (const JointsFrame& f : frames) {
    if (!f[XrJoint::kPalm].valid) continue;
    sum += f[XrJoint::kPalm].p_m;
    ++count;
  }
  if (count > 0) X_GS.translation() = *palm_G - X_GS.linear() * (sum / count);
  return X_GS;
}

JointsReplay replay_joints(const std::vector<JointsFrame>& frames, JointsSpace space,
                           const HandModel& right, bool calibrate,
                           const std::optional<Eigen::Vector3d>& palm_G,
                           const RetargetOptions& options) {
  JointsReplay out;
  out.X_GS = placement(frames, space, palm_G);
  std::array<std::vector<JointsFrame>, 2> sides;
  for (const JointsFrame& f : frames) sides[f.left_hand ? 1 : 0].push_back(to_cockpit(f, out.X_GS));
  for (int s = 0; s < 2; ++s) {
    ReplayedHand& hand = out.hands[static_cast<std::size_t>(s)];
    const std::vector<JointsFrame>& side = sides[static_cast<std::size_t>(s)];
    if (side.empty()) continue;
    hand.present = true;
    hand.model = s == 1 ? mirrored(right) : right;
    if (calibrate) {
      hand.calibration = estimate_hand(hand.model, side);
      hand.model = calibrated(hand.model, *hand.calibration);
    }
    Retargeter retarget(hand.model, options);
    for (const JointsFrame& f : side) {
      const RetargetResult& r = retarget.fit(f);
      if (!r.placed) {
        ++hand.unplaced_frames;
        continue;
      }
      hand.samples.push_back(retarget.glove_sample(f.t_ns));
      hand.frames_G.push_back(f);
      for (double e : r.tip_error_m)
        if (e >= 0.0) hand.tip_error_m.push_back(e);
    }
    std::sort(hand.tip_error_m.begin(), hand.tip_error_m.end());
    if (!hand.tip_error_m.empty()) {
      const std::size_t n = hand.tip_error_m.size();
      hand.tip_error_p50_m = hand.tip_error_m[n / 2];
      hand.tip_error_p99_m = hand.tip_error_m[std::min(n - 1, n * 99 / 100)];
    }
  }
  return out;
}

}  // namespace vcockpit::hand::tracking
