// On the penalty path (contact.solver: penalty), substeps are chosen every step from the pairs
// that can touch within it: a light box falling from high up steps whole (nothing to touch), gets
// its short substeps before it reaches the floor, lands without bouncing off and rests at
// m g / k_eff; a box far from it pays nothing. On the soft constraints (the default) the same box
// lands and rests the same at the full step.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"

namespace vcockpit::test {
namespace {

struct LightBoxDrop {
  int first_substeps = 0, most_substeps = 0, substeps_at_first_contact = 0;
  bool landed = false;
  double top_after_landing_m = 0.0;
  physics::BodyState rest;
};

constexpr double kLightBoxK_Npm = 1e5;  // floor and box: k_eff = 5e4
constexpr double kLightBoxMass_kg = 0.02;

LightBoxDrop drop_a_light_box(physics::ContactSolver solver) {
  physics::Scene scene;
  scene.contact.solver = solver;
  scene.objects.push_back(floor_box(material(kLightBoxK_Npm)));
  scene.objects.push_back(dynamic_object("light", physics::Shape::box({0.03, 0.03, 0.03}), kLightBoxMass_kg,
                                         at(0, 0, 0.3, 10, 20, 30), material(kLightBoxK_Npm)));
  physics::World world(scene);
  LightBoxDrop out;
  for (int i = 0; i < 2000; ++i) {
    world.step();
    if (i == 0) out.first_substeps = world.substeps();
    out.most_substeps = std::max(out.most_substeps, world.substeps());
    const double z = world.bodies()[1].X_GO.translation().z();
    if (!out.landed && !world.contacts().empty()) {
      out.landed = true;
      out.substeps_at_first_contact = world.substeps();
    }
    if (out.landed) out.top_after_landing_m = std::max(out.top_after_landing_m, z);
  }
  out.rest = world.bodies()[1];
  return out;
}

void expect_landed_without_launch_and_at_rest(const LightBoxDrop& drop) {
  ASSERT_TRUE(drop.landed);
  // no launch (too few substeps threw it metres up): at most a tumble and a small rebound
  EXPECT_LT(drop.top_after_landing_m, 0.05);
  EXPECT_LT(drop.rest.v_G.norm(), 1e-3);
  EXPECT_LT(drop.rest.w_G.norm(), 1e-2);
  // on a face: the centroid 1.5 cm up, less the resting depth m g / k_eff
  EXPECT_NEAR(drop.rest.X_GO.translation().z(), 0.015 - kLightBoxMass_kg * 9.81 / (kLightBoxK_Npm / 2), 2e-5);
}

TEST(SubstepChoice, FallingLightBoxGetsItsSubstepsBeforeItLandsAndRests) {
  const LightBoxDrop drop = drop_a_light_box(physics::ContactSolver::kPenalty);
  EXPECT_EQ(drop.first_substeps, 1);  // 0.28 m above the floor: nothing within reach
  EXPECT_EQ(drop.substeps_at_first_contact, drop.most_substeps);  // the full count before the first touch
  EXPECT_GT(drop.most_substeps, 8);
  expect_landed_without_launch_and_at_rest(drop);
}

TEST(SubstepChoice, OnSoftContactsTheLightBoxLandsAndRestsAtTheFullStep) {
  const LightBoxDrop drop = drop_a_light_box(physics::ContactSolver::kSoft);
  EXPECT_EQ(drop.most_substeps, 1);
  expect_landed_without_launch_and_at_rest(drop);
}

TEST(SubstepChoice, ABoxOutOfReachDoesNotSetTheCount) {
  // a heavy box resting alone, and the same with a light box falling far away from it
  physics::Scene alone;
  alone.contact.solver = physics::ContactSolver::kPenalty;  // (soft: always one)
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
