// The launcher's rule for giving up on a node (launcher/restart_guard.hpp): five deaths in a row
// within 2 s of each start stop its restarts; a death after a good run, or a clean exit, starts
// the count over.

#include "launcher/restart_guard.hpp"

#include <gtest/gtest.h>

namespace vcockpit::rig {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

TEST(RestartGuard, ANodeThatDiesAtOnceEveryTimeIsGivenUpOnTheFifthDeath) {
  RestartGuard guard;
  int64_t t = 0;
  for (int death = 1; death < RestartGuard::kInARow; ++death, t += kSecond) {
    EXPECT_TRUE(guard.allows_restart(t, t + kSecond / 20, 1)) << death;
    EXPECT_EQ(guard.quick_deaths(), death);
  }
  EXPECT_FALSE(guard.allows_restart(t, t + kSecond / 20, 1));
}

TEST(RestartGuard, ADeathAfterAGoodRunStartsTheCountOver) {
  RestartGuard guard;
  for (int i = 0; i < RestartGuard::kInARow - 1; ++i) EXPECT_TRUE(guard.allows_restart(0, 1, 1));
  // killed (128 + 9) after a run of 30 s: restarted, and the count is back at 0
  EXPECT_TRUE(guard.allows_restart(0, 30 * kSecond, 137));
  EXPECT_EQ(guard.quick_deaths(), 0);
  for (int i = 0; i < RestartGuard::kInARow - 1; ++i) EXPECT_TRUE(guard.allows_restart(0, 1, 1));
  EXPECT_FALSE(guard.allows_restart(0, 1, 1));
}

TEST(RestartGuard, OnlyAFailureCountsAndOnlyWithinTwoSecondsOfTheStart) {
  RestartGuard guard;
  for (int i = 0; i < 2 * RestartGuard::kInARow; ++i) {
    EXPECT_TRUE(guard.allows_restart(0, 1, 0)) << "a clean exit is not a failure to start";
    EXPECT_TRUE(guard.allows_restart(0, RestartGuard::kSoon_ns, 1)) << "2 s: it did start";
  }
  EXPECT_EQ(guard.quick_deaths(), 0);
}

}  // namespace
}  // namespace vcockpit::rig
