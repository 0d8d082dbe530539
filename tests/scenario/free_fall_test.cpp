// A sphere falling freely for 1 s stays within the semi-implicit Euler bound of g t^2 / 2.

#include <gtest/gtest.h>

#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"

namespace vcockpit::test {
namespace {

TEST(FreeFall, SphereFollowsBallisticPathWithinTheSemiImplicitEulerBound) {
  physics::Scene scene;
  scene.step_s = 0.001;
  const double z0_m = 10.0;
  scene.objects.push_back(
      dynamic_object("ball", physics::Shape::sphere(0.05), 0.5, at(0, 0, z0_m), material(1e5)));
  physics::World world(scene);
  for (int i = 0; i < 1000; ++i) world.step();

  const double g = 9.81, t = 1.0, dt = scene.step_s;
  const double z = world.bodies()[0].X_GO.translation().z();
  const double exact_m = z0_m - 0.5 * g * t * t;
  // semi-implicit Euler: z_n = z0 - g dt^2 n (n + 1) / 2 = exact - g dt t / 2
  const double bound_m = 0.5 * g * dt * t;
  EXPECT_LE(std::abs(z - exact_m), bound_m + 1e-9) << "z = " << z;
  EXPECT_NEAR(z, exact_m - bound_m, 1e-9);  // and it is exactly the discrete solution
  EXPECT_NEAR(world.bodies()[0].v_G.z(), -g * t, 1e-9);
  EXPECT_EQ(world.bodies()[0].X_GO.translation().x(), 0.0);
  EXPECT_EQ(world.time_ns(), 1'000'000'000);
}

}  // namespace
}  // namespace vcockpit::test
