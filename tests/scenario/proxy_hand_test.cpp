// The proxy hand (proxy_hand.hpp) against what a cockpit user sees:
//   - a tracked hand pressed 4 cm into a console (a box, or a static mesh of 2 or 800 triangles
//     on top) leaves the drawn hand resting on it, no link more than 1 mm inside, and sliding
//     along it with the tracked hand;
//   - a hand swept through a ball at 2 m/s pushes it at about the pushing speed, not 2 m/s (the
//     same sweep with the proxy off throws it faster: the test tells the two apart);
//   - a cup squeezed by the palm against the console is neither crushed into it nor set
//     chattering (with the proxy off, it is pressed several mm into the console);
//   - the wrist approaches a far tracked pose no faster than max_speed_mps;
//   - a held grip presses as hard on each side (the thumb's and the fingers');
//   - a finger that a heavy block stops short of the tracked one pulls the wrist back by the
//     share finger_pull_ratio gives (half for 1), and not at all for 0; of the default cockpit's
//     objects, the heavy bar and the pivoting levers' handles pull, knobs, buttons, switches,
//     the sliding gear lever and light objects do not; a hand that holds something keeps its
//     pull, turned with the wrist.
// Geometry is checked analytically: each capsule's lowest end point and the palm box's corners
// against the console's top face.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "common/pose.hpp"
#include "hand/config/hand_yaml.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/physics/proxy_hand.hpp"
#include "physics_node/physics/world.hpp"
#include "tests/support/scene_builder.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::physics {
namespace {

using test::at;
using test::source_dir;

constexpr double kConsoleTop_m = 0.70;

// A closed box mesh of `size_m` centred on its origin, its top face an n x n grid of squares (each
// two triangles), every other face two triangles: a console as a model file would give it.
std::shared_ptr<model::TriangleMesh> box_mesh(const Eigen::Vector3d& size_m, int n) {
  auto mesh = std::make_shared<model::TriangleMesh>();
  const Eigen::Vector3d h = 0.5 * size_m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      mesh->vertices_m.emplace_back(-h.x() + size_m.x() * i / n, -h.y() + size_m.y() * j / n, h.z());
  const auto top = [n](int i, int j) { return static_cast<uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      mesh->triangles.push_back({top(i, j), top(i + 1, j), top(i + 1, j + 1)});
      mesh->triangles.push_back({top(i, j), top(i + 1, j + 1), top(i, j + 1)});
    }
  const uint32_t b = static_cast<uint32_t>(mesh->vertices_m.size());  // bottom corners
  for (int k = 0; k < 4; ++k)
    mesh->vertices_m.emplace_back((k == 1 || k == 2) ? h.x() : -h.x(), k >= 2 ? h.y() : -h.y(), -h.z());
  const std::array<uint32_t, 4> t = {top(0, 0), top(n, 0), top(n, n), top(0, n)};
  for (uint32_t k = 0; k < 4; ++k) {  // sides, counter-clockwise from outside
    const uint32_t k1 = (k + 1) % 4;
    mesh->triangles.push_back({b + k, b + k1, t[k1]});
    mesh->triangles.push_back({b + k, t[k1], t[k]});
  }
  mesh->triangles.push_back({b + 0, b + 2, b + 1});
  mesh->triangles.push_back({b + 0, b + 3, b + 2});
  return mesh;
}

// A console (top at z = 0.70, x 0.1..0.7, y -0.3..0.3) on a floor, the default hand, and the
// given objects. `mesh_grid` > 0: the console is a static mesh whose top has that many squares a
// side (0: a box).
Scene console_scene(bool proxy, int mesh_grid = 0) {
  Scene scene;
  scene.hands = {load_hand_model(source_dir() + "/config/hand.yaml")};
  scene.hand_material = test::material(2.0e4, 1.0, 0.8);
  scene.objects.push_back(test::floor_box(test::material(5.0e4, 0.7, 0.6, 0.9)));
  scene.objects.push_back(test::static_box("console", {0.6, 0.6, 0.7}, at(0.4, 0.0, 0.35),
                                           test::material(5.0e4, 0.6, 0.5, 0.9)));
  if (mesh_grid > 0)
    scene.objects.back().shape = Shape::triangle_mesh(box_mesh({0.6, 0.6, 0.7}, mesh_grid), nullptr);
  scene.proxy.enabled = proxy;
  return scene;
}

// How deep the hand's links are below the console's top (m; 0 when above it). Valid while the
// hand is over the console's top face.
double depth_below_top(const World& world) {
  const HandModel& hand = world.scene().hands[0];
  const auto& X_GL = world.X_GL();
  double lowest_m = 1e9;
  const Eigen::Vector3d half = 0.5 * hand.palm_size_m;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d c((corner & 1) ? half.x() : -half.x(), (corner & 2) ? half.y() : -half.y(),
                            (corner & 4) ? half.z() : -half.z());
    lowest_m = std::min(lowest_m, (X_GL[0] * c).z());
  }
  for (int l = 1; l < kLinkCount; ++l) {
    const Capsule& capsule = hand.capsules[static_cast<std::size_t>(l)];
    const double a = X_GL[l].translation().z();
    const double b = (X_GL[l] * Eigen::Vector3d(capsule.length_m, 0, 0)).z();
    lowest_m = std::min(lowest_m, std::min(a, b) - capsule.radius_m);
  }
  return std::max(0.0, kConsoleTop_m - lowest_m);
}

