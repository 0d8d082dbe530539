// A light, stiff box (20 g on 1e5 N/m, k_eff 5e4: omega h = 1.6 at the 1 ms step, near the 2 where
// an explicit spring step goes unstable) dropped from 30 cm, tumbled, onto a floor: the soft
// contacts take it at the full step, one collision and one solve a step, with no launch, and it
// comes to rest on a face at m g / k_eff deep.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"

namespace vcockpit::test {
namespace {

constexpr double kLightBoxK_Npm = 1e5;  // floor and box: k_eff = 5e4
constexpr double kLightBoxMass_kg = 0.02;

TEST(LightBoxDrop, LandsWithoutLaunchAndRestsOnAFaceAtItsWeightOverTheSprings) {
  physics::Scene scene;
  scene.objects.push_back(floor_box(material(kLightBoxK_Npm)));
  scene.objects.push_back(dynamic_object("light", physics::Shape::box({0.03, 0.03, 0.03}), kLightBoxMass_kg,
                                         at(0, 0, 0.3, 10, 20, 30), material(kLightBoxK_Npm)));
  physics::World world(scene);
  bool landed = false;
  double top_after_landing_m = 0.0;
  for (int i = 0; i < 2000; ++i) {
    world.step();
    if (!landed && !world.contacts().empty()) landed = true;
    if (landed) top_after_landing_m = std::max(top_after_landing_m, world.bodies()[1].X_GO.translation().z());
  }
  const physics::BodyState& rest = world.bodies()[1];
  ASSERT_TRUE(landed);
  // no launch: at most a tumble and a small rebound
  EXPECT_LT(top_after_landing_m, 0.05);
  EXPECT_LT(rest.v_G.norm(), 1e-3);
  EXPECT_LT(rest.w_G.norm(), 1e-2);
  // on a face: the centroid 1.5 cm up, less the resting depth m g / k_eff
  EXPECT_NEAR(rest.X_GO.translation().z(), 0.015 - kLightBoxMass_kg * 9.81 / (kLightBoxK_Npm / 2), 2e-5);
}

}  // namespace
}  // namespace vcockpit::test
