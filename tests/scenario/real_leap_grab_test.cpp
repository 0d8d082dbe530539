// A real hand recording (tests/data/real/README.md: a Leap Motion "grab", Apache-2.0) replayed
// offline on its scene, a 60 g bar on a pedestal where the recorded fist closes. The recorded
// thumb reaches 18 mm into the table and the pedestal, the fingers close 4 cm past the bar, and
// the ring finger wraps the bar at 104-111 deg from the thumb. What a user expects of it: the bar
// is taken as the fist closes, held while the fist stays closed (until about 0.75 s), let go
// because the hand opened, and left where it was, on the pedestal:
//   - GRASP by 0.30 s; the first RELEASE between 0.70 and 1.00 s, for the hand opening;
//   - until 0.3 s after that release the bar never more than 1 cm below the pedestal's top (not
//     asserted; the figure is printed). The recorded hand itself carries the bar off the 1.8 cm
//     pedestal: the closing fist pushes it 5-6 mm across before the grasp, and from the grasp
//     the closed hand moves it 12-14 mm more (wrist frame 14.2 mm, rigid fit of the hand's links
//     11.9 mm, at 0.685 s, before the fingers open at all), then 30 mm by 0.74 s, while they
//     have opened 4 deg from their tightest. Nearly all of it is across the bar, the pedestal's
//     narrow way (the links' fit in the bar's frame: 14.5 mm across at 0.703 s, 32.7 mm at
//     0.746 s; 2.4 and 8.9 mm along):
//       build/bin/grip_drift --scene tests/data/real/leap_grab_scene.yaml
//         --log tests/data/real/leap_grab.csv --object bar --from 0.178
//     A 9 mm half-width is less than any rule that follows the hand moves it;
//   - a free bar (before the grasp, after the release) never faster than 0.5 m/s horizontally;
//   - no link more than 1 mm inside the bar or any static object, at any step.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "tests/scenario/real_grip/real_grip_run.hpp"

namespace vcockpit {
namespace {

std::string source_dir() { return std::getenv("VCOCKPIT_SOURCE_DIR"); }

TEST(RealLeapGrab, TheClosedFistHoldsTheBarUntilItOpensAndLeavesItOnThePedestal) {
  const real_grip::RealGripRun run = real_grip::replay_real_grip(
      source_dir() + "/tests/data/real/leap_grab_scene.yaml",
      source_dir() + "/tests/data/real/leap_grab.csv", "bar", "pedestal");
  std::printf("%sdeepest below the pedestal top %.1f mm (at %.3f s), fastest free %.3f m/s (at %.3f s), "
              "deepest link in the bar %.2f mm, in a static object %.2f mm\n",
              run.events.c_str(), run.deepest_below_support_m * 1e3, run.deepest_below_support_at_s,
              run.fastest_free_horizontal_mps,
              run.fastest_free_at_s, run.deepest_link_in_object_m * 1e3,
              run.deepest_link_in_static_m * 1e3);
  ASSERT_GE(run.grasp_s, 0.0) << "the closing fist never grasped the bar";
  EXPECT_LE(run.grasp_s, 0.30);
  ASSERT_GE(run.release_s, 0.0) << "never let go";
  EXPECT_GE(run.release_s, 0.70) << run.events;
  EXPECT_LE(run.release_s, 1.00) << run.events;
  // the hand opening: its thumb leaves the bar as the fist opens from its tightest grip
  EXPECT_EQ(run.release_reason, physics::GraspReason::kHandOpened)
      << physics::grasp_reason_name(run.release_reason);
  EXPECT_EQ(run.grasps, 1) << run.events;
  EXPECT_LE(run.fastest_free_horizontal_mps, 0.5);
  EXPECT_LE(run.deepest_link_in_object_m, 1e-3);
  EXPECT_LE(run.deepest_link_in_static_m, 1e-3);
}

}  // namespace
}  // namespace vcockpit
