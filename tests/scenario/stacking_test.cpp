// A box dropped on another box comes to rest on it: dynamic-dynamic contacts act.

#include <gtest/gtest.h>

#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"

namespace vcockpit::test {
namespace {

TEST(Stacking, BoxDroppedOnABoxComesToRestOnIt) {
  physics::Scene scene;
  scene.objects.push_back(floor_box(material(1e5)));
  scene.objects.push_back(dynamic_object("lower", physics::Shape::box({0.2, 0.2, 0.1}), 2.0,
                                         at(0, 0, 0.05), material(5e4)));
  scene.objects.push_back(dynamic_object("upper", physics::Shape::box({0.1, 0.1, 0.1}), 0.5,
                                         at(0.02, -0.01, 0.2, 0, 0, 20), material(5e4)));
  physics::World world(scene);
  for (int i = 0; i < 4000; ++i) world.step();

  const auto& lower = world.bodies()[1];
  const auto& upper = world.bodies()[2];
  // resting heights: lower on the floor (2.5 kg above it), upper on the lower box
  const double lower_depth_m = 2.5 * 9.81 / (1e5 * 5e4 / 1.5e5);
  const double upper_depth_m = 0.5 * 9.81 / (5e4 / 2);
  EXPECT_NEAR(lower.X_GO.translation().z(), 0.05 - lower_depth_m, 2e-4);
  EXPECT_NEAR(upper.X_GO.translation().z(), lower.X_GO.translation().z() + 0.1 - upper_depth_m,
              2e-4);
  EXPECT_NEAR(upper.X_GO.translation().x(), 0.02, 5e-3);  // landed where it fell, did not slide off
  EXPECT_LT(upper.v_G.norm(), 1e-3);
  EXPECT_LT(upper.w_G.norm(), 1e-2);
  EXPECT_GT(upper.X_GO.linear()(2, 2), 0.9999);  // flat on the lower box
}

}  // namespace
}  // namespace vcockpit::test
