#pragma once
// Hand-size calibration from a hand-tracking recording: the user's bone lengths and knuckle
// positions, so the drawn hand matches the real one and grasps land where the real fingers were.
//
//   bones     each finger's three phalanx lengths (the thumb: metacarpal, proximal, distal), the
//             median over the steady frames (palm slower than 0.5 m/s) where the finger's four
//             joints are all tracked;
//   knuckles  each finger's knuckle (the thumb's base), and the tracker's palm joint, in H,
//             the median over the
//             same frames with the palm placed as the retargeter places it; three passes, each
//             on the hand the last one made, since the palm's placement uses the knuckles.
// A finger the recording never tracks whole keeps the model's. The wrist joint is not measured:
// the anchors are measured in the frame they place, so each one measured is free to drift with
// that frame, and a wrist 1.6 cm off the model's turned the calibrated hand enough to miss the
// tips by 1.3 mm (HandCalibration test; palm.wrist_tracking_point sets it by hand). Pure,
// deterministic.

#include <array>
#include <vector>

#include "hand/hand_model.hpp"
#include "hand/tracking/joints_log.hpp"

namespace vcockpit::hand::tracking {

struct HandCalibration {
  std::array<std::array<double, 3>, kFingerCount> bone_m{};  // proximal, middle, distal link
  std::array<bool, kFingerCount> bones_measured{};
  std::array<Eigen::Vector3d, kFingerCount> knuckle_H{};
  std::array<bool, kFingerCount> knuckle_measured{};
  Eigen::Vector3d palm_H = Eigen::Vector3d::Zero();  // the tracker's palm joint, in H
  bool palm_measured = false;

  int steady_frames = 0;
};

// `frames_G`: one hand's frames (the model's side), in G (to_cockpit).
HandCalibration estimate_hand(const HandModel& model, const std::vector<JointsFrame>& frames_G);

// The model with the calibration's bone lengths (the chain rows' `a` after each phalanx's tag,
// and its capsule), knuckles (each chain's base moved by its knuckle's change) and the tracker's
// palm joint (HandModel::p_H_palm_joint; the palm's collision box stays: a tracker's palm point
// is not its centre, Leap's lies 2 cm nearer the knuckles).
HandModel calibrated(const HandModel& model, const HandCalibration& calibration);

}  // namespace vcockpit::hand::tracking
