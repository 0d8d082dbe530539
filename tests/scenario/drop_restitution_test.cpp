// A ball thrown down onto a floor bounces back with the restitution of the paper's contact force
// (eqs. 11-14): a spring and a dashpot in parallel, F = max(0, k d - c d'), c = 2 zeta sqrt(k m),
// which pulls never (the force ends where it would turn negative, before the spring is back at
// rest). Its coefficient of restitution depends on zeta alone, not on k or m or the speed
// (Schwager and Poeschel 2007, the clamped linear dashpot):
//   zeta < 1/sqrt(2): e = exp(-zeta / sqrt(1 - zeta^2) (pi - atan(2 zeta sqrt(1 - zeta^2) / (1 - 2 zeta^2))))
//   zeta > 1/sqrt(2): e = exp(-zeta / sqrt(1 - zeta^2) atan(2 zeta sqrt(1 - zeta^2) / (2 zeta^2 - 1)))
// Without gravity (so nothing but the contact acts), for three damping ratios, two stiffnesses,
// two speeds and four moments of first touch within a step, the speed it leaves with over the
// speed it came in at converges on e as the substeps shrink, at first order (semi-implicit
// Euler's error in omega dt, and the depth it is already at when a substep first finds it):
//   - at the default substep (contact.substep_safety 0.2: omega dt = 0.2) within 25 % of e (on
//     average within 5 %), the error's sign and size set by when in a substep it first touches:
//     5 % at worst for zeta 0.3, 15 % for 0.7, 22.5 % for 0.9 (printed);
//   - at a quarter of it, within 6 %, and at most half the default's worst error.
// This is the penalty path's convergence (contact.solver: penalty); the soft constraints, the
// default, meet e at the full step (soft_contact_test.cpp).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"

namespace vcockpit::test {
namespace {

double dashpot_restitution(double zeta) {
  const double s = std::sqrt(1.0 - zeta * zeta);
  const double phase = zeta < 1.0 / std::sqrt(2.0)
                           ? M_PI - std::atan(2.0 * zeta * s / (1.0 - 2.0 * zeta * zeta))
                           : std::atan(2.0 * zeta * s / (2.0 * zeta * zeta - 1.0));
  return std::exp(-zeta / s * phase);
}

// The ball's upward speed once it has left the floor, over its downward speed before it touched.
double rebound_ratio(double zeta, double k_Npm, double speed_mps, double gap_m, double safety) {
  physics::Scene scene;
  scene.step_s = 0.001;
  scene.contact.solver = physics::ContactSolver::kPenalty;  // (soft: soft_contact_test.cpp)
  scene.gravity_mps2 = Eigen::Vector3d::Zero();
  scene.sleep.enabled = false;
  scene.contact.substep_safety = safety;
  scene.contact.max_substeps = 128;
  scene.objects.push_back(floor_box(material(k_Npm, 0.6, 0.4, zeta)));
  physics::ObjectSpec ball =
      dynamic_object("ball", physics::Shape::sphere(0.03), 0.1, at(0, 0, 0.03 + gap_m), material(k_Npm, 0.6, 0.4, zeta));
  ball.v_G = Eigen::Vector3d(0, 0, -speed_mps);
  scene.objects.push_back(ball);
  physics::World world(scene);
  for (int i = 0; i < 2000; ++i) {
    world.step();
    const physics::BodyState& b = world.bodies()[1];
    // left the floor: above it and moving up, with no contact
    if (b.v_G.z() > 0.0 && b.X_GO.translation().z() > 0.03 + 0.002 && world.contacts().empty())
      return b.v_G.z() / speed_mps;
  }
  return -1.0;  // never came back
}

TEST(DropRestitution, TheReboundSpeedConvergesOnTheDashpotsRestitution) {
  for (const double zeta : {0.3, 0.7, 0.9}) {
    const double e = dashpot_restitution(zeta);
    for (const double k_Npm : {3.0e4, 1.0e5}) {
      double worst_coarse = 0.0, worst_fine = 0.0, sum_coarse = 0.0;
      int runs = 0;
      for (const double speed_mps : {1.0, 3.0}) {
        for (const double gap_m : {0.010, 0.0102, 0.0105, 0.0108}) {
          const double coarse = rebound_ratio(zeta, k_Npm, speed_mps, gap_m, 0.2) / e - 1.0;
          const double fine = rebound_ratio(zeta, k_Npm, speed_mps, gap_m, 0.05) / e - 1.0;
          worst_coarse = std::max(worst_coarse, std::abs(coarse));
          worst_fine = std::max(worst_fine, std::abs(fine));
          sum_coarse += coarse;
          ++runs;
        }
      }
      std::printf("zeta %.1f k %.0e N/m: e %.4f; out/in off it by at most %.1f %% at the default "
                  "substep (mean %+.1f %%), %.1f %% at a quarter of it\n",
                  zeta, k_Npm, e, 100 * worst_coarse, 100 * sum_coarse / runs, 100 * worst_fine);
      const std::string what = "zeta " + std::to_string(zeta) + ", k " + std::to_string(k_Npm);
      EXPECT_LT(worst_coarse, 0.25) << what;
      EXPECT_LT(std::abs(sum_coarse / runs), 0.05) << what << ": on average";
      EXPECT_LT(worst_fine, 0.06) << what;
      EXPECT_LT(worst_fine, worst_coarse / 2.0) << what << ": first order in the substep";
    }
  }
}

}  // namespace
}  // namespace vcockpit::test
