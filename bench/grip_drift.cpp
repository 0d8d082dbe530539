// grip_drift: how far a recorded hand carries an object it closes on, from the recording alone.
// From a moment of the recording (--from, s after its first sample: when the object is taken),
// the object's displacement from its pose in the scene is printed every --every s.
//   --log GLOVE.csv     the object moved the way the hand model moves: by the wrist frame
//                       (eq. 29) and by the rigid fit (Kabsch) of the hand's link points (the
//                       palm's origin and each phalanx's midpoint), with the gripping fingers'
//                       mean flexion change (an opening hand shows as a negative change) and the
//                       links' fit's displacement in the object's own frame (which way it went:
//                       across a bar or along it);
//   --joints HAND.csv   a hand-joints log (hand_import), before any hand model: how far the
//                       tracker's own palm, thumb tip and finger tips (their mean) went, in the
//                       object's frame, and how far the tips are from the palm (a hand opening
//                       shows as a growing distance). A recording's own fingertips are where a
//                       real object would be; the hand model and its fit add their error.
// A recording whose closed hand carries the object farther than half its support is wide will
// set it down off it, however faithfully the simulator follows the hand.
//   grip_drift --scene S.yaml (--log GLOVE.csv | --joints HAND.csv [--hand left|right])
//              --object NAME --from T [--to T] [--every 0.05]

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "hand/glove_log.hpp"
#include "hand/hand_model.hpp"
#include "hand/tracker.hpp"
#include "hand/tracking/joints_log.hpp"
#include "hand/tracking/joints_replay.hpp"
#include "hand/tracking/rigid_fit.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/physics/grasp_tracker.hpp"

namespace {

using namespace vcockpit;
using Points = std::vector<Eigen::Vector3d>;
using hand::tracking::rigid_fit;

struct HandAt {
  double t_s = 0.0;
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  Points points;           // the palm's origin, then each phalanx's midpoint
  double flexion_rad = 0;  // index to little, mean
};

HandAt hand_at(const hand::HandModel& model, hand::GloveSample sample, double t_s) {
  hand::clamp_to_limits(model, sample.joints_rad);
  HandAt h;
  h.t_s = t_s;
  h.X_GH = hand::X_GH_from_sample(model, sample);
  hand::HandLinkPoses links;
  hand::forward_kinematics(model, sample.joints_rad, links);
  h.points.push_back(h.X_GH * links.X_HL[0].translation());
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const double half_m = 0.5 * model.capsules[static_cast<std::size_t>(l)].length_m;
    h.points.push_back(h.X_GH * (links.X_HL[static_cast<std::size_t>(l)] * Eigen::Vector3d(half_m, 0, 0)));
  }
  for (int f = 1; f < hand::kFingerCount; ++f)
    h.flexion_rad += physics::finger_flexion_rad(sample.joints_rad, static_cast<hand::Finger>(f));
  h.flexion_rad /= hand::kFingerCount - 1;
  return h;
}