double lowest_link_height(const World& world) { return kConsoleTop_m - depth_below_top(world); }

HandInput hand_at(const HandModel& hand, const Eigen::Vector3d& p_G) {
  HandInput in;
  in.X_GH = Eigen::Isometry3d::Identity();  // palm down, fingers along +x
  in.X_GH.translation() = p_G;
  in.q_rad = hand.rest_pose();
  return in;
}

double lerp(double a, double b, double s) { return a + std::clamp(s, 0.0, 1.0) * (b - a); }

// The console as a box, as a static mesh with a top of two triangles, and as one of 800 (a
// finger then touches several at once, each its own contact point): the proxy's "never more than
// 1 mm inside a static object" holds against all three.
class PressedIntoTheConsole : public ::testing::TestWithParam<int> {};

TEST_P(PressedIntoTheConsole, TheHandRestsOnItAndSlides) {
  World world(console_scene(true, GetParam()));
  const HandModel& hand = world.scene().hands[0];
  double deepest_m = 0.0;
  double lowest_at_rest_m = 1.0;
  double offset_at_rest_m = 0.0;
  for (int step = 0; step < 1200; ++step) {
    const double t_s = step * 1e-3;
    // down from 6 cm above the top to 4 cm into it in 0.4 s, held, then 5 cm along +x
    const double z = lerp(kConsoleTop_m + 0.06, kConsoleTop_m - 0.04, t_s / 0.4);
    const double x = lerp(0.25, 0.30, (t_s - 0.8) / 0.3);
    world.set_hand_input(hand_at(hand, {x, 0.0, z}));
    world.step();
    deepest_m = std::max(deepest_m, depth_below_top(world));
    if (step == 799) {
      lowest_at_rest_m = lowest_link_height(world);
      offset_at_rest_m = world.tracked_offset_m();
    }
  }
  EXPECT_LE(deepest_m, 1.0e-3) << "a link went " << deepest_m * 1e3 << " mm into the console";
  // it rests on the top (touching within a millimetre), while the tracked hand is 4 cm below
  EXPECT_LT(lowest_at_rest_m - kConsoleTop_m, 1.0e-3);
  EXPECT_GT(offset_at_rest_m, 0.03);
  // and slides with the tracked hand along the surface
  EXPECT_NEAR(world.X_GH().translation().x(), 0.30, 2e-3);
  EXPECT_NEAR(world.X_GH().translation().y(), 0.0, 2e-3);
}

INSTANTIATE_TEST_SUITE_P(ProxyHand, PressedIntoTheConsole, ::testing::Values(0, 1, 20),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return info.param == 0 ? std::string("Box")
                                                  : "Mesh" + std::to_string(info.param) + "x" +
                                                        std::to_string(info.param);
                         });

