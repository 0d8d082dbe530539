// The default cockpit is closed: the ball knocked or thrown in any direction comes to rest
// inside the shell, on the pilot's side of the front bulkhead (within reach), and the shell
// keeps out of the bundled gestures' way.

#include <gtest/gtest.h>

#include <string>

#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "physics_node/physics/broadphase.hpp"
#include "physics_node/physics/world.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::test {
namespace {

physics::Scene cockpit() { return load_scene(source_dir() + "/config/cockpit.yaml"); }

physics::Aabb box_of(const physics::Scene& scene, const std::string& name) {
  const int i = scene.find_object(name);
  EXPECT_GE(i, 0) << name;
  const physics::ObjectSpec& o = scene.objects.at(static_cast<std::size_t>(std::max(i, 0)));
  return physics::shape_aabb(o.shape, o.X_GO);
}

// The space the shell's inner faces enclose.
struct Inside {
  Eigen::Vector3d lo, hi;
  double bulkhead_x;  // the face of the bulkhead below the panel: the pilot's side is x below it
};

Inside inside_of(const physics::Scene& scene) {
  Inside in;
  in.lo = {box_of(scene, "back_wall").hi.x(), box_of(scene, "right_wall").hi.y(),
           box_of(scene, "floor").hi.z()};
  in.hi = {box_of(scene, "nose_bulkhead").lo.x(), box_of(scene, "left_wall").lo.y(),
           box_of(scene, "canopy").lo.z()};
  in.bulkhead_x = box_of(scene, "front_bulkhead").lo.x();
  return in;
}

struct Throw {
  const char* what;
  Eigen::Vector3d v_mps;
  Eigen::Vector3d w_radps;
};

TEST(CockpitShell, TheBallComesToRestInsideWithinReachWhereverItIsSent) {
  const physics::Scene scene = cockpit();
  const Inside in = inside_of(scene);
  EXPECT_LT(in.lo.x(), 0.0) << "the back wall is behind the pilot";
  const int ball = scene.find_object("ball");
  ASSERT_GE(ball, 0);
  const double r_m = scene.objects[static_cast<std::size_t>(ball)].shape.radius_m;
  const std::vector<Throw> throws = {
      {"rolled forward off the console", {1.0, 0.0, 0.0}, {0.0, 1.0 / r_m, 0.0}},
      {"rolled right against the wall", {0.0, -1.0, 0.0}, {1.0 / r_m, 0.0, 0.0}},
      {"thrown back over the pilot", {-4.0, 1.0, 3.0}, {0.0, 0.0, 0.0}},
      {"thrown up at the windscreen", {3.0, 1.5, 4.0}, {0.0, 0.0, 0.0}},
      {"thrown left at the window", {0.5, 5.0, 2.5}, {0.0, 0.0, 20.0}},
  };
  for (const Throw& t : throws) {
    SCOPED_TRACE(t.what);
    physics::Scene s = scene;
    s.objects[static_cast<std::size_t>(ball)].v_G = t.v_mps;
    s.objects[static_cast<std::size_t>(ball)].w_G = t.w_radps;
    physics::World world(s);
    bool left = false;
    int still_steps = 0;  // at rest for this many steps in a row: 1 s of it ends the run
    for (int k = 0; k < 20'000 && !left && still_steps < 1000; ++k) {  // 20 s at most
      world.step();
      const physics::BodyState& b = world.bodies()[static_cast<std::size_t>(ball)];
      const Eigen::Vector3d p = b.X_GO.translation();
      left = (p.array() < in.lo.array()).any() || (p.array() > in.hi.array()).any();
      still_steps = b.v_G.norm() < 1e-4 && b.w_G.norm() < 1e-2 ? still_steps + 1 : 0;
    }
    const physics::BodyState& b = world.bodies()[static_cast<std::size_t>(ball)];
    const Eigen::Vector3d p = b.X_GO.translation();
    ASSERT_FALSE(left) << "left the shell at " << p.transpose();
    EXPECT_TRUE(world.body_faults().empty());
    EXPECT_LT(p.x(), in.bulkhead_x - r_m + 1e-3) << "on the pilot's side of the bulkhead";
    EXPECT_LT(b.v_G.norm(), 1e-3) << "at rest at " << p.transpose();
    EXPECT_LT(b.w_G.norm(), 0.05) << "at rest at " << p.transpose();
  }
}

// No hand link touches the shell (or anything static) in the bundled gestures: the shell was
// built round the hand's paths.
TEST(CockpitShell, TheBundledGesturesKeepClearOfTheShell) {
  for (const char* log_name : {"reach_grasp_lift_release.csv", "open_hand_sweep.csv"}) {
    SCOPED_TRACE(log_name);
    physics::World world(cockpit());
    const hand::HandModel& hand = world.scene().hands[0];
    const auto log =
        hand::read_glove_log(source_dir() + "/config/glove_logs/" + log_name, hand);
    physics_io::ReplayDriver driver(world, hand);
    const int objects = static_cast<int>(world.scene().objects.size());
    int touches = 0;
    auto step = [&] {
      world.step();
      for (const physics::AppliedContact& c : world.contacts()) {
        const bool hand_pair = c.contact.body_b >= objects;
        if (hand_pair && !world.scene().objects[static_cast<std::size_t>(c.contact.body_a)].dynamic) {
          if (touches++ == 0)
            ADD_FAILURE() << "the hand touches "
                          << world.scene().objects[static_cast<std::size_t>(c.contact.body_a)].name
                          << " at " << world.time_ns() * 1e-9 << " s";
        }
      }
    };
    for (const auto& sample : log.samples) driver.feed(sample, step);
    EXPECT_EQ(touches, 0);
  }
}

}  // namespace
}  // namespace vcockpit::test
