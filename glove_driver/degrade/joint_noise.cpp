#include "glove_driver/degrade/joint_noise.hpp"

#include <cmath>

#include "common/assert.hpp"
#include "glove_driver/degrade/seeded_random.hpp"

namespace vcockpit::degrade {

void add_joint_noise(std::vector<hand::GloveSample>& samples, double sigma_rad, uint64_t seed) {
  SeededRandom random(seed, "joint_noise");
  for (hand::GloveSample& s : samples) {
    for (double& q : s.joints_rad) q += sigma_rad * random.normal();
  }
}

void quantize_joints(std::vector<hand::GloveSample>& samples, const hand::HandModel& hand,
                     int bits) {
  VCOCKPIT_ASSERT(bits >= 1 && bits <= 24, "quantize_joints: bits in [1, 24]");
  const double levels = std::ldexp(1.0, bits) - 1.0;
  for (hand::GloveSample& s : samples) {
    for (int j = 0; j < hand::kJointCount; ++j) {
      const hand::JointRange& range = hand.joints[j];
      const double step = (range.max_rad - range.min_rad) / levels;
      if (!(step > 0)) continue;  // a channel with no range has nothing to quantise
      double& q = s.joints_rad[j];
      q = range.min_rad + std::round((q - range.min_rad) / step) * step;
    }
  }
}

}  // namespace vcockpit::degrade
