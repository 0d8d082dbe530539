#pragma once
// Synthetic glove source: keyframed gestures. Each keyframe gives the hand pose in the world
// (X_GH) and a hand shape; between keyframes the pose and the joint angles follow a
// minimum-jerk profile (zero velocity and acceleration at every keyframe, like a person's
// point-to-point reach), orientations by slerp.
//
// Script YAML:
//   rate_hz: 1000                      # optional, samples per second
//   shapes:                            # optional extra shapes: joint angles in degrees,
//     grip: {index_mcp: 50, ...}       #   joints not named take the hand's rest pose
//   grasp_point: {shape: grip, fingers: [index, middle]}   # optional, see below
//   tip_point: {shape: point, finger: index}   # optional: a fingertip, for pressing and pushing
//   keyframes:
//     - {t_s: 0.0, position: [x, y, z], rpy_deg: [r, p, y], shape: open}
//     - {t_s: 1.2, position: [...], shape: power}   # omitted position/rpy_deg: as before
//     - {t_s: 2.0, grasp_at: [x, y, z]}             # the grasp point there, not the wrist
//     - {t_s: 3.0, tip_at: [x, y, z]}               # the fingertip's centre there
// Built-in shapes: rest (hand.yaml rest pose), open, pinch, power.
//
// Placing the hand by its grasp point, so one script fits hands of every size: `position` puts
// the wrist (the origin of H) at a point, which suits one hand only — a smaller hand's fingers
// would close short of an object a larger hand's reach round. `grasp_at` puts the script's grasp
// point there instead: the point midway between the thumb tip and the mean of the named
// fingertips when the hand takes `shape` (the shape the grip closes to), computed from the
// loaded hand model. A script places that point at the object's centre, and each hand's wrist
// follows from its own size. The point is fixed in H (one shape for the whole script), so the
// wrist does not move as the fingers close. A keyframe that gives neither position nor grasp_at
// keeps the previous keyframe's: its wrist if that gave `position`, its grasp point if it gave
// `grasp_at` (turning the hand then turns it about that point).
//
// `tip_at` places the hand the same way by one fingertip instead: the centre of the tip's
// rounded end (its surface is the finger's radius further on) when the hand takes the tip
// point's shape. A script that presses buttons and flips switches aims the fingertip at the
// control, whatever the hand's size. Between two keyframes placed by the same point, that point
// moves straight; otherwise the wrist does.

#include <map>
#include <string>
#include <vector>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit {
class ConfigNode;
}

namespace vcockpit::glove {

// What a keyframe places: the wrist (position), the grasp point (grasp_at) or the tip point
// (tip_at).
enum class Anchor : uint8_t { kWrist, kGraspPoint, kTipPoint };

struct Keyframe {
  int64_t t_ns = 0;
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  Anchor anchor = Anchor::kWrist;
  Eigen::Vector3d p_G_anchor = Eigen::Vector3d::Zero();  // where the anchor point is (not the wrist)
  hand::JointAngles joints_rad{};
  std::string shape;
};

class GestureScript {
 public:
  // Throws ConfigError (file:line:col:key) on any bad value.
  static GestureScript load(const std::string& path, const hand::HandModel& hand);
  static GestureScript parse(const ConfigNode& root, const hand::HandModel& hand);

  double rate_hz() const { return rate_hz_; }
  // The grasp point in H for this hand (zero when the script has none).
  const Eigen::Vector3d& p_H_grasp() const { return p_H_grasp_; }
  // The tip point in H for this hand (zero when the script has none).
  const Eigen::Vector3d& p_H_tip() const { return p_H_tip_; }
  int64_t duration_ns() const { return keyframes_.back().t_ns; }
  const std::vector<Keyframe>& keyframes() const { return keyframes_; }

  // The hand in the world and its joints at time t (clamped to the script's span).
  void evaluate(int64_t t_ns, Eigen::Isometry3d& X_GH, hand::JointAngles& joints_rad) const;
  // The glove reading that produces that hand: tracker pose X_MT through the hand's tracker
  // mounting (X_MT = X_GM^-1 X_GH X_TH^-1).
  hand::GloveSample sample_at(int64_t t_ns) const;

 private:
  GestureScript(const hand::HandModel& hand) : hand_(&hand) {}

  const hand::HandModel* hand_;
  double rate_hz_ = 1000.0;
  bool has_grasp_point_ = false;
  Eigen::Vector3d p_H_grasp_ = Eigen::Vector3d::Zero();
  bool has_tip_point_ = false;
  Eigen::Vector3d p_H_tip_ = Eigen::Vector3d::Zero();
  // the anchor's point in H: zero for the wrist
  const Eigen::Vector3d& p_H_anchor(Anchor anchor) const;
  std::vector<Keyframe> keyframes_;
};

// The samples a synthetic glove driver publishes for the script at `path` (and its recorder
// writes): one every 1 / rate_hz from 0 to the script's end. Throws ConfigError.
std::vector<hand::GloveSample> script_samples(const std::string& path, const hand::HandModel& hand);

// The built-in hand shapes (degrees by joint name) for a hand model.
std::map<std::string, hand::JointAngles> builtin_shapes(const hand::HandModel& hand);

// Midway between the thumb tip and the mean of `fingers`' tips (not the thumb), in H, for the
// hand in shape q.
Eigen::Vector3d grasp_point_H(const hand::HandModel& hand, const hand::JointAngles& q,
                              const std::vector<hand::Finger>& fingers);

}  // namespace vcockpit::glove