// A 6 cm, 60 g ball on the console, swept by the fingers of a hand moving at 2 m/s.
double ball_speed_after_sweep(bool proxy) {
  Scene scene = console_scene(proxy);
  scene.objects.push_back(test::dynamic_object("ball", Shape::sphere(0.03), 0.06,
                                               at(0.45, 0.0, kConsoleTop_m + 0.03),
                                               test::material(2.0e4, 0.9, 0.8)));
  World world(std::move(scene));
  const HandModel& hand = world.scene().hands[0];
  const int ball = world.scene().find_object("ball");
  double fastest_mps = 0.0;
  for (int step = 0; step < 400; ++step) {
    const double t_s = step * 1e-3;
    // the palm 3 cm above the top, from x 0.15 to 0.55 at 2 m/s: the fingers meet the ball
    world.set_hand_input(hand_at(hand, {lerp(0.15, 0.55, t_s / 0.2), 0.0, kConsoleTop_m + 0.045}));
    world.step();
    fastest_mps = std::max(fastest_mps, world.bodies()[ball].v_G.norm());
  }
  return fastest_mps;
}

TEST(ProxyHand, ASweptBallGetsAboutThePushSpeed) {
  const double with_proxy_mps = ball_speed_after_sweep(true);
  const double kinematic_mps = ball_speed_after_sweep(false);
  const double push_mps = ProxyParams{}.push_speed_mps;
  EXPECT_LE(with_proxy_mps, push_mps + 0.2) << "the ball was thrown at " << with_proxy_mps;
  EXPECT_GT(with_proxy_mps, 0.5 * push_mps) << "the hand should still push the ball";
  EXPECT_GT(kinematic_mps, 1.0) << "without the proxy the 2 m/s hand throws the ball";
}

// A hand whose first input has fingers through a 60 g ball on the console (a tracker that starts
// with the hand where a virtual object stands), held there, then drawn back and swept through the
// ball's place at 2 m/s: the hand (27 mm in it) passes through the ball until it is in it no
// deeper than proxy.pass_through_depth_m (GraspHold::passing_through), then pushes it as any hand
// does. Before, the first step pushed
// the ball out of the fingers at once.
struct AppearedInside {
  bool passing = false;             // after the first input
  double still_fastest_mps = 0.0;   // while the hand stays where it appeared
  double still_drift_m = 0.0;
  bool cleared = false;             // no longer passing through once drawn back
  double sweep_fastest_mps = 0.0;   // drawn back, then swept through its place
};

AppearedInside appear_inside_ball(bool proxy) {
  const Eigen::Vector3d ball_at(0.45, 0.0, kConsoleTop_m + 0.03);
  const double palm_z = kConsoleTop_m + 0.045;  // the sweep's height: the fingers meet the ball
  Scene scene = console_scene(proxy);
  scene.objects.push_back(test::dynamic_object("ball", Shape::sphere(0.03), 0.06,
                                               at(ball_at.x(), ball_at.y(), ball_at.z()),
                                               test::material(2.0e4, 0.9, 0.8)));
  World world(std::move(scene));
  const HandModel& hand = world.scene().hands[0];
  const auto ball = static_cast<std::size_t>(world.scene().find_object("ball"));
  // the wrist 12 cm behind the ball's centre: the middle finger's first two links in it
  const double x = ball_at.x() - 0.12;
  world.set_hand_input(hand_at(hand, {x, 0.0, palm_z}));
  AppearedInside out;
  out.passing = world.state().hands[0].grasp[ball].passing_through;
  for (int step = 0; step < 300; ++step) {  // held where it appeared
    world.step();
    const BodyState& b = world.bodies()[ball];
    out.still_fastest_mps = std::max(out.still_fastest_mps, b.v_G.norm());
    out.still_drift_m = std::max(out.still_drift_m, (b.X_GO.translation() - ball_at).norm());
  }
  for (int step = 0; step < 600; ++step) {  // back 15 cm over 0.3 s, then through at 2 m/s
    const double t_s = step * 1e-3;
    const double back_x = x - 0.15;
    const double hand_x =
        t_s < 0.3 ? lerp(x, back_x, t_s / 0.3) : lerp(back_x, back_x + 0.4, (t_s - 0.3) / 0.2);
    world.set_hand_input(hand_at(hand, {hand_x, 0.0, palm_z}));
    world.step();
    if (step == 299) out.cleared = !world.state().hands[0].grasp[ball].passing_through;
    out.sweep_fastest_mps = std::max(out.sweep_fastest_mps, world.bodies()[ball].v_G.norm());
  }
  return out;
}

