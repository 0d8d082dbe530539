// The MuJoCo twin of a scene (bench/mujoco_scene.hpp): the cockpit compiles with our counts and
// masses, resting objects stay put, states and poses round-trip (MuJoCo's quaternion order and
// free-joint velocity frames), the hand's geoms sit exactly where our collision geometry does,
// and the crowded cockpit (500 loose objects) steps. Also prints, without asserting, what MuJoCo
// does with the cup when started from our holding state.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "bench/bench_scenes.hpp"
#include "bench/mujoco_scene.hpp"
#include "common/pose.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::bench {
namespace {

using hand::kLinkCount;

int dynamic_count(const physics::Scene& scene) {
  return static_cast<int>(std::count_if(scene.objects.begin(), scene.objects.end(),
                                        [](const physics::ObjectSpec& o) { return o.dynamic; }));
}

std::vector<physics::BodyState> initial_states(const physics::Scene& scene) {
  std::vector<physics::BodyState> states(scene.objects.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    states[i].X_GO = scene.objects[i].X_GO;
    states[i].v_G = scene.objects[i].v_G;
    states[i].w_G = scene.objects[i].w_G;
  }
  return states;
}

Eigen::Vector3d vec3(const mjtNum* p) { return {p[0], p[1], p[2]}; }
Eigen::Matrix3d mat3(const mjtNum* p) {  // MuJoCo's 3x3 matrices are row-major
  Eigen::Matrix3d R;
  R << p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8];
  return R;
}

bool pair_can_collide(const mjModel* m, int g1, int g2) {
  return (m->geom_contype[g1] & m->geom_conaffinity[g2]) ||
         (m->geom_contype[g2] & m->geom_conaffinity[g1]);
}

// Our world stepped to the moment the bundled log holds the cup (4 s of steps): once.
struct Held {
  std::unique_ptr<physics::World> world;
  physics::HandInput hand;
};
const Held& held_cockpit() {
  static const Held held = [] {
    Held h;
    h.world = std::make_unique<physics::World>(cockpit_scene());
    h.hand = step_to_hold(*h.world);
    return h;
  }();
  return held;
}

