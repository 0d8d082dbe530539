// Substeps are chosen every step from the pairs that can touch within it: a light box falling
// from high up steps whole (nothing to touch), gets its short substeps before it reaches the
// floor, lands without bouncing off and rests at m g / k_eff; a box far from it pays nothing.

#include <gtest/gtest.h>

#include <cmath>

#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"

namespace vcockpit::test {
namespace {

TEST(SubstepChoice, FallingLightBoxGetsItsSubstepsBeforeItLandsAndRests) {
  const double k_Npm = 1e5;  // floor and box: k_eff = 5e4
  const double mass_kg = 0.02;
  physics::Scene scene;
  scene.objects.push_back(floor_box(material(k_Npm)));
  scene.objects.push_back(dynamic_object("light", physics::Shape::box({0.03, 0.03, 0.03}), mass_kg,
                                         at(0, 0, 0.3, 10, 20, 30), material(k_Npm)));
  physics::World world(scene);

  int first_substeps = 0, most_substeps = 0, substeps_at_first_contact = 0;
  double top_after_landing_m = 0.0;
  bool landed = false;
  for (int i = 0; i < 2000; ++i) {
    world.step();
    if (i == 0) first_substeps = world.substeps();
    most_substeps = std::max(most_substeps, world.substeps());
    const double z = world.bodies()[1].X_GO.translation().z();
    if (!landed && !world.contacts().empty()) {
      landed = true;
      substeps_at_first_contact = world.substeps();
    }
    if (landed) top_after_landing_m = std::max(top_after_landing_m, z);
  }
  EXPECT_EQ(first_substeps, 1);  // 0.28 m above the floor: nothing within reach
  ASSERT_TRUE(landed);
  EXPECT_EQ(substeps_at_first_contact, most_substeps);  // the full count before the first touch
  EXPECT_GT(most_substeps, 8);
  // no launch (too few substeps threw it metres up): at most a tumble and a small rebound
  EXPECT_LT(top_after_landing_m, 0.05);

  const auto& box = world.bodies()[1];
  EXPECT_LT(box.v_G.norm(), 1e-3);
  EXPECT_LT(box.w_G.norm(), 1e-2);
  // on a face: the centroid 1.5 cm up, less the resting depth m g / k_eff
  EXPECT_NEAR(box.X_GO.translation().z(), 0.015 - mass_kg * 9.81 / (k_Npm / 2), 2e-5);
}

TEST(SubstepChoice, ABoxOutOfReachDoesNotSetTheCount) {
  // a heavy box resting alone, and the same with a light box falling far away from it
  physics::Scene alone;
  alone.objects.push_back(floor_box(material(1e5)));
  alone.objects.push_back(dynamic_object("heavy", physics::Shape::box({0.2, 0.2, 0.2}), 5.0,
                                         at(0, 0, 0.1), material(1e5)));
  physics::Scene with_light = alone;
  with_light.objects.push_back(dynamic_object("light", physics::Shape::box({0.03, 0.03, 0.03}),
                                              0.02, at(1.0, 1.0, 1.5), material(1e5)));
  physics::World a(alone), b(with_light);
  for (int i = 0; i < 50; ++i) {
    a.step();
    b.step();
    ASSERT_EQ(a.substeps(), b.substeps()) << "step " << i;
  }
}

}  // namespace
}  // namespace vcockpit::test
