// A calibrated hand written as hand.yaml loads back as that hand, for either side, and keeps the
// source's other settings.

#include <gtest/gtest.h>

#include <cstdlib>

#include "hand/config/calibrated_hand_yaml.hpp"
#include "hand/config/hand_yaml.hpp"
#include "tests/support/process.hpp"

namespace vcockpit {
namespace {

std::string source_dir() { return std::getenv("VCOCKPIT_SOURCE_DIR"); }

TEST(CalibratedHandYaml, TheWrittenFileLoadsAsTheCalibratedHandOnEitherSide) {
  const std::string source = source_dir() + "/config/hand.yaml";
  const hand::HandModel right = load_hand_model(source);
  for (const bool left : {false, true}) {
    SCOPED_TRACE(left ? "left" : "right");
    hand::HandModel hand = right;
    hand.p_H_palm_joint += Eigen::Vector3d(0.020, -0.001, 0.002);
    hand.p_H_wrist_joint = Eigen::Vector3d(-0.01, 0.003, -0.012);
    for (auto& chain : hand.fingers) {
      chain.X_HB.translation() *= 1.1;
      for (auto& row : chain.rows) row.a_m *= 1.12;
    }
    if (left) hand = hand::mirrored(hand);
    const std::string path = test::make_temp_dir("calibrated_hand_yaml") + "/hand.yaml";
    write_calibrated_hand_yaml(source, hand, path, {"calibrated in a test"});
    const hand::HandModel back = load_hand_model(path);
    EXPECT_EQ(back.left, left);
    EXPECT_LT((back.p_H_palm_joint - hand.p_H_palm_joint).norm(), 1e-8);
    EXPECT_LT((back.p_H_wrist_joint - hand.p_H_wrist_joint).norm(), 1e-8);
    EXPECT_LT((back.X_HP.translation() - hand.X_HP.translation()).norm(), 1e-12) << "the box stays";
    for (int f = 0; f < hand::kFingerCount; ++f) {
      const auto& a = hand.fingers[static_cast<std::size_t>(f)];
      const auto& b = back.fingers[static_cast<std::size_t>(f)];
      EXPECT_LT((a.X_HB.translation() - b.X_HB.translation()).norm(), 1e-8) << f;
      ASSERT_EQ(a.rows.size(), b.rows.size());
      for (std::size_t i = 0; i < a.rows.size(); ++i) EXPECT_NEAR(a.rows[i].a_m, b.rows[i].a_m, 1e-9);
    }
    for (int l = 1; l < hand::kLinkCount; ++l)
      EXPECT_NEAR(back.capsules[static_cast<std::size_t>(l)].length_m,
                  right.capsules[static_cast<std::size_t>(l)].length_m * 1.12, 1e-9);
    for (int j = 0; j < hand::kJointCount; ++j)
      EXPECT_EQ(back.joints[static_cast<std::size_t>(j)].max_rad, right.joints[static_cast<std::size_t>(j)].max_rad);
  }
}

}  // namespace
}  // namespace vcockpit