TEST(MujocoScene, CockpitCompilesWithOurCountsAndMasses) {
  const physics::Scene scene = cockpit_scene();
  MujocoWorld mj(scene);
  const mjModel* m = mj.model();
  const int dynamic = dynamic_count(scene);
  ASSERT_GT(dynamic, 0);
  EXPECT_EQ(m->nbody, 1 + dynamic + kLinkCount);
  EXPECT_EQ(m->ngeom, static_cast<int>(scene.objects.size()) + kLinkCount);
  EXPECT_EQ(m->nmocap, kLinkCount);
  // a free joint per loose object, a hinge or slide per control
  const int controls = static_cast<int>(scene.controls.size());
  EXPECT_EQ(m->njnt, dynamic);
  EXPECT_EQ(m->nq, 7 * (dynamic - controls) + controls);
  EXPECT_EQ(m->nv, 6 * (dynamic - controls) + controls);
  EXPECT_EQ(mj.timestep_s(), scene.step_s);
  EXPECT_EQ(vec3(m->opt.gravity), scene.gravity_mps2);
  EXPECT_EQ(m->opt.integrator, mjINT_EULER);
  EXPECT_EQ(m->opt.solver, mjSOL_NEWTON);
  EXPECT_EQ(m->opt.cone, mjCONE_PYRAMIDAL);

  for (int i = 0; i < static_cast<int>(scene.objects.size()); ++i) {
    const physics::ObjectSpec& o = scene.objects[static_cast<std::size_t>(i)];
    const int g = mj.object_geom(i);
    ASSERT_GE(g, 0) << o.name;
    EXPECT_EQ(m->geom_friction[3 * g], o.material.mu_s) << o.name;
    if (!o.dynamic) {
      EXPECT_EQ(mj.object_body(i), -1);
      EXPECT_EQ(m->geom_bodyid[g], 0) << o.name;
      continue;
    }
    const int b = mj.object_body(i);
    ASSERT_GT(b, 0) << o.name;
    EXPECT_EQ(m->geom_bodyid[g], b);
    EXPECT_NEAR(m->body_mass[b], o.mass_kg, 1e-15 * o.mass_kg) << o.name;
    // the inertial sits at our centroid: the body origin, or a control's X_JO from its joint
    // frame; same principal moments
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    if (o.control >= 0) centroid = scene.controls[static_cast<std::size_t>(o.control)].X_JO.translation();
    EXPECT_LT((vec3(m->body_ipos + 3 * b) - centroid).norm(), 1e-15) << o.name;
    Eigen::Vector3d ours = o.I_O.diagonal(), theirs = vec3(m->body_inertia + 3 * b);
    std::sort(ours.begin(), ours.end());
    std::sort(theirs.begin(), theirs.end());
    EXPECT_LT((ours - theirs).norm(), 1e-12 * ours.norm()) << o.name;
  }

  // the pairs that act in ours: static-dynamic, dynamic-dynamic, hand-dynamic, and a control
  // with the hand and free objects only
  const int floor = mj.object_geom(scene.find_object("floor"));
  const int console = mj.object_geom(scene.find_object("centre_console"));
  const int cup = mj.object_geom(scene.find_object("cup"));
  const int checklist = mj.object_geom(scene.find_object("checklist"));
  const int palm = mj.hand_geom(0), tip = mj.hand_geom(kLinkCount - 1);
  EXPECT_TRUE(pair_can_collide(m, floor, cup));
  EXPECT_TRUE(pair_can_collide(m, cup, checklist));
  EXPECT_TRUE(pair_can_collide(m, palm, cup));
  EXPECT_TRUE(pair_can_collide(m, tip, cup));
  EXPECT_FALSE(pair_can_collide(m, floor, console));
  EXPECT_FALSE(pair_can_collide(m, palm, console));
  EXPECT_FALSE(pair_can_collide(m, palm, tip));
  // a control meets the hand and free objects, never its panel or another control
  const int button = mj.object_geom(scene.find_object("master_caution"));
  const int toggle = mj.object_geom(scene.find_object("fuel_pump"));
  const int panel = mj.object_geom(scene.find_object("instrument_panel"));
  EXPECT_TRUE(pair_can_collide(m, tip, button));
  EXPECT_TRUE(pair_can_collide(m, cup, button));
  EXPECT_FALSE(pair_can_collide(m, panel, button));
  EXPECT_FALSE(pair_can_collide(m, toggle, button));
}

TEST(MujocoScene, RestingObjectsStayPutForOneSecond) {
  const physics::Scene scene = cockpit_scene();
  MujocoWorld mj(scene);  // the hand stays parked far away
  const int steps = static_cast<int>(std::lround(1.0 / scene.step_s));
  for (int k = 0; k < steps; ++k) mj.step();
  for (int i = 0; i < static_cast<int>(scene.objects.size()); ++i) {
    const physics::ObjectSpec& o = scene.objects[static_cast<std::size_t>(i)];
    // (a control's detents have no MuJoCo counterpart: a lever the detent holds in ours creeps
    // under gravity in MuJoCo, so only the loose objects are checked)
    if (!o.dynamic || o.control >= 0) continue;
    const Eigen::Vector3d p = mj.object_pose(i).translation();
    EXPECT_LT((p - o.X_GO.translation()).norm(), 0.01) << o.name;
    EXPECT_GT(p.z(), 0.0) << o.name << " fell through the floor";
  }
}

