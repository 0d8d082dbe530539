// KinematicsMemo: every answer is forward_kinematics' to the bit, whether computed, kept or
// remembered; only the same angles bit for bit are a repeat; the oldest answer goes first.

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>

#include "hand/config/hand_yaml.hpp"
#include "hand/kinematics_memo.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::hand {
namespace {

const HandModel& shipped_hand() {
  static const HandModel model = load_hand_model(test::source_dir() + "/config/hand.yaml");
  return model;
}

JointAngles random_angles(std::mt19937& rng) {
  JointAngles q{};
  for (int j = 0; j < kJointCount; ++j) {
    const JointRange& r = shipped_hand().joints[static_cast<std::size_t>(j)];
    q[static_cast<std::size_t>(j)] = std::uniform_real_distribution<double>(r.min_rad, r.max_rad)(rng);
  }
  return q;
}

bool same_bits(const HandLinkPoses& a, const HandLinkPoses& b) {
  for (int l = 0; l < kLinkCount; ++l)
    if (std::memcmp(a.X_HL[static_cast<std::size_t>(l)].data(), b.X_HL[static_cast<std::size_t>(l)].data(),
                    sizeof(double) * 16) != 0)
      return false;
  for (int f = 0; f < kFingerCount; ++f)
    if (std::memcmp(a.p_H_tip[static_cast<std::size_t>(f)].data(), b.p_H_tip[static_cast<std::size_t>(f)].data(),
                    sizeof(double) * 3) != 0)
      return false;
  return true;
}

HandLinkPoses direct(const JointAngles& q) {
  HandLinkPoses links;
  forward_kinematics(shipped_hand(), q, links);
  return links;
}

TEST(KinematicsMemo, ARepeatIsAHitAndTheSameBitsAsForwardKinematics) {
  std::mt19937 rng(11);
  KinematicsMemo memo(shipped_hand());
  const JointAngles a = random_angles(rng);
  const JointAngles b = random_angles(rng);
  HandLinkPoses out;
  memo.solve(a, out);
  EXPECT_TRUE(same_bits(out, direct(a)));
  memo.solve(b, out);
  EXPECT_TRUE(same_bits(out, direct(b)));
  EXPECT_EQ(memo.misses(), 2u);
  memo.solve(a, out);
  EXPECT_TRUE(same_bits(out, direct(a)));
  memo.solve(b, out);
  EXPECT_TRUE(same_bits(out, direct(b)));
  EXPECT_EQ(memo.hits(), 2u);
  EXPECT_EQ(memo.misses(), 2u);
}

TEST(KinematicsMemo, AnglesThatDifferInTheLastBitAreNotARepeat) {
  std::mt19937 rng(12);
  KinematicsMemo memo(shipped_hand());
  const JointAngles a = random_angles(rng);
  JointAngles nudged = a;
  nudged[3] = std::nextafter(nudged[3], 10.0);
  HandLinkPoses out;
  memo.solve(a, out);
  memo.solve(nudged, out);
  EXPECT_EQ(memo.misses(), 2u);
  EXPECT_TRUE(same_bits(out, direct(nudged)));
  // and -0 is not +0 (its sine keeps the sign)
  JointAngles zero{};
  JointAngles negative_zero{};
  negative_zero[5] = -0.0;
  memo.solve(zero, out);
  memo.solve(negative_zero, out);
  EXPECT_EQ(memo.misses(), 4u);
  EXPECT_TRUE(same_bits(out, direct(negative_zero)));
}

TEST(KinematicsMemo, TheOldestAnswerGoesFirstAndARememberedOneIsKept) {
  std::mt19937 rng(13);
  KinematicsMemo memo(shipped_hand());
  std::vector<JointAngles> q;
  for (int i = 0; i < 5; ++i) q.push_back(random_angles(rng));
  HandLinkPoses out;
  for (int i = 0; i < 5; ++i) memo.solve(q[static_cast<std::size_t>(i)], out);  // q[0] is gone
  EXPECT_EQ(memo.misses(), 5u);
  for (int i = 1; i < 5; ++i) memo.solve(q[static_cast<std::size_t>(i)], out);
  EXPECT_EQ(memo.hits(), 4u);
  memo.solve(q[0], out);
  EXPECT_EQ(memo.misses(), 6u);
  EXPECT_TRUE(same_bits(out, direct(q[0])));
  // an answer found elsewhere (a proxy's moved fingers) is a hit afterwards
  const JointAngles moved = random_angles(rng);
  memo.remember(moved, direct(moved));
  memo.solve(moved, out);
  EXPECT_EQ(memo.misses(), 6u);
  EXPECT_TRUE(same_bits(out, direct(moved)));
}

}  // namespace
}  // namespace vcockpit::hand