void print_glove_drift(const physics::Scene& scene, const std::string& scene_path,
                       const std::string& log_path, const std::string& object_name,
                       const Eigen::Isometry3d& X_GO, double from_s, double to_s, double every_s) {
  if (scene.hands.empty()) throw std::invalid_argument(scene_path + ": no hand");
  const hand::HandModel& model = scene.hands.front();
  const hand::GloveLog log = hand::read_glove_log(log_path, model);
  if (log.samples.empty()) throw std::invalid_argument(log_path + ": no samples");
  const int64_t t0_ns = log.samples.front().t_ns;

  std::vector<HandAt> hands;
  for (const hand::GloveSample& s : log.samples)
    hands.push_back(hand_at(model, s, hand::ns_to_log_seconds(s.t_ns - t0_ns)));
  const auto taken = std::find_if(hands.begin(), hands.end(), [&](const HandAt& h) { return h.t_s >= from_s; });
  if (taken == hands.end()) throw std::invalid_argument("--from is past the log's end");

  std::printf("# %s on %s, '%s' taken at %.3f s; its displacement (mm) moved by the wrist "
              "frame and by the rigid fit of the hand's links; the fingers' flexion change (deg)\n",
              log_path.c_str(), scene_path.c_str(), object_name.c_str(), taken->t_s);
  std::printf("%8s %12s %10s %12s %10s %10s   %s\n", "t_s", "wrist_xy", "wrist_z", "links_xy", "links_z",
              "flexion", "links_in_object_frame(x y z)");
  double next_s = taken->t_s;
  for (auto it = taken; it != hands.end() && it->t_s <= to_s; ++it) {
    if (it->t_s + 1e-9 < next_s) continue;
    next_s += every_s;
    const Eigen::Vector3d d_wrist =
        (it->X_GH * taken->X_GH.inverse() * X_GO).translation() - X_GO.translation();
    const Eigen::Vector3d d_links =
        (rigid_fit(taken->points, it->points) * X_GO).translation() - X_GO.translation();
    const Eigen::Vector3d d_links_O = X_GO.linear().transpose() * d_links;
    std::printf("%8.3f %12.1f %10.1f %12.1f %10.1f %10.1f   %6.1f %6.1f %6.1f\n", it->t_s,
                d_wrist.head<2>().norm() * 1e3, d_wrist.z() * 1e3, d_links.head<2>().norm() * 1e3,
                d_links.z() * 1e3, (it->flexion_rad - taken->flexion_rad) * 57.29577951308232,
                d_links_O.x() * 1e3, d_links_O.y() * 1e3, d_links_O.z() * 1e3);
  }
}

// The tracker's palm, thumb tip and mean finger tip (index to little, those tracked) of one
// frame of a hand-joints log, in G; false when the palm, the thumb tip or every finger tip is
// not tracked.
struct TrackedGrip {
  Eigen::Vector3d palm_G, thumb_G, fingers_G;
};

bool tracked_grip(const hand::tracking::JointsFrame& f, const Eigen::Isometry3d& X_GS, TrackedGrip& out) {
  using hand::tracking::XrJoint;
  if (!f[XrJoint::kPalm].valid || !f[XrJoint::kThumbTip].valid) return false;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (XrJoint tip : {XrJoint::kIndexTip, XrJoint::kMiddleTip, XrJoint::kRingTip, XrJoint::kLittleTip}) {
    if (!f[tip].valid) continue;
    sum += f[tip].p_m;
    ++count;
  }
  if (count == 0) return false;
  out.palm_G = X_GS * f[XrJoint::kPalm].p_m;
  out.thumb_G = X_GS * f[XrJoint::kThumbTip].p_m;
  out.fingers_G = X_GS * (sum / count);
  return true;
}

