// grip_drift: how far a recorded hand carries an object it closes on, from the glove log alone.
// From a moment of the log (--from, s after its first sample: when the object is taken), the
// object is moved the way the tracked hand moves: by the wrist frame (eq. 29) and by the rigid
// fit (Kabsch) of the hand's link points (the palm's origin and each phalanx's midpoint), and its
// displacement from its pose in the scene is printed every --every s, with the gripping fingers'
// mean flexion change (an opening hand shows as a negative change), and the links' fit's
// displacement in the object's own frame (which way it went: across a bar or along it). A
// recording whose closed hand carries the object farther than half its support is wide will set it down off it, however
// faithfully the simulator follows the hand.
//   grip_drift --scene S.yaml --log GLOVE.csv --object NAME --from T [--to T] [--every 0.05]

#include <CLI/CLI.hpp>
#include <Eigen/SVD>

#include <algorithm>
#include <array>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "hand/glove_log.hpp"
#include "hand/hand_model.hpp"
#include "hand/tracker.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/physics/grasp_tracker.hpp"

namespace {

using namespace vcockpit;
using Points = std::vector<Eigen::Vector3d>;

// The rigid transform taking points `a` onto `b` in the least-squares sense (Kabsch).
Eigen::Isometry3d rigid_fit(const Points& a, const Points& b) {
  Eigen::Vector3d ca = Eigen::Vector3d::Zero(), cb = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) {
    ca += a[i];
    cb += b[i];
  }
  ca /= static_cast<double>(a.size());
  cb /= static_cast<double>(b.size());
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) H += (a[i] - ca) * (b[i] - cb).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0) D(2, 2) = -1.0;
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = svd.matrixV() * D * svd.matrixU().transpose();
  X.translation() = cb - X.linear() * ca;
  return X;
}

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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"grip_drift: how far a recorded hand carries an object it closes on"};
  std::string scene_path, log_path, object_name;
  double from_s = 0.0, to_s = 1e9, every_s = 0.05;
  app.add_option("--scene", scene_path, "scene YAML (its hand reads the log)")->required()->check(CLI::ExistingFile);
  app.add_option("--log", log_path, "glove log CSV")->required()->check(CLI::ExistingFile);
  app.add_option("--object", object_name, "the object the hand closes on")->required();
  app.add_option("--from", from_s, "when the object is taken (s after the log's first sample)")->required()->check(CLI::NonNegativeNumber);
  app.add_option("--to", to_s, "the last moment to print (s)")->check(CLI::NonNegativeNumber);
  app.add_option("--every", every_s, "print interval (s)")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  try {
    const physics::Scene scene = load_scene(scene_path);
    const int object = scene.find_object(object_name);
    if (object < 0) throw std::invalid_argument(scene_path + ": no object '" + object_name + "'");
    if (scene.hands.empty()) throw std::invalid_argument(scene_path + ": no hand");
    const hand::HandModel& model = scene.hands.front();
    const hand::GloveLog log = hand::read_glove_log(log_path, model);
    if (log.samples.empty()) throw std::invalid_argument(log_path + ": no samples");
    const Eigen::Isometry3d X_GO = scene.objects[static_cast<std::size_t>(object)].X_GO;
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
  } catch (const std::exception& e) {
    std::cerr << "grip_drift: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
