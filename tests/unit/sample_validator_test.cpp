// SampleValidator: non-finite, bad quaternion and stale samples rejected, joints clamped and counted.

#include <gtest/gtest.h>

#include <cmath>

#include "hand/config/hand_yaml.hpp"
#include "hand/sample_validator.hpp"

namespace vcockpit::hand {
namespace {

HandModel default_hand() {
  return load_hand_model(std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/config/hand.yaml");
}

TEST(SampleValidator, RejectsNonFiniteBadQuaternionAndStaleAndClampsJoints) {
  const auto hand = default_hand();
  SampleValidator validator(hand);
  GloveSample ok;
  ok.t_ns = 100;
  ok.joints_rad = hand.rest_pose();
  EXPECT_TRUE(validator.accept(ok));

  GloveSample nan = ok;
  nan.t_ns = 200;
  nan.joints_rad[3] = std::nan("");
  EXPECT_FALSE(validator.accept(nan));

  GloveSample bad_q = ok;
  bad_q.t_ns = 200;
  bad_q.q_MT = Eigen::Quaterniond(2, 0, 0, 0);
  EXPECT_FALSE(validator.accept(bad_q));

  GloveSample stale = ok;
  stale.t_ns = 100;
  EXPECT_FALSE(validator.accept(stale));

  GloveSample beyond = ok;
  beyond.t_ns = 300;
  beyond.joints_rad[static_cast<int>(Joint::kIndexPip)] = 10.0;
  EXPECT_TRUE(validator.accept(beyond));
  EXPECT_EQ(beyond.joints_rad[static_cast<int>(Joint::kIndexPip)],
            hand.joints[static_cast<int>(Joint::kIndexPip)].max_rad);

  const auto& c = validator.counts();
  EXPECT_EQ(c.accepted, 2u);
  EXPECT_EQ(c.rejected_nonfinite, 1u);
  EXPECT_EQ(c.rejected_out_of_range, 1u);
  EXPECT_EQ(c.rejected_stale, 1u);
  EXPECT_EQ(c.clamped, 1u);
  EXPECT_EQ(c.rejected(), 3u);
}
TEST(SampleValidator, CountsEveryClampedJointValue) {
  const auto hand = default_hand();
  SampleValidator validator(hand);
  GloveSample s;
  s.t_ns = 100;
  s.joints_rad = hand.rest_pose();
  s.joints_rad[static_cast<int>(Joint::kIndexPip)] = 10.0;
  s.joints_rad[static_cast<int>(Joint::kMiddlePip)] = -10.0;
  s.joints_rad[static_cast<int>(Joint::kRingPip)] = 10.0;
  EXPECT_TRUE(validator.accept(s));
  EXPECT_EQ(validator.counts().clamped, 3u) << "values, as node_status and the log reader count";
  EXPECT_EQ(validator.counts().accepted, 1u);
}

}  // namespace
}  // namespace vcockpit::hand
