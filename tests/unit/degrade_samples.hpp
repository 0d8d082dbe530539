#pragma once
// Clean glove logs made in the test, for the degradation tests: a wrist moving smoothly and a
// hand whose grip opens, closes on nothing in particular, holds and opens again.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "common/pose.hpp"
#include "hand/glove_sample.hpp"
#include "hand/config/hand_yaml.hpp"

namespace vcockpit::test {

inline hand::HandModel default_hand() {
  return load_hand_model(std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/config/hand.yaml");
}

// rate_hz rows over [0, duration_s]; the wrist moves on a slow line and turns at a constant
// rate about a fixed axis; joints in mid-range.
inline std::vector<hand::GloveSample> smooth_log(const hand::HandModel& hand, double duration_s,
                                                 double rate_hz) {
  std::vector<hand::GloveSample> out;
  for (int64_t k = 0;; ++k) {
    const int64_t t_ns = std::llround(static_cast<double>(k) * 1e9 / rate_hz);
    if (t_ns > std::llround(duration_s * 1e9)) break;
    const double t = static_cast<double>(t_ns) * 1e-9;
    hand::GloveSample s;
    s.t_ns = t_ns;
    s.p_MT_m = Eigen::Vector3d(0.3 + 0.05 * t, -0.3 - 0.02 * t, 0.9 + 0.01 * t);
    s.q_MT = Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * t, Eigen::Vector3d(1, 2, 3).normalized()));
    for (int j = 0; j < hand::kJointCount; ++j) {
      s.joints_rad[j] = 0.5 * (hand.joints[j].min_rad + hand.joints[j].max_rad);
    }
    out.push_back(s);
  }
  return out;
}

// 1 kHz over [0, duration_s]: every joint channel sweeps its whole range [min, max], the wrist
// as in smooth_log.
inline std::vector<hand::GloveSample> sweep_log(const hand::HandModel& hand,
                                                double duration_s = 4.0) {
  auto out = smooth_log(hand, duration_s, 1000.0);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double u = static_cast<double>(i) / static_cast<double>(out.size() - 1);
    for (int j = 0; j < hand::kJointCount; ++j) {
      out[i].joints_rad[j] = hand.joints[j].min_rad + u * (hand.joints[j].max_rad - hand.joints[j].min_rad);
    }
  }
  return out;
}

// Minimum-jerk 0 -> 1.
inline double min_jerk(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
}

// Index and middle flexion, thumb opposition: 0 open, 1 closed.
inline hand::JointAngles grip_shape(const hand::HandModel& hand, double closed) {
  hand::JointAngles q = hand.rest_pose();
  auto set = [&](hand::Joint j, double open_deg, double closed_deg) {
    q[static_cast<int>(j)] = deg_to_rad(open_deg + closed * (closed_deg - open_deg));
  };
  set(hand::Joint::kThumbRotation, 10, 50);
  set(hand::Joint::kThumbMcp, 0, 30);
  set(hand::Joint::kThumbIp, 0, 30);
  set(hand::Joint::kIndexMcp, 0, 50);
  set(hand::Joint::kIndexPip, 0, 60);
  set(hand::Joint::kMiddleMcp, 0, 50);
  set(hand::Joint::kMiddlePip, 0, 60);
  return q;
}

// 1 kHz, 4 s: open at rest until 1.0 s, the grip closes over [1.0, 1.0 + close_s] with the
// wrist still, holds until 2.5 s, opens over [2.5, 3.0]; the wrist then travels 10 cm while the
// hand curls again over [3.2, 3.8] (a curl in transit, not a grip).
inline std::vector<hand::GloveSample> grip_log(const hand::HandModel& hand, double close_s = 0.8) {
  std::vector<hand::GloveSample> out;
  for (int64_t k = 0; k <= 4000; ++k) {
    const double t = static_cast<double>(k) * 1e-3;
    hand::GloveSample s;
    s.t_ns = k * 1'000'000;
    const double travel = min_jerk((t - 3.2) / 0.6);
    s.p_MT_m = Eigen::Vector3d(0.3 + 0.1 * travel, -0.3, 0.9);
    const double closed = min_jerk((t - 1.0) / close_s) - min_jerk((t - 2.5) / 0.5) +
                          min_jerk((t - 3.2) / 0.6);
    s.joints_rad = grip_shape(hand, closed);
    out.push_back(s);
  }
  return out;
}

}  // namespace vcockpit::test