TEST(ProxyHand, AHandThatAppearsInsideABallPassesThroughItUntilItIsClear) {
  const double push_mps = ProxyParams{}.push_speed_mps;
  for (const bool proxy : {true, false}) {
    const AppearedInside r = appear_inside_ball(proxy);
    std::printf("proxy %d: still: fastest %.4f m/s, drift %.2f mm; swept: fastest %.3f m/s\n",
                proxy, r.still_fastest_mps, r.still_drift_m * 1e3, r.sweep_fastest_mps);
    ASSERT_TRUE(r.passing) << "the hand did not start in the ball";
    EXPECT_LE(r.still_fastest_mps, 0.02) << "proxy " << proxy;
    EXPECT_LE(r.still_drift_m, 1e-3) << "proxy " << proxy;
    EXPECT_TRUE(r.cleared) << "proxy " << proxy;
    // clear of it, the hand is solid again: the sweep pushes the ball (the proxy at about the
    // pushing speed)
    EXPECT_GT(r.sweep_fastest_mps, 0.5 * push_mps) << "proxy " << proxy;
    if (proxy) {
      EXPECT_LE(r.sweep_fastest_mps, push_mps + 0.2);
    }
  }
}

struct Squeeze {
  double cup_sink_m = 0.0;   // deepest the cup's base went below the console's top
  double max_spin_radps = 0.0;
  int reversals = 0;         // steps whose spin (> 0.05 rad/s) turned by more than 90 degrees
  double wobble_deg = 0.0;   // the most the cup turned from its attitude at 0.4 s
  double drift_m = 0.0;
};

// A 200 g cup on the console, the palm brought down on it and on to 3 cm into it, held there.
Squeeze squeeze_cup(bool proxy) {
  Scene scene = console_scene(proxy);
  const double height_m = 0.10;
  scene.objects.push_back(test::dynamic_object("cup", Shape::cylinder(0.035, height_m), 0.2,
                                               at(0.35, 0.0, kConsoleTop_m + 0.5 * height_m),
                                               test::material(3.0e4, 0.5, 0.4, 0.8)));
  World world(std::move(scene));
  const HandModel& hand = world.scene().hands[0];
  const int cup = world.scene().find_object("cup");
  const Eigen::Vector3d start = world.bodies()[cup].X_GO.translation();
  // palm centre over the cup (the palm box sits ahead of the wrist)
  const double x_wrist = 0.35 - hand.X_HP.translation().x();
  const double palm_below_wrist_m = -hand.X_HP.translation().z() + 0.5 * hand.palm_size_m.z();
  const double cup_top = kConsoleTop_m + height_m;
  Squeeze s;
  Eigen::Vector3d w_before = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_held = Eigen::Quaterniond::Identity();
  for (int step = 0; step < 1000; ++step) {
    const double t_s = step * 1e-3;
    const double palm_bottom = lerp(cup_top + 0.02, cup_top - 0.03, t_s / 0.3);
    HandInput in = hand_at(hand, {x_wrist, 0.0, palm_bottom + palm_below_wrist_m});
    in.q_rad.fill(0.0);  // a flat hand, as far as the joints' ranges allow
    hand::clamp_to_limits(hand, in.q_rad);
    world.set_hand_input(in);
    world.step();
    const BodyState& b = world.bodies()[cup];
    s.cup_sink_m = std::max(s.cup_sink_m, kConsoleTop_m - (b.X_GO.translation().z() - 0.5 * height_m));
    if (step == 400) q_held = Eigen::Quaterniond(b.X_GO.linear());
    if (step > 400) {
      s.wobble_deg = std::max(s.wobble_deg,
                              rad_to_deg(q_held.angularDistance(Eigen::Quaterniond(b.X_GO.linear()))));
    }
    if (t_s > 0.4) {
      s.max_spin_radps = std::max(s.max_spin_radps, b.w_G.norm());
      if (b.w_G.norm() > 0.05 && w_before.norm() > 0.05 && b.w_G.dot(w_before) < 0.0) ++s.reversals;
    }
    w_before = b.w_G;
    s.drift_m = (b.X_GO.translation() - start).head<2>().norm();
  }
  return s;
}

