// tracker jitter: the statistics of the noise are the ones asked for; seeded.

#include <gtest/gtest.h>

#include "glove_driver/degrade/tracker_jitter.hpp"
#include "tests/unit/degrade_samples.hpp"

namespace vcockpit::degrade {
namespace {

struct Moments {
  double mean = 0.0;
  double sd = 0.0;
};

Moments moments(const std::vector<double>& v) {
  Moments m;
  for (double x : v) m.mean += x;
  m.mean /= static_cast<double>(v.size());
  for (double x : v) m.sd += (x - m.mean) * (x - m.mean);
  m.sd = std::sqrt(m.sd / static_cast<double>(v.size() - 1));
  return m;
}

TEST(TrackerJitter, PositionAndOrientationNoiseHaveTheirSigmas) {
  const auto hand = test::default_hand();
  const auto clean = test::smooth_log(hand, 20.0, 1000.0);  // 20001 samples
  auto noisy = clean;
  const TrackerJitter jitter{0.5e-3, deg_to_rad(0.2)};
  add_tracker_jitter(noisy, jitter, 7);
  std::array<std::vector<double>, 3> dp, dtheta;
  for (std::size_t i = 0; i < clean.size(); ++i) {
    const Eigen::Vector3d d = noisy[i].p_MT_m - clean[i].p_MT_m;
    // the rotation in the tracker's own frame: q_clean^-1 q_noisy
    const Eigen::AngleAxisd r(clean[i].q_MT.inverse() * noisy[i].q_MT);
    const Eigen::Vector3d rv = r.angle() * r.axis();
    for (int a = 0; a < 3; ++a) {
      dp[a].push_back(d[a]);
      dtheta[a].push_back(rv[a]);
    }
    EXPECT_EQ(noisy[i].joints_rad, clean[i].joints_rad);
    EXPECT_EQ(noisy[i].t_ns, clean[i].t_ns);
  }
  const double n = static_cast<double>(clean.size());
  for (int a = 0; a < 3; ++a) {
    const Moments p = moments(dp[a]);
    const Moments r = moments(dtheta[a]);
    // sd of a sample sd ~ sigma / sqrt(2n) = 0.5 %: 3 % is six of those
    EXPECT_NEAR(p.sd, jitter.sigma_m, 0.03 * jitter.sigma_m) << "axis " << a;
    EXPECT_NEAR(r.sd, jitter.sigma_rad, 0.03 * jitter.sigma_rad) << "axis " << a;
    EXPECT_LT(std::abs(p.mean), 5 * jitter.sigma_m / std::sqrt(n)) << "axis " << a;
    EXPECT_LT(std::abs(r.mean), 5 * jitter.sigma_rad / std::sqrt(n)) << "axis " << a;
  }
}

TEST(TrackerJitter, SameSeedSameNoiseOtherSeedOther) {
  const auto hand = test::default_hand();
  const auto clean = test::smooth_log(hand, 1.0, 1000.0);
  auto a = clean, b = clean, c = clean;
  add_tracker_jitter(a, {0.5e-3, 0.003}, 11);
  add_tracker_jitter(b, {0.5e-3, 0.003}, 11);
  add_tracker_jitter(c, {0.5e-3, 0.003}, 12);
  for (std::size_t i = 0; i < clean.size(); ++i) {
    EXPECT_EQ(a[i].p_MT_m, b[i].p_MT_m);
    EXPECT_EQ(a[i].q_MT.coeffs(), b[i].q_MT.coeffs());
  }
  EXPECT_NE(a[10].p_MT_m, c[10].p_MT_m);
}

}  // namespace
}  // namespace vcockpit::degrade