void print_joints_drift(const std::string& joints_path, bool left, const std::string& object_name,
                        const Eigen::Isometry3d& X_GO, double from_s, double to_s, double every_s) {
  const hand::tracking::JointsLog log = hand::tracking::read_joints_log(joints_path);
  const Eigen::Isometry3d X_GS = hand::tracking::placement(log.frames, log.space, std::nullopt);
  const hand::tracking::JointsFrame* first = nullptr;
  const hand::tracking::JointsFrame* taken = nullptr;
  TrackedGrip at_taken;
  for (const auto& f : log.frames) {
    if (f.left_hand != left) continue;
    if (first == nullptr) first = &f;
    if (hand::ns_to_log_seconds(f.t_ns - first->t_ns) + 1e-9 >= from_s && tracked_grip(f, X_GS, at_taken)) {
      taken = &f;
      break;
    }
  }
  if (taken == nullptr)
    throw std::invalid_argument(joints_path + ": no " + (left ? "left" : "right") +
                                " hand with its palm and tips tracked from --from on");
  const Eigen::Matrix3d R_OG = X_GO.linear().transpose();
  const auto in_O = [&](const Eigen::Vector3d& d_G) { return Eigen::Vector3d(R_OG * d_G * 1e3); };
  const auto reach_mm = [](const TrackedGrip& g) {
    return 0.5 * ((g.thumb_G - g.palm_G).norm() + (g.fingers_G - g.palm_G).norm()) * 1e3;
  };
  std::printf("# %s, %s hand, '%s' taken at %.3f s: the tracked palm, thumb tip and finger tips' "
              "mean, their displacement in the object's frame (mm); the tips' mean distance "
              "from the palm, change since (mm; an opening hand grows)\n",
              joints_path.c_str(), left ? "left" : "right", object_name.c_str(),
              hand::ns_to_log_seconds(taken->t_ns - first->t_ns));
  std::printf("%8s   %-22s %-22s %-22s %8s\n", "t_s", "palm(x y z)", "thumb_tip(x y z)",
              "finger_tips(x y z)", "reach");
  double next_s = hand::ns_to_log_seconds(taken->t_ns - first->t_ns);
  for (const auto* f = taken; f != log.frames.data() + log.frames.size(); ++f) {
    if (f->left_hand != left) continue;
    const double t_s = hand::ns_to_log_seconds(f->t_ns - first->t_ns);
    if (t_s > to_s) break;
    TrackedGrip now;
    if (t_s + 1e-9 < next_s || !tracked_grip(*f, X_GS, now)) continue;
    next_s += every_s;
    const Eigen::Vector3d palm = in_O(now.palm_G - at_taken.palm_G);
    const Eigen::Vector3d thumb = in_O(now.thumb_G - at_taken.thumb_G);
    const Eigen::Vector3d fingers = in_O(now.fingers_G - at_taken.fingers_G);
    std::printf("%8.3f   %6.1f %6.1f %6.1f   %6.1f %6.1f %6.1f   %6.1f %6.1f %6.1f   %8.1f\n", t_s,
                palm.x(), palm.y(), palm.z(), thumb.x(), thumb.y(), thumb.z(), fingers.x(),
                fingers.y(), fingers.z(), reach_mm(now) - reach_mm(at_taken));
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"grip_drift: how far a recorded hand carries an object it closes on"};
  std::string scene_path, log_path, joints_path, hand_side = "right", object_name;
  double from_s = 0.0, to_s = 1e9, every_s = 0.05;
  app.add_option("--scene", scene_path, "scene YAML (its hand reads the log)")->required()->check(CLI::ExistingFile);
  auto* log_opt = app.add_option("--log", log_path, "glove log CSV")->check(CLI::ExistingFile);
  auto* joints_opt = app.add_option("--joints", joints_path, "hand-joints log CSV (hand_import)")->check(CLI::ExistingFile);
  log_opt->excludes(joints_opt);
  app.add_option("--hand", hand_side, "the hand of the hand-joints log")->check(CLI::IsMember({"right", "left"}));
  app.add_option("--object", object_name, "the object the hand closes on")->required();
  app.add_option("--from", from_s, "when the object is taken (s after the log's first sample)")->required()->check(CLI::NonNegativeNumber);
  app.add_option("--to", to_s, "the last moment to print (s)")->check(CLI::NonNegativeNumber);
  app.add_option("--every", every_s, "print interval (s)")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  if (log_path.empty() == joints_path.empty()) {
    std::cerr << "grip_drift: give --log (a glove log) or --joints (a hand-joints log)\n";
    return 2;
  }
  try {
    const physics::Scene scene = load_scene(scene_path);
    const int object = scene.find_object(object_name);
    if (object < 0) throw std::invalid_argument(scene_path + ": no object '" + object_name + "'");
    const Eigen::Isometry3d X_GO = scene.objects[static_cast<std::size_t>(object)].X_GO;
    if (!log_path.empty())
      print_glove_drift(scene, scene_path, log_path, object_name, X_GO, from_s, to_s, every_s);
    else
      print_joints_drift(joints_path, hand_side == "left", object_name, X_GO, from_s, to_s, every_s);
  } catch (const std::exception& e) {
    std::cerr << "grip_drift: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