TEST(ProxyHand, ACupSqueezedAgainstTheConsoleIsNotCrushed) {
  const Squeeze proxy = squeeze_cup(true);
  const Squeeze kinematic = squeeze_cup(false);
  // resting, the cup sinks m g / k (0.07 mm); the palm adds at most grip_force_N / k_pair
  EXPECT_LT(proxy.cup_sink_m, 1.5e-3) << "the cup was pressed " << proxy.cup_sink_m * 1e3 << " mm in";
  // chatter: the cup shaking under the palm. Measured as what can be seen, the spin and how far
  // the cup turns while held; the spin's reversals are printed only: with exact finger normals
  // (segment_contact.hpp) a cup at rest reverses a spin of a few tenths of a rad/s, turning it
  // by hundredths of a degree. The palm lands on the cup's top and tips it by ~0.4 deg; pressed
  // on toward the tracked hand 3 cm below, the proxy then slides along that tilted top (a
  // god-object's slide: at most 3 cm x the tilt, 0.2 mm) and drags the cup a few tenths of a
  // degree round by friction until it reaches the top's point nearest the tracked hand, and stops
  EXPECT_LT(proxy.max_spin_radps, 1.0) << "the squeezed cup chatters";
  EXPECT_LT(proxy.wobble_deg, 0.5) << "the squeezed cup chatters";
  EXPECT_LT(proxy.drift_m, 0.01);
  EXPECT_GT(kinematic.cup_sink_m, 4e-3) << "without the proxy the palm crushes the cup in";
  std::printf("squeezed cup: proxy sink %.2f mm, %d reversals, max spin %.2f rad/s, turned %.3f deg; "
              "kinematic sink %.2f mm, %d reversals, max spin %.2f rad/s, turned %.3f deg\n",
              proxy.cup_sink_m * 1e3, proxy.reversals, proxy.max_spin_radps, proxy.wobble_deg,
              kinematic.cup_sink_m * 1e3, kinematic.reversals, kinematic.max_spin_radps,
              kinematic.wobble_deg);
}

TEST(ProxyHand, TheWristApproachesAFarTrackedPoseAtItsMaximumSpeed) {
  World world(console_scene(true));
  const HandModel& hand = world.scene().hands[0];
  world.set_hand_input(hand_at(hand, {0.2, 0.0, 1.2}));
  world.step();
  world.set_hand_input(hand_at(hand, {0.2, 1.0, 1.2}));  // a 1 m jump, e.g. a tracker glitch
  for (int step = 0; step < 100; ++step) world.step();
  const double moved_m = world.X_GH().translation().y();
  EXPECT_NEAR(moved_m, 100 * 1e-3 * world.scene().proxy.max_speed_mps, 1e-9);
  EXPECT_NEAR(world.tracked_offset_m(), 1.0 - moved_m, 1e-6);
}

// The fingers catch up with a far tracked shape no faster than the wrist: a glove that jumps from
// an open hand to a fist (a glitch, or a finger the world held back and let go) moves no fingertip
// more than max_speed_mps * step per step, and the fist is reached in the end.
TEST(ProxyHand, TheFingersApproachAFarTrackedShapeAtTheMaximumSpeed) {
  World world(console_scene(true));
  const HandModel& hand = world.scene().hands[0];
  HandInput open = hand_at(hand, {0.2, 0.0, 1.2});
  world.set_hand_input(open);
  world.step();
  HandInput fist = open;
  for (int j = 0; j < kJointCount; ++j) fist.q_rad[j] = hand.joints[j].max_rad;
  world.set_hand_input(fist);
  const double reach_m = world.scene().proxy.max_speed_mps * world.scene().step_s;
  HandLinkPoses before;
  HandLinkPoses now;
  forward_kinematics(hand, world.state().hands[0].q_rad, before);
  double fastest_m = 0.0;
  for (int step = 0; step < 200; ++step) {
    world.step();
    forward_kinematics(hand, world.state().hands[0].q_rad, now);
    for (int f = 0; f < kFingerCount; ++f)
      fastest_m = std::max(fastest_m, (now.p_H_tip[f] - before.p_H_tip[f]).norm());
    before = now;
  }
  EXPECT_LE(fastest_m, reach_m * 1.01);  // the shares are measured again to within this
  EXPECT_GT(fastest_m, 0.9 * reach_m);  // and it does move at that speed
  for (int j = 0; j < kJointCount; ++j) EXPECT_NEAR(world.state().hands[0].q_rad[j], fist.q_rad[j], 1e-9) << j;
}