TEST(MujocoScene, ObjectStateRoundTrips) {
  const physics::Scene scene = cockpit_scene();
  MujocoWorld mj(scene);
  const int cup = scene.find_object("cup");
  std::vector<physics::BodyState> states = initial_states(scene);
  physics::BodyState& s = states[static_cast<std::size_t>(cup)];
  s.X_GO = pose_from_position_rpy_deg({0.1, -0.2, 1.3}, {20.0, -35.0, 110.0});
  mj.set_object_states(states);
  const Eigen::Isometry3d X = mj.object_pose(cup);
  EXPECT_LT((X.translation() - s.X_GO.translation()).norm(), 1e-15);
  EXPECT_LT((X.linear() - s.X_GO.linear()).norm(), 1e-14);
  // static objects report their spec pose
  const int floor = scene.find_object("floor");
  EXPECT_TRUE(mj.object_pose(floor).isApprox(scene.objects[static_cast<std::size_t>(floor)].X_GO));
}

// The free joint's qvel is the linear velocity in world and the angular one in the body frame:
// one step of a free, tilted, spinning body moves and turns it as our state says.
TEST(MujocoScene, FreeJointVelocityFrames) {
  physics::Scene scene;
  scene.gravity_mps2.setZero();
  physics::ObjectSpec o;
  o.name = "spinner";  // elongated, so a wrong frame for w would show
  o.dynamic = true;
  o.shape = physics::Shape::box({0.1, 0.2, 0.3});
  physics::mass_properties_from_density(o.shape, 500.0, o.mass_kg, o.I_O);
  scene.objects.push_back(o);
  MujocoWorld mj(scene);
  physics::BodyState s;
  s.X_GO = pose_from_position_rpy_deg({0.3, 0.2, 0.5}, {30.0, 40.0, -60.0});
  s.v_G = {0.5, -0.25, 1.0};
  s.w_G = Eigen::Vector3d(0.3, -0.2, 0.9).normalized() * 0.5;
  mj.set_object_states({s});
  const double dt = mj.timestep_s();
  mj.step();
  const Eigen::Isometry3d X = mj.object_pose(0);
  EXPECT_LT((X.translation() - (s.X_GO.translation() + dt * s.v_G)).norm(), 1e-12);
  // gyroscopic effects change w by O(dt) over the step, so the turn agrees to O(dt^2 |w|^2)
  const Eigen::Matrix3d R_expected =
      Eigen::AngleAxisd(dt * s.w_G.norm(), s.w_G.normalized()).toRotationMatrix() *
      s.X_GO.linear();
  EXPECT_LT((X.linear() - R_expected).norm(), 1e-6);
  const Eigen::Matrix3d R_if_world_frame =  // what a world-frame reading of qvel would give
      Eigen::AngleAxisd(dt * s.w_G.norm(), s.X_GO.linear() * s.w_G.normalized())
          .toRotationMatrix() * s.X_GO.linear();
  EXPECT_GT((R_if_world_frame - R_expected).norm(), 1e-4);  // the check above can tell
}

// Names are made XML- and MuJoCo-safe (and unique after cleaning); a scene may have no hand.
TEST(MujocoScene, OddNamesAndNoHand) {
  physics::Scene scene;
  physics::ObjectSpec floor;
  floor.name = "floor <\"&'>";
  floor.shape = physics::Shape::box({1.0, 1.0, 0.1});
  floor.X_GO.translation().z() = -0.05;
  scene.objects.push_back(floor);
  for (const char* name : {"a b", "a_b", "a&b"}) {
    physics::ObjectSpec o;
    o.name = name;
    o.dynamic = true;
    o.shape = physics::Shape::sphere(0.02);
    physics::mass_properties_from_density(o.shape, 500.0, o.mass_kg, o.I_O);
    o.X_GO.translation() = Eigen::Vector3d(0.1 * static_cast<double>(scene.objects.size()), 0.0,
                                           0.02);
    scene.objects.push_back(o);
  }
  MujocoWorld mj(scene);
  EXPECT_EQ(mj.model()->nbody, 1 + 3);
  EXPECT_EQ(mj.model()->nmocap, 0);
  EXPECT_EQ(mj.hand_geom(0), -1);
  std::array<Eigen::Isometry3d, kLinkCount> X_GL;
  X_GL.fill(Eigen::Isometry3d::Identity());
  EXPECT_THROW(mj.set_hand(X_GL), std::logic_error);
  for (int k = 0; k < 100; ++k) mj.step();
  EXPECT_EQ(mj.contact_count(), 3);  // each sphere on the floor
  for (int i = 1; i <= 3; ++i)
    EXPECT_NEAR(mj.object_pose(i).translation().z(), 0.02, 1e-3);
}

