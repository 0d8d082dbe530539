#pragma once
// Glove samples made in the test for grip_fit: the project's hand closed in a fist round nothing
// (a power grasp's joint angles) or laid flat, palm down, at a fixed place in the world.

#include <cstdlib>
#include <string>

#include "common/pose.hpp"
#include "hand/glove_sample.hpp"
#include "hand/config/hand_yaml.hpp"

namespace vcockpit::test {

inline std::string source_dir() {
  return std::getenv("VCOCKPIT_SOURCE_DIR");
}

inline hand::HandModel grip_fit_hand() {
  return load_hand_model(source_dir() + "/config/hand.yaml");
}

// The wrist at (0.3, -0.3, 1.0) m, palm down (H = world axes), joints at `closure` of the way
// from flat (all 0) to a fist: MCP 60, PIP 70, DIP 40 deg; thumb rotation 45, MCP 30, IP 30;
// spreads, palm arch and wrist 0.
inline hand::GloveSample fist_sample(double closure = 1.0, int64_t t_ns = 0) {
  using hand::Joint;
  hand::GloveSample s;
  s.t_ns = t_ns;
  s.p_MT_m = Eigen::Vector3d(0.3, -0.3, 1.0);
  const auto set = [&](Joint j, double deg) {
    s.joints_rad[static_cast<int>(j)] = closure * deg_to_rad(deg);
  };
  for (Joint j : {Joint::kIndexMcp, Joint::kMiddleMcp, Joint::kRingMcp, Joint::kLittleMcp})
    set(j, 60);
  for (Joint j : {Joint::kIndexPip, Joint::kMiddlePip, Joint::kRingPip, Joint::kLittlePip})
    set(j, 70);
  for (Joint j : {Joint::kIndexDip, Joint::kMiddleDip, Joint::kRingDip, Joint::kLittleDip})
    set(j, 40);
  set(Joint::kThumbRotation, 45);
  set(Joint::kThumbMcp, 30);
  set(Joint::kThumbIp, 30);
  return s;
}

inline hand::GloveSample flat_sample() {
  return fist_sample(0.0);
}

}  // namespace vcockpit::test