// A held torch gripped by the thumb on one side and three fingers on the other: the fingers go
// in only a third as deep as a free grip's, so each presses a third of the thumb's force and
// the grip balances; the thumb keeps the full depth. Against one finger both keep it; an
// object not held is not balanced (it moves under the forces instead).
TEST(ProxyHand, AHeldGripPressesAsHardOnEachSide) {
  Scene scene = console_scene(true);
  scene.objects.push_back(test::dynamic_object("torch", Shape::cylinder(0.018, 0.16), 0.25,
                                               at(0.4, 0.0, 0.9), test::material(3.0e4, 0.5, 0.4, 0.8)));
  const int torch = 2;
  ProxyHand proxy(scene);
  const int first_link = static_cast<int>(scene.objects.size());
  const auto body = [&](Link l) { return first_link + static_cast<int>(l); };
  const auto contact = [&](Link l, double n_y) {
    ContactPoint c;
    c.body_a = torch;
    c.body_b = body(l);
    c.n_G = Eigen::Vector3d(0.0, n_y, 0.0);  // from the torch into the link
    c.depth_m = 1e-4;
    return c;
  };
  const double free_limit_m = proxy.depth_limit_m(torch);
  const std::vector<ContactPoint> grip = {contact(Link::kThumbDistal, 1.0),
                                          contact(Link::kIndexDistal, -1.0),
                                          contact(Link::kMiddleDistal, -1.0),
                                          contact(Link::kRingDistal, -1.0)};
  std::vector<uint8_t> held(scene.objects.size(), 0);
  proxy.balance_held_grips(grip, held);
  EXPECT_EQ(proxy.depth_limit_m(torch, body(Link::kIndexDistal)), free_limit_m) << "not held";
  held[torch] = 1;
  proxy.balance_held_grips(grip, held);
  EXPECT_DOUBLE_EQ(proxy.depth_limit_m(torch, body(Link::kThumbDistal)), free_limit_m);
  for (Link l : {Link::kIndexDistal, Link::kMiddleDistal, Link::kRingDistal})
    EXPECT_DOUBLE_EQ(proxy.depth_limit_m(torch, body(l)), free_limit_m / 3.0);
  const std::vector<ContactPoint> pinch = {grip[0], grip[1]};
  proxy.balance_held_grips(pinch, held);
  EXPECT_DOUBLE_EQ(proxy.depth_limit_m(torch, body(Link::kThumbDistal)), free_limit_m);
  EXPECT_DOUBLE_EQ(proxy.depth_limit_m(torch, body(Link::kIndexDistal)), free_limit_m);
  // thumb and palm against one finger: the two yield to it
  const std::vector<ContactPoint> against_palm = {contact(Link::kPalm, 1.0), grip[0], grip[1]};
  proxy.balance_held_grips(against_palm, held);
  EXPECT_DOUBLE_EQ(proxy.depth_limit_m(torch, body(Link::kPalm)), free_limit_m / 2.0);
  EXPECT_DOUBLE_EQ(proxy.depth_limit_m(torch, body(Link::kIndexDistal)), free_limit_m);
}

// The index finger, alone flexed, closes 1 cm into the top of a 5 kg block resting on the
// console, the wrist held still above it. The block stops the proxy's fingertip; the tracked one
// goes on. With finger_pull_ratio r the wrist rises by r / (1 + r) of the fingertip's shortfall
// (the finger's spring and the wrist's balance), so for r = 1 half of it; for r = 0 the wrist
// stays on the tracked one. The block is not pushed into the console. A 200 g block (lighter
// than the grip force: a finger pushes such a thing along) does not pull at all.
struct FingerPull {
  double wrist_rise_m = 0.0;  // the proxy's wrist above the tracked one
  double shortfall_m = 0.0;   // the tracked fingertip's depth in the block less the proxy's
  double block_sink_m = 0.0;
  double proxy_tip_depth_m = 0.0;
};

