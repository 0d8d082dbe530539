#include "bench/study/trial_variation.hpp"

#include <algorithm>
#include <cmath>

#include "glove_driver/degrade/seeded_random.hpp"

namespace vcockpit::study {
namespace {

// The inputs a trial may get, with their share of the trials: mostly a good rig, some worse.
struct Input {
  const char* name;
  std::vector<std::string> presets;
  double weight;
};
const std::vector<Input>& inputs() {
  static const std::vector<Input> kInputs = {
      {"clean", {}, 0.20},
      {"typical", {"typical"}, 0.30},
      {"120hz_jitter", {"120hz", "jitter"}, 0.10},
      {"glove_noise", {"100hz", "glove_noise"}, 0.10},
      {"30hz", {"30hz"}, 0.08},
      {"overrange", {"overrange"}, 0.08},
      {"dropouts", {"60hz", "dropouts"}, 0.08},
      {"harsh", {"harsh"}, 0.06},
  };
  return kInputs;
}

// Minimum jerk from 0 to 1 over u in [0, 1].
double min_jerk(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
}

constexpr hand::Joint kFlexion[] = {
    hand::Joint::kThumbMcp,  hand::Joint::kThumbIp,   hand::Joint::kIndexMcp,
    hand::Joint::kIndexPip,  hand::Joint::kIndexDip,  hand::Joint::kMiddleMcp,
    hand::Joint::kMiddlePip, hand::Joint::kMiddleDip, hand::Joint::kRingMcp,
    hand::Joint::kRingPip,   hand::Joint::kRingDip,   hand::Joint::kLittleMcp,
    hand::Joint::kLittlePip, hand::Joint::kLittleDip};

constexpr double kClosingSpan_s = 0.8;  // the scripts close their grips over this long

}  // namespace

TrialVariation draw_variation(uint64_t seed) {
  TrialVariation v;
  v.seed = seed;
  degrade::SeededRandom random(seed, "study");
  static const char* kSizes[][2] = {
      {"small", "hand_small.yaml"}, {"medium", "hand.yaml"}, {"large", "hand_large.yaml"}};
  const auto size = random.below(3);
  v.hand_size = kSizes[size][0];
  v.hand_yaml = kSizes[size][1];
  double pick = random.uniform();
  const Input* input = &inputs().back();
  for (const Input& in : inputs()) {
    if (pick < in.weight) {
      input = &in;
      break;
    }
    pick -= in.weight;
  }
  v.input = input->name;
  v.presets = input->presets;
  v.grip_closure_s = random.uniform(0.3, 0.8);
  v.aperture_scale = random.uniform(0.85, 1.15);
  for (auto& offset : v.approach_offset_G) {
    const double heading = random.uniform(0.0, 2.0 * M_PI);
    const double sideways_m = random.uniform(0.0, 0.025);
    offset = {sideways_m * std::cos(heading), sideways_m * std::sin(heading),
              random.uniform(0.0, 0.02)};
  }
  return v;
}

TrialVariation plain_variation() {
  TrialVariation v;
  v.hand_size = "medium";
  v.hand_yaml = "hand.yaml";
  v.input = "clean";
  v.grip_closure_s = 0.0;
  return v;
}

degrade::DegradeSpec degrade_spec(const TrialVariation& v) {
  degrade::DegradeSpec spec;
  for (const std::string& preset : v.presets) degrade::apply_preset(preset, spec);
  if (v.grip_closure_s > 0) spec.grip_closure_s = v.grip_closure_s;
  spec.seed = v.seed;
  return spec;
}

std::vector<hand::GloveSample> vary_approach(std::vector<hand::GloveSample> samples,
                                             const TrialVariation& v, int side, double arrive_s,
                                             double approach_end_s, const hand::HandModel& hand) {
  if (samples.empty()) return samples;
  const int64_t t0_ns = samples.front().t_ns;
  const Eigen::Matrix3d R_MG = hand.tracker.X_GM.linear().transpose();
  const Eigen::Vector3d offset_M = R_MG * v.approach_offset_G[side];
  const double rise_end_s = 0.75 * arrive_s;
  for (hand::GloveSample& s : samples) {
    const double t_s = static_cast<double>(s.t_ns - t0_ns) * 1e-9;
    // the offset: up over the first three quarters of the reach, down over the last
    const double w = t_s < rise_end_s ? min_jerk(t_s / rise_end_s)
                                      : 1.0 - min_jerk((t_s - rise_end_s) /
                                                       (arrive_s - rise_end_s));
    s.p_MT_m += w * offset_M;
    // the aperture: fully varied until the hand arrives, back to the script's by the grip's end
    const double a = 1.0 + (v.aperture_scale - 1.0) *
                               (1.0 - min_jerk((t_s - approach_end_s) / kClosingSpan_s));
    for (hand::Joint j : kFlexion) {
      const auto k = static_cast<std::size_t>(j);
      const double q = s.joints_rad[k] * a;
      s.joints_rad[k] = std::clamp(q, hand.joints[k].min_rad, hand.joints[k].max_rad);
    }
  }
  return samples;
}

}  // namespace vcockpit::study
