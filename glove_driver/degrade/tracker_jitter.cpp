#include "glove_driver/degrade/tracker_jitter.hpp"

#include "glove_driver/degrade/seeded_random.hpp"

namespace vcockpit::degrade {

void add_tracker_jitter(std::vector<hand::GloveSample>& samples, const TrackerJitter& jitter,
                        uint64_t seed) {
  SeededRandom random(seed, "tracker_jitter");
  for (hand::GloveSample& s : samples) {
    const Eigen::Vector3d dp(random.normal(), random.normal(), random.normal());
    const Eigen::Vector3d dtheta(random.normal(), random.normal(), random.normal());
    s.p_MT_m += jitter.sigma_m * dp;
    const Eigen::Vector3d rotation_vector = jitter.sigma_rad * dtheta;
    const double angle = rotation_vector.norm();
    if (angle > 0) {
      s.q_MT = (s.q_MT * Eigen::Quaterniond(Eigen::AngleAxisd(angle, rotation_vector / angle)))
                   .normalized();
    }
  }
}

}  // namespace vcockpit::degrade