FingerPull pull_of_a_flexed_index(double ratio, double block_kg = 5.0) {
  constexpr double kBlockTop_m = kConsoleTop_m + 0.04;
  constexpr double kIndexFlex_rad = 50.0 * M_PI / 180.0;
  constexpr double kInto_m = 0.01;
  Scene scene = console_scene(true);
  scene.proxy.finger_pull_ratio = ratio;
  const HandModel hand = scene.hands[0];
  HandInput open = hand_at(hand, {0.3, 0.0, 1.0});
  for (int j = 0; j < kJointCount; ++j) open.q_rad[j] = std::clamp(0.0, hand.joints[j].min_rad, hand.joints[j].max_rad);
  HandInput flexed = open;
  const int mcp = static_cast<int>(hand::Joint::kIndexMcp);
  flexed.q_rad[mcp] = kIndexFlex_rad;
  const auto tip_G = [&](const HandInput& in) {
    HandLinkPoses links;
    forward_kinematics(hand, in.q_rad, links);
    return Eigen::Vector3d(in.X_GH * links.p_H_tip[static_cast<std::size_t>(Finger::kIndex)]);
  };
  const auto distal = static_cast<std::size_t>(Link::kIndexDistal);
  const double radius_m = hand.capsules[distal].radius_m;
  // the wrist so high that the flexed tracked fingertip ends kInto_m below the block's top
  const Eigen::Vector3d tip = tip_G(flexed);
  const double wrist_z = open.X_GH.translation().z() + (kBlockTop_m - kInto_m + radius_m - tip.z());
  open.X_GH.translation().z() = wrist_z;
  flexed.X_GH.translation().z() = wrist_z;
  const Eigen::Vector3d tip_at = tip_G(flexed);
  scene.objects.push_back(test::dynamic_object("block", Shape::box({0.03, 0.03, 0.04}),
                                               block_kg, at(tip_at.x(), tip_at.y(), kConsoleTop_m + 0.02),
                                               test::material(5.0e4, 0.8, 0.7, 0.9)));
  World world(std::move(scene));
  const int block = world.scene().find_object("block");
  const auto block_z = [&] { return world.bodies()[block].X_GO.translation().z(); };
  double settled_z = 0.0;  // the block on the console under its own weight (m g / k: ~2 mm in)
  FingerPull out;
  for (int step = 0; step < 1000; ++step) {
    const double t_s = step * 1e-3;
    HandInput in = open;
    in.q_rad[mcp] = lerp(0.0, kIndexFlex_rad, (t_s - 0.2) / 0.3);
    world.set_hand_input(in);
    world.step();
    if (step == 199) settled_z = block_z();
    if (step >= 200) out.block_sink_m = std::max(out.block_sink_m, settled_z - block_z());
  }
  const double top_m = block_z() + 0.02;
  const double tracked_tip_low_m = (world.tracked_X_GL()[distal] *
                                    Eigen::Vector3d(hand.capsules[distal].length_m, 0, 0)).z() - radius_m;
  const double proxy_tip_low_m = (world.X_GL()[distal] *
                                  Eigen::Vector3d(hand.capsules[distal].length_m, 0, 0)).z() - radius_m;
  out.wrist_rise_m = world.X_GH().translation().z() - wrist_z;
  out.proxy_tip_depth_m = top_m - proxy_tip_low_m;
  out.shortfall_m = (top_m - tracked_tip_low_m) - out.proxy_tip_depth_m;
  return out;
}

TEST(ProxyHand, AFingerAHeavyBlockStopsPullsTheWristBackByItsShare) {
  const FingerPull half = pull_of_a_flexed_index(1.0);
  const FingerPull none = pull_of_a_flexed_index(0.0);
  const FingerPull light = pull_of_a_flexed_index(1.0, 0.2);
  std::printf("finger pull: r = 1: wrist up %.2f mm for a %.2f mm shortfall (tip %.2f mm in); "
              "r = 0: wrist up %.2f mm for %.2f mm\n",
              half.wrist_rise_m * 1e3, half.shortfall_m * 1e3, half.proxy_tip_depth_m * 1e3,
              none.wrist_rise_m * 1e3, none.shortfall_m * 1e3);
  EXPECT_GT(none.shortfall_m, 6e-3) << "the block stops the proxy's fingertip";
  EXPECT_GT(half.shortfall_m, 6e-3);
  EXPECT_NEAR(none.wrist_rise_m, 0.0, 1e-5);
  // r / (1 + r) of the shortfall (to within the tracked and the proxy's fingertips' different
  // tilts: the pull is measured at the contact point, not the lowest point)
  EXPECT_NEAR(half.wrist_rise_m, 0.5 * half.shortfall_m, 0.15 * half.shortfall_m);
  EXPECT_GT(half.wrist_rise_m, 3e-3);
  EXPECT_LT(half.proxy_tip_depth_m, 1e-3) << "the fingertip stays on the block's top";
  EXPECT_LT(half.block_sink_m, 5e-4) << "the finger presses it at most with the grip force";
  EXPECT_LT(none.block_sink_m, 5e-4);
  EXPECT_NEAR(light.wrist_rise_m, 0.0, 1e-5) << "a light block is pushed, it does not pull";
  EXPECT_GT(light.shortfall_m, 6e-3);
}

