#include "glove_driver/glove/gesture_script.hpp"

#include <cmath>

#include <algorithm>

#include "common/pose.hpp"
#include "hand/tracker.hpp"
#include "common/yaml_config.hpp"

namespace vcockpit::glove {
namespace {

using hand::Joint;
using hand::JointAngles;

JointAngles shape_from_degrees(const hand::HandModel& hand,
                               std::initializer_list<std::pair<Joint, double>> degrees) {
  JointAngles q = hand.rest_pose();
  for (auto [joint, deg] : degrees) q[static_cast<int>(joint)] = deg_to_rad(deg);
  hand::clamp_to_limits(hand, q);
  return q;
}

// Minimum-jerk blend 0 -> 1 with zero velocity and acceleration at both ends.
double min_jerk(double u) { return u * u * u * (10.0 + u * (-15.0 + 6.0 * u)); }

}  // namespace

std::map<std::string, JointAngles> builtin_shapes(const hand::HandModel& hand) {
  std::map<std::string, JointAngles> shapes;
  shapes["rest"] = hand.rest_pose();
  // open: fingers straight and slightly spread, thumb out to the side
  shapes["open"] = shape_from_degrees(
      hand, {{Joint::kThumbRotation, 10}, {Joint::kThumbMcp, 0}, {Joint::kThumbIp, 0},
             {Joint::kThumbAbduction, 20}, {Joint::kIndexMcp, 0}, {Joint::kIndexPip, 0},
             {Joint::kIndexDip, 0}, {Joint::kMiddleMcp, 0}, {Joint::kMiddlePip, 0},
             {Joint::kMiddleDip, 0}, {Joint::kRingMcp, 0}, {Joint::kRingPip, 0},
             {Joint::kRingDip, 0}, {Joint::kLittleMcp, 0}, {Joint::kLittlePip, 0},
             {Joint::kLittleDip, 0}, {Joint::kMiddleIndexAbduction, 5},
             {Joint::kRingMiddleAbduction, 5}, {Joint::kLittleRingAbduction, 5}});
  // pinch: thumb tip against the index tip, other fingers curled out of the way
  shapes["pinch"] = shape_from_degrees(
      hand, {{Joint::kThumbRotation, 40}, {Joint::kThumbMcp, 25}, {Joint::kThumbIp, 20},
             {Joint::kThumbAbduction, 10}, {Joint::kIndexMcp, 45}, {Joint::kIndexPip, 40},
             {Joint::kIndexDip, 20}, {Joint::kMiddleMcp, 60}, {Joint::kMiddlePip, 80},
             {Joint::kMiddleDip, 50}, {Joint::kRingMcp, 65}, {Joint::kRingPip, 85},
             {Joint::kRingDip, 50}, {Joint::kLittleMcp, 70}, {Joint::kLittlePip, 85},
             {Joint::kLittleDip, 50}});
  // power: all fingers wrapped round a handle, thumb closing over them
  shapes["power"] = shape_from_degrees(
      hand, {{Joint::kThumbRotation, 50}, {Joint::kThumbMcp, 35}, {Joint::kThumbIp, 30},
             {Joint::kThumbAbduction, 5}, {Joint::kIndexMcp, 55}, {Joint::kIndexPip, 70},
             {Joint::kIndexDip, 40}, {Joint::kMiddleMcp, 60}, {Joint::kMiddlePip, 75},
             {Joint::kMiddleDip, 40}, {Joint::kRingMcp, 60}, {Joint::kRingPip, 75},
             {Joint::kRingDip, 40}, {Joint::kLittleMcp, 60}, {Joint::kLittlePip, 70},
             {Joint::kLittleDip, 40}});
  return shapes;
}

Eigen::Vector3d grasp_point_H(const hand::HandModel& hand, const hand::JointAngles& q,
                              const std::vector<hand::Finger>& fingers) {
  hand::HandLinkPoses poses;
  hand::forward_kinematics(hand, q, poses);
  Eigen::Vector3d fingers_mean = Eigen::Vector3d::Zero();
  for (hand::Finger f : fingers) fingers_mean += poses.p_H_tip[static_cast<int>(f)];
  fingers_mean /= static_cast<double>(fingers.size());
  return 0.5 * (poses.p_H_tip[static_cast<int>(hand::Finger::kThumb)] + fingers_mean);
}

GestureScript GestureScript::load(const std::string& path, const hand::HandModel& hand) {
  return parse(ConfigNode::load_file(path), hand);
}

GestureScript GestureScript::parse(const ConfigNode& root, const hand::HandModel& hand) {
  root.expect_keys({"rate_hz", "shapes", "grasp_point", "tip_point", "keyframes"});
  GestureScript script(hand);
  if (auto rate = root.find("rate_hz")) {
    script.rate_hz_ = rate->as_double();
    if (script.rate_hz_ <= 0 || script.rate_hz_ > 100'000) rate->fail("must be in (0, 100000] Hz");
  }
  auto shapes = builtin_shapes(hand);
  if (auto extra = root.find("shapes")) {
    for (const auto& name : extra->keys()) {
      const ConfigNode node = (*extra)[name];
      JointAngles q = hand.rest_pose();
      for (const auto& joint_name : node.keys()) {
        const int j = hand::joint_index(joint_name);
        if (j < 0) node[joint_name].fail("unknown joint '" + joint_name + "'");
        q[j] = deg_to_rad(node[joint_name].as_double());
      }
      if (hand::clamp_to_limits(hand, q) > 0) node.fail("joint angles beyond the hand's limits");
      shapes[name] = q;
    }
  }
  if (auto grasp = root.find("grasp_point")) {
    grasp->expect_keys({"shape", "fingers"});
    const std::string shape = grasp->get_string("shape");
    auto it = shapes.find(shape);
    if (it == shapes.end()) (*grasp)["shape"].fail("unknown hand shape '" + shape + "'");
    const ConfigNode names = (*grasp)["fingers"];
    std::vector<hand::Finger> fingers;
    for (const ConfigNode& name : names.elements()) {
      const std::string text = name.as_string();
      bool found = false;
      for (int f = 1; f < hand::kFingerCount; ++f) {  // the thumb is always one side
        if (hand::finger_name(static_cast<hand::Finger>(f)) == text) {
          fingers.push_back(static_cast<hand::Finger>(f));
          found = true;
        }
      }
      if (!found) name.fail("expected index, middle, ring or little, found '" + text + "'");
    }
    if (fingers.empty()) names.fail("name at least one finger to oppose the thumb");
    script.has_grasp_point_ = true;
    script.p_H_grasp_ = grasp_point_H(hand, it->second, fingers);
  }
  if (auto tip = root.find("tip_point")) {
    tip->expect_keys({"shape", "finger"});
    const std::string shape = tip->get_string("shape");
    auto it = shapes.find(shape);
    if (it == shapes.end()) (*tip)["shape"].fail("unknown hand shape '" + shape + "'");
    const std::string text = tip->get_string("finger");
    int finger = -1;
    for (int f = 0; f < hand::kFingerCount; ++f)
      if (hand::finger_name(static_cast<hand::Finger>(f)) == text) finger = f;
    if (finger < 0) (*tip)["finger"].fail("expected thumb, index, middle, ring or little, found '" + text + "'");
    hand::HandLinkPoses poses;
    hand::forward_kinematics(hand, it->second, poses);
    script.has_tip_point_ = true;
    script.p_H_tip_ = poses.p_H_tip[finger];
  }
  const ConfigNode frames = root["keyframes"];
  if (frames.size() < 1) frames.fail("needs at least one keyframe");
  for (const ConfigNode& frame : frames.elements()) {
    frame.expect_keys({"t_s", "position", "grasp_at", "tip_at", "rpy_deg", "shape"});
    Keyframe k;
    const double t_s = frame.get_double("t_s");
    k.t_ns = hand::log_seconds_to_ns(t_s);
    if (script.keyframes_.empty() ? t_s < 0 : k.t_ns <= script.keyframes_.back().t_ns) {
      frame["t_s"].fail("keyframe times must start at 0 or later and increase");
    }
    const Keyframe* previous = script.keyframes_.empty() ? nullptr : &script.keyframes_.back();
    auto position = frame.find("position");
    auto grasp_at = frame.find("grasp_at");
    auto tip_at = frame.find("tip_at");
    auto rpy = frame.find("rpy_deg");
    if ((position ? 1 : 0) + (grasp_at ? 1 : 0) + (tip_at ? 1 : 0) > 1)
      frame.fail("give one of position (the wrist), grasp_at and tip_at");
    if (grasp_at && !script.has_grasp_point_) {
      grasp_at->fail("grasp_at needs the script's grasp_point: {shape, fingers}");
    }
    if (tip_at && !script.has_tip_point_) {
      tip_at->fail("tip_at needs the script's tip_point: {shape, finger}");
    }
    if (!previous && (!(position || grasp_at || tip_at) || !rpy)) {
      frame.fail("the first keyframe needs position (or grasp_at or tip_at) and rpy_deg");
    }
    const Eigen::Matrix3d R = rpy ? pose_from_position_rpy_deg({0, 0, 0}, rpy->as_doubles<3>()).linear()
                                  : Eigen::Matrix3d(previous->X_GH.linear());
    if (position) k.anchor = Anchor::kWrist;
    else if (grasp_at) k.anchor = Anchor::kGraspPoint;
    else if (tip_at) k.anchor = Anchor::kTipPoint;
    else k.anchor = previous->anchor;
    if (k.anchor == Anchor::kWrist) {
      k.p_G_anchor = position ? Eigen::Vector3d(position->as_doubles<3>().data())
                              : previous->X_GH.translation();
      k.X_GH = make_pose(k.p_G_anchor, R);
    } else {
      const auto given = grasp_at ? grasp_at : tip_at;
      k.p_G_anchor = given ? Eigen::Vector3d(given->as_doubles<3>().data()) : previous->p_G_anchor;
      k.X_GH = make_pose(k.p_G_anchor - R * script.p_H_anchor(k.anchor), R);
    }
    k.shape = frame.get_string("shape", previous ? previous->shape : "rest");
    auto it = shapes.find(k.shape);
    if (it == shapes.end()) frame["shape"].fail("unknown hand shape '" + k.shape + "'");
    k.joints_rad = it->second;
    script.keyframes_.push_back(k);
  }
  return script;
}

void GestureScript::evaluate(int64_t t_ns, Eigen::Isometry3d& X_GH,
                             JointAngles& joints_rad) const {
  auto next = std::upper_bound(keyframes_.begin(), keyframes_.end(), t_ns,
                               [](int64_t t, const Keyframe& k) { return t < k.t_ns; });
  if (next == keyframes_.begin() || next == keyframes_.end()) {
    const Keyframe& k = next == keyframes_.begin() ? keyframes_.front() : keyframes_.back();
    X_GH = k.X_GH;
    joints_rad = k.joints_rad;
    return;
  }
  const Keyframe& a = *(next - 1);
  const Keyframe& b = *next;
  const double s = min_jerk(static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns));
  const Eigen::Quaterniond qa(a.X_GH.linear());
  const Eigen::Quaterniond qb(b.X_GH.linear());
  const Eigen::Matrix3d R = qa.slerp(s, qb).toRotationMatrix();
  if (a.anchor == b.anchor && a.anchor != Anchor::kWrist) {
    // the anchor point moves straight and the hand turns about it
    X_GH = make_pose(a.p_G_anchor + s * (b.p_G_anchor - a.p_G_anchor) - R * p_H_anchor(a.anchor), R);
  } else {
    X_GH = make_pose(a.X_GH.translation() + s * (b.X_GH.translation() - a.X_GH.translation()), R);
  }
  for (int j = 0; j < hand::kJointCount; ++j) {
    joints_rad[j] = a.joints_rad[j] + s * (b.joints_rad[j] - a.joints_rad[j]);
  }
}

const Eigen::Vector3d& GestureScript::p_H_anchor(Anchor anchor) const {
  static const Eigen::Vector3d kWrist = Eigen::Vector3d::Zero();
  switch (anchor) {
    case Anchor::kGraspPoint: return p_H_grasp_;
    case Anchor::kTipPoint: return p_H_tip_;
    case Anchor::kWrist: break;
  }
  return kWrist;
}

std::vector<hand::GloveSample> script_samples(const std::string& path, const hand::HandModel& hand) {
  const auto script = GestureScript::load(path, hand);
  std::vector<hand::GloveSample> out;
  for (int64_t k = 0;; ++k) {
    const int64_t t_ns = std::llround(static_cast<double>(k) * 1e9 / script.rate_hz());
    if (t_ns > script.duration_ns()) break;
    out.push_back(script.sample_at(t_ns));
  }
  return out;
}

hand::GloveSample GestureScript::sample_at(int64_t t_ns) const {
  Eigen::Isometry3d X_GH;
  hand::GloveSample out;
  out.t_ns = t_ns;
  evaluate(t_ns, X_GH, out.joints_rad);
  const Eigen::Isometry3d X_TH =
      hand::X_MH_from_tracker(*hand_, Eigen::Isometry3d::Identity(), out.joints_rad);
  const Eigen::Isometry3d X_MT = hand_->tracker.X_GM.inverse() * X_GH * X_TH.inverse();
  out.p_MT_m = X_MT.translation();
  out.q_MT = Eigen::Quaterniond(X_MT.linear()).normalized();
  return out;
}

}  // namespace vcockpit::glove