TEST(MujocoScene, HandGeomsSitWhereOursDo) {
  const Held& held = held_cockpit();
  const physics::World& world = *held.world;
  const hand::HandModel& hand = world.scene().hands[0];
  MujocoWorld mj(world.scene());
  mj.set_hand(world.X_GL());
  mj.forward();
  const mjData* d = mj.data();
  Eigen::Matrix3d Ry90;  // our capsule's z onto the phalanx axis x_L
  Ry90 << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  for (int l = 0; l < kLinkCount; ++l) {
    const Eigen::Isometry3d& X_GL = world.X_GL()[static_cast<std::size_t>(l)];
    Eigen::Isometry3d X_GC = X_GL;  // palm: the box is centred on the link frame
    if (l != 0) {
      X_GC = X_GL * Eigen::Translation3d(
                        0.5 * hand.capsules[static_cast<std::size_t>(l)].length_m, 0.0, 0.0);
      X_GC.linear() = X_GL.linear() * Ry90;
    }
    const int g = mj.hand_geom(l);
    EXPECT_LT((vec3(d->geom_xpos + 3 * g) - X_GC.translation()).norm(), 1e-9) << "link " << l;
    EXPECT_LT((mat3(d->geom_xmat + 9 * g) - X_GC.linear()).norm(), 1e-9) << "link " << l;
  }
}

TEST(MujocoScene, CrowdedCockpitSteps) {
  const physics::Scene scene = crowded_cockpit_scene(500);
  MujocoWorld mj(scene);
  EXPECT_EQ(mj.model()->nbody, 1 + dynamic_count(scene) + kLinkCount);
  for (int k = 0; k < 10; ++k) ASSERT_NO_THROW(mj.step());
  EXPECT_GT(mj.contact_count(), 500);  // every loose object rests on the floor
  std::printf("crowded cockpit (500 loose): %d contacts after 10 steps (nconmax %d, njmax %d)\n",
              mj.contact_count(), mj.model()->nconmax, mj.model()->njmax);
}

// The benchmark's scenes are what they say: the crowded cockpit's loose objects start clear of
// the cockpit's static bodies (they once stood half inside the back wall, and 17 of 100 were
// shot through the floor in the first steps) and rest on the floor; the pile settles in its bin.
// Our physics, 0.3 s of each (without sleeping) and 6 s of the pile.
TEST(BenchScenes, LooseObjectsStartClearOfTheCockpitAndStayOnTheFloor) {
  for (const int loose : {100, 500}) {
    physics::Scene scene = crowded_cockpit_scene(loose);
    scene.sleep.enabled = false;
    physics::World world(scene);
    world.step();
    const auto name = [&](int body) {
      return body < static_cast<int>(scene.objects.size()) ? scene.objects[static_cast<std::size_t>(body)].name
                                                           : std::string("a hand link");
    };
    for (const physics::AppliedContact& a : world.contacts()) {
      const std::string na = name(a.contact.body_a), nb = name(a.contact.body_b);
      const bool a_loose = na.rfind("loose_", 0) == 0, b_loose = nb.rfind("loose_", 0) == 0;
      if ((a_loose && nb != "floor") || (b_loose && na != "floor"))
        ADD_FAILURE() << na << " and " << nb << " touch at the start, " << a.contact.depth_m * 1e3
                      << " mm deep";
    }
    for (int k = 0; k < 300; ++k) world.step();  // (the objects in the wall flew within 10 steps)
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      const physics::ObjectSpec& o = scene.objects[i];
      if (o.name.rfind("loose_", 0) != 0) continue;
      const Eigen::Vector3d moved = world.bodies()[i].X_GO.translation() - o.X_GO.translation();
      EXPECT_LT(moved.norm(), 0.002) << o.name << " of " << loose << " moved " << moved.transpose();
    }
  }
}