TEST(ProxyHand, HeavyObjectsAndLeverHandlesHoldFingersBackKnobsAndButtonsDoNot) {
  const Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  const ProxyHand proxy(scene);
  const auto part = [&](const char* control) {
    const int c = scene.find_control(control);
    EXPECT_GE(c, 0) << control;
    return scene.controls[static_cast<std::size_t>(c)].body;
  };
  EXPECT_TRUE(proxy.holds_fingers_back(scene.find_object("heavy_bar")));  // 2.5 kg
  EXPECT_TRUE(proxy.holds_fingers_back(part("throttle")));
  EXPECT_TRUE(proxy.holds_fingers_back(part("flaps")));
  EXPECT_FALSE(proxy.holds_fingers_back(scene.find_object("cup")));  // lighter than the grip force
  EXPECT_FALSE(proxy.holds_fingers_back(part("nav_mode")));
  EXPECT_FALSE(proxy.holds_fingers_back(part("heading_bug")));
  EXPECT_FALSE(proxy.holds_fingers_back(part("master_caution")));
  EXPECT_FALSE(proxy.holds_fingers_back(part("landing_lights")));
  EXPECT_FALSE(proxy.holds_fingers_back(part("gear")));  // it slides: a fingertip pushes it
  EXPECT_FALSE(proxy.holds_fingers_back(scene.find_object("left_pedestal")));  // static
}

// A hand that holds an object keeps the pull it had, turned with the wrist (the grip it centred
// stays centred); a hand that holds nothing, even while the other hand holds the bar, finds its
// pull afresh from its own contacts (none here). Two hands, far apart above the console.
TEST(ProxyHand, AHoldingHandKeepsItsFingerPullTurnedWithTheWrist) {
  Scene scene = console_scene(true);
  scene.hands.push_back(hand::mirrored(scene.hands[0]));
  scene.objects.push_back(test::dynamic_object("bar", Shape::box({0.3, 0.03, 0.03}), 2.5,
                                               at(0.4, 0.0, 0.715),
                                               test::material(5.0e4, 0.8, 0.7, 0.9)));
  World world(std::move(scene));
  const int bar = world.scene().find_object("bar");
  const std::array<HandInput, 2> in = {hand_at(world.scene().hands[0], {0.2, -0.2, 1.2}),
                                       hand_at(world.scene().hands[1], {0.2, 0.2, 1.2})};
  for (int h = 0; h < 2; ++h) world.set_hand_input(in[static_cast<std::size_t>(h)], h);
  world.step();
  const Eigen::Vector3d pull_G(0.004, -0.003, 0.002);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  // the bar held by: no hand, hand 0, hand 1, both (BodyState::holders, a bit per hand)
  for (const uint8_t holders : {0, 1, 2, 3}) {
    World w(world.scene());
    WorldState state = world.state();
    for (HandState& hs : state.hands) hs.finger_pull_G = pull_G;
    state.bodies[static_cast<std::size_t>(bar)].holders = holders;
    w.restore(state);
    for (int h = 0; h < 2; ++h) {  // each wrist turns 0.01 rad about z in this step
      HandInput turning = in[static_cast<std::size_t>(h)];
      turning.X_GH.linear() = turn;
      w.set_hand_input(turning, h);
    }
    w.step();
    for (int h = 0; h < 2; ++h) {
      const Eigen::Vector3d after_G = w.state().hands[static_cast<std::size_t>(h)].finger_pull_G;
      if ((holders >> h & 1) != 0) {
        EXPECT_LT((after_G - turn * pull_G).norm(), 1e-12)
            << "hand " << h << " holds (holders " << int{holders} << "): " << after_G.transpose();
      } else {
        EXPECT_EQ(after_G, Eigen::Vector3d::Zero())
            << "hand " << h << " holds nothing (holders " << int{holders} << ")";
      }
    }
  }
}

}  // namespace
}  // namespace vcockpit::physics
