// Between two glove samples (physics_io/sample_interpolation.hpp): exact at the ends, linear in
// position and joints, slerp in orientation (the angle grows linearly), and the source stamp
// interpolated at the same fraction.

#include "physics_node/io/sample_interpolation.hpp"

#include <gtest/gtest.h>

namespace vcockpit::physics_io {
namespace {

hand::GloveSample sample(int64_t t_ns, double x_m, double angle_rad, double q_rad) {
  hand::GloveSample s;
  s.t_ns = t_ns;
  s.p_MT_m = Eigen::Vector3d(x_m, 0.5 * x_m, -x_m);
  s.q_MT = Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, Eigen::Vector3d(1, 2, 2) / 3.0));
  s.joints_rad.fill(q_rad);
  return s;
}

TEST(SampleInterpolation, ExactAtTheEndsAndClampedOutside) {
  const auto a = sample(1'000, 0.1, 0.2, 0.3);
  const auto b = sample(31'000, 0.4, 1.7, -0.3);
  for (int64_t t : {0, 1'000}) {
    const auto s = interpolate_sample(a, b, t);
    EXPECT_EQ(s.p_MT_m, a.p_MT_m);
    EXPECT_EQ(s.q_MT.coeffs(), a.q_MT.coeffs());
    EXPECT_EQ(s.joints_rad, a.joints_rad);
  }
  for (int64_t t : {31'000, 40'000}) {
    const auto s = interpolate_sample(a, b, t);
    EXPECT_EQ(s.p_MT_m, b.p_MT_m);
    EXPECT_EQ(s.q_MT.coeffs(), b.q_MT.coeffs());
    EXPECT_EQ(s.joints_rad, b.joints_rad);
  }
}

TEST(SampleInterpolation, LinearInPositionAndJointsSlerpInOrientation) {
  const auto a = sample(0, 0.1, 0.2, 0.3);
  const auto b = sample(30'000'000, 0.4, 1.7, -0.3);
  for (double f : {0.1, 1.0 / 3.0, 0.5, 0.9}) {
    const auto t = static_cast<int64_t>(f * 30'000'000);
    const double s_exact = static_cast<double>(t) / 30'000'000.0;
    const auto s = interpolate_sample(a, b, t);
    EXPECT_EQ(s.t_ns, t);
    const auto expected = sample(t, 0.1 + 0.3 * s_exact, 0.2 + 1.5 * s_exact, 0.3 - 0.6 * s_exact);
    EXPECT_LT((s.p_MT_m - expected.p_MT_m).norm(), 1e-15);
    EXPECT_LT(s.q_MT.angularDistance(expected.q_MT), 1e-12) << "angle grows linearly (slerp)";
    for (int j = 0; j < hand::kJointCount; ++j)
      EXPECT_NEAR(s.joints_rad[j], expected.joints_rad[j], 1e-15);
  }
}

TEST(SampleInterpolation, SlerpTakesTheShortArcWhateverTheQuaternionSign) {
  auto a = sample(0, 0, 0.1, 0);
  auto b = sample(10, 0, 0.5, 0);
  b.q_MT.coeffs() *= -1.0;  // the same rotation
  const auto s = interpolate_sample(a, b, 5);
  EXPECT_NEAR(s.q_MT.angularDistance(a.q_MT), 0.2, 1e-12);
}

TEST(SampleInterpolation, StampsAtTheSameFraction) {
  EXPECT_EQ(interpolate_stamp_ns(100, 400, 0, 30, 10), 200);
  EXPECT_EQ(interpolate_stamp_ns(100, 400, 0, 30, -5), 100);
  EXPECT_EQ(interpolate_stamp_ns(100, 400, 0, 30, 31), 400);
}

}  // namespace
}  // namespace vcockpit::physics_io
