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
//   keyframes:
//     - {t_s: 0.0, position: [x, y, z], rpy_deg: [r, p, y], shape: open}
//     - {t_s: 1.2, position: [...], shape: power}   # omitted position/rpy_deg: as before
// Built-in shapes: rest (hand.yaml rest pose), open, pinch, power.

#include <map>
#include <string>
#include <vector>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit {
class ConfigNode;
}

namespace vcockpit::glove {

struct Keyframe {
  int64_t t_ns = 0;
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  hand::JointAngles joints_rad{};
  std::string shape;
};

class GestureScript {
 public:
  // Throws ConfigError (file:line:col:key) on any bad value.
  static GestureScript load(const std::string& path, const hand::HandModel& hand);
  static GestureScript parse(const ConfigNode& root, const hand::HandModel& hand);

  double rate_hz() const { return rate_hz_; }
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
  std::vector<Keyframe> keyframes_;
};

// The built-in hand shapes (degrees by joint name) for a hand model.
std::map<std::string, hand::JointAngles> builtin_shapes(const hand::HandModel& hand);

}  // namespace vcockpit::glove
