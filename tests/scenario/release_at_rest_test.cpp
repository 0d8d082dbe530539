// What a let-go object does (issue: release at rest). The cockpit's cup, gripped by the scripted
// hand of config/gestures/cup_pick_place.yaml:
//   - set down on the console and let go by a still hand, it comes to rest where it was set down
//     (the scripted hand lets it go 9 mm above the console: it drops and rests within 1 cm);
//   - let go in mid-air by a still hand opening (tests/data/gestures/cup_let_go_mid_air.yaml), it
//     falls straight down onto the console, not thrown by the opening fingers, and rests there.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "glove_driver/glove/gesture_script.hpp"
#include "hand/sample_validator.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/replay_driver.hpp"

namespace vcockpit {
namespace {

std::string source_dir() { return std::getenv("VCOCKPIT_SOURCE_DIR"); }

struct LetGo {
  double release_s = -1.0;
  physics::GraspReason reason = physics::GraspReason::kStableGrasp;
  Eigen::Vector3d at_release_G = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_G = Eigen::Vector3d::Zero();
  // from the release until it first touches anything but the hand (its fall)
  double fastest_horizontal_falling_mps = 0.0;
  bool landed = false;
  double end_speed_mps = 0.0;
  double end_tilt_deg = 0.0;  // the cup's axis from the vertical
  int grasps = 0;
};

LetGo replay_cup(const std::string& script) {
  physics::World world(load_scene(source_dir() + "/config/cockpit.yaml"));
  const hand::HandModel& hand = world.scene().hands.at(0);
  const int cup = world.scene().find_object("cup");
  physics_io::ReplayDriver driver(world, hand);
  LetGo out;
  const auto step = [&] {
    world.step();
    const physics::BodyState& body = world.bodies()[static_cast<std::size_t>(cup)];
    for (const auto& e : world.step_events()) {
      if (e.object != cup) continue;
      if (e.grasp) ++out.grasps;
      if (!e.grasp && out.release_s < 0.0) {
        out.release_s = static_cast<double>(world.time_ns()) * 1e-9;
        out.reason = e.reason;
        out.at_release_G = body.X_GO.translation();
      }
    }
    if (out.release_s >= 0.0 && !out.landed) {
      const int objects = static_cast<int>(world.scene().objects.size());
      for (const auto& a : world.contacts()) {
        const bool cup_pair = a.contact.body_a == cup || a.contact.body_b == cup;
        const int other = a.contact.body_a == cup ? a.contact.body_b : a.contact.body_a;
        if (cup_pair && other < objects) out.landed = true;
      }
      if (!out.landed)
        out.fastest_horizontal_falling_mps =
            std::max(out.fastest_horizontal_falling_mps, body.v_G.head<2>().norm());
    }
  };
  hand::SampleValidator validator(hand);
  for (hand::GloveSample sample : glove::script_samples(script, hand))
    if (validator.accept(sample)) driver.feed(sample, step);
  for (int i = 0; i < 1000; ++i) step();  // a second more, the hand where it ended
  const physics::BodyState& body = world.bodies()[static_cast<std::size_t>(cup)];
  out.end_G = body.X_GO.translation();
  out.end_speed_mps = body.v_G.norm();
  out.end_tilt_deg = std::acos(std::clamp(body.X_GO.linear().col(2).z(), -1.0, 1.0)) * 180.0 / M_PI;
  std::printf("release %.3f s (%s) at (%.4f, %.4f, %.4f); end (%.4f, %.4f, %.4f) at %.4f m/s, tilt "
              "%.1f deg; fastest horizontal while falling %.3f m/s\n",
              out.release_s, physics::grasp_reason_name(out.reason), out.at_release_G.x(),
              out.at_release_G.y(), out.at_release_G.z(), out.end_G.x(), out.end_G.y(), out.end_G.z(),
              out.end_speed_mps, out.end_tilt_deg, out.fastest_horizontal_falling_mps);
  return out;
}

bool let_go_by_the_hand(physics::GraspReason r) {
  return r == physics::GraspReason::kHandOpened || r == physics::GraspReason::kThumbLeft ||
         r == physics::GraspReason::kFingersLeft;
}

TEST(ReleaseAtRest, ACupSetDownByAStillHandStaysWhereItWasSetDown) {
  const LetGo run = replay_cup(source_dir() + "/config/gestures/cup_pick_place.yaml");
  ASSERT_EQ(run.grasps, 1);
  ASSERT_GE(run.release_s, 0.0);
  EXPECT_TRUE(let_go_by_the_hand(run.reason)) << physics::grasp_reason_name(run.reason);
  EXPECT_LT(run.fastest_horizontal_falling_mps, 0.05) << "pushed by the opening fingers";
  // (it is let go a few mm above the console and lands with a small bounce: within 1 cm)
  EXPECT_LT((run.end_G - run.at_release_G).head<2>().norm(), 0.01);
  EXPECT_LT(std::abs(run.end_G.z() - run.at_release_G.z()), 0.01);
  EXPECT_LT(run.end_speed_mps, 0.01);
  EXPECT_LT(run.end_tilt_deg, 2.0);
}

TEST(ReleaseAtRest, ACupLetGoInMidAirFallsStraightDownAndRests) {
  const LetGo run = replay_cup(source_dir() + "/tests/data/gestures/cup_let_go_mid_air.yaml");
  ASSERT_EQ(run.grasps, 1);
  ASSERT_GE(run.release_s, 0.0);
  EXPECT_TRUE(let_go_by_the_hand(run.reason)) << physics::grasp_reason_name(run.reason);
  EXPECT_GT(run.release_s, 5.0) << "let go while the hand was still lifting it";
  EXPECT_GT(run.at_release_G.z() - run.end_G.z(), 0.08) << "it fell to the console";
  EXPECT_LT(run.fastest_horizontal_falling_mps, 0.05) << "thrown by the opening fingers";
  // landing from 10 cm at 1.4 m/s it bounces 1-2 cm (the contact model's, not the release's)
  EXPECT_LT((run.end_G - run.at_release_G).head<2>().norm(), 0.025);
  EXPECT_LT(run.end_speed_mps, 0.01);
  EXPECT_LT(run.end_tilt_deg, 5.0);
}

}  // namespace
}  // namespace vcockpit