TEST(BenchScenes, ThePileSettlesInItsBin) {
  const physics::Scene scene = pile_scene(200);
  physics::World world(scene);
  for (int k = 0; k < 6000; ++k) world.step();
  int asleep = 0;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    if (!scene.objects[i].dynamic) continue;
    const Eigen::Vector3d p = world.bodies()[i].X_GO.translation();
    EXPECT_GT(p.z(), 0.0) << scene.objects[i].name << " under the floor";
    EXPECT_LT(p.head<2>().cwiseAbs().maxCoeff(), 0.25) << scene.objects[i].name << " out of the bin";
    asleep += world.bodies()[i].asleep ? 1 : 0;
  }
  EXPECT_EQ(asleep, 200) << "6 s after the drop";
}

// The cup our hand holds is welded to MuJoCo's palm where it is (MuJoCo's way to hold a body, as
// ours is attached), so both engines step the same situation: it stays in the still hand.
// (Without the weld MuJoCo's soft contacts let it slip out and fall within 0.2 s.)
TEST(MujocoScene, HeldCupStaysInTheHand) {
  const Held& held = held_cockpit();
  const physics::World& world = *held.world;
  const int cup = world.scene().find_object("cup");
  MujocoWorld mj(world.scene());
  mj.set_hand(world.X_GL());
  mj.set_object_states(world.bodies());
  mj.forward();
  const Eigen::Isometry3d X0 = world.bodies()[static_cast<std::size_t>(cup)].X_GO;
  double max_drift_m = 0.0, max_turn_deg = 0.0;
  for (int k = 1; k <= 500; ++k) {
    mj.step();
    const Eigen::Isometry3d X = mj.object_pose(cup);
    max_drift_m = std::max(max_drift_m, (X.translation() - X0.translation()).norm());
    max_turn_deg = std::max(
        max_turn_deg, Eigen::AngleAxisd(X.linear() * X0.linear().transpose()).angle() * 180.0 / M_PI);
  }
  std::printf("held cup over 0.5 s in MuJoCo: drift at most %.5f m, turned at most %.3f deg, "
              "%d contacts\n", max_drift_m, max_turn_deg, mj.contact_count());
  EXPECT_LT(max_drift_m, 0.002);
  EXPECT_LT(max_turn_deg, 1.0);
}

// An object that is not held has its weld off: the free cup falls from the same place.
TEST(MujocoScene, ReleasedCupFalls) {
  const Held& held = held_cockpit();
  const physics::World& world = *held.world;
  const int cup = world.scene().find_object("cup");
  MujocoWorld mj(world.scene());
  mj.set_hand(world.X_GL());
  std::vector<physics::BodyState> states = world.bodies();
  states[static_cast<std::size_t>(cup)].held_by = physics::kNotHeld;
  mj.set_object_states(states);
  // the hand away: nothing holds the cup up
  std::array<Eigen::Isometry3d, hand::kLinkCount> X_GL = world.X_GL();
  for (auto& X : X_GL) X.translation().z() += 10.0;
  mj.set_hand(X_GL);
  const double z0 = mj.object_pose(cup).translation().z();
  for (int k = 0; k < 100; ++k) mj.step();
  EXPECT_LT(mj.object_pose(cup).translation().z(), z0 - 0.03);  // ~g t^2 / 2 = 4.9 cm in 0.1 s
}

}  // namespace
}  // namespace vcockpit::bench
