// The control model's pieces (control.hpp), each against what a cockpit builder specifies:
// the over-centre snap of a toggle, a gate's stop, positions with hysteresis, the latching
// button's push-on / push-off, and a grasped knob that turns with the hand's rotation about its
// axis only.

#include "physics_node/physics/control.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vcockpit::physics {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// A 2-position toggle: +-20 deg, snapping away from 0 with 0.05 N m; a 1 g-cm^2 bat.
ControlSpec toggle() {
  ControlSpec c;
  c.kind = ControlKind::kToggle;
  c.joint = JointKind::kRevolute;
  c.q_min = -20 * kDeg;
  c.q_max = 20 * kDeg;
  c.snap = 0.05;
  c.damping = 1e-5;
  c.positions = {{"down", -20 * kDeg, -1.0, -10 * kDeg}, {"up", 20 * kDeg, 10 * kDeg, 1.0}};
  return c;
}

// Pushes with Q for `push_s`, then lets go for 0.2 s; returns the final state.
ControlState push(const ControlSpec& c, ControlState s, double Q, double push_s) {
  const double M = 1e-7, dt = 1e-4;
  for (double t = 0; t < push_s; t += dt) integrate_control(c, M, Q, dt, 0u, s);
  for (double t = 0; t < 0.2; t += dt) integrate_control(c, M, 0.0, dt, 0u, s);
  update_position(c, s);
  return s;
}

TEST(ControlModel, AToggleFlipsOnlyWhenPushedHarderThanItsSnap) {
  const ControlSpec c = toggle();
  ControlState up;
  up.q = c.q_max;
  up.position = 1;
  const ControlState weak = push(c, up, -0.9 * c.snap, 0.1);
  EXPECT_EQ(weak.q, c.q_max) << "below the snap force it stays";
  EXPECT_EQ(weak.position, 1);
  const ControlState strong = push(c, up, -1.1 * c.snap, 0.1);
  EXPECT_EQ(strong.q, c.q_min) << "above it, it goes over centre and snaps to the other end";
  EXPECT_EQ(strong.position, 0);
}

TEST(ControlModel, AGateStopsTheLeverUnlessLifted) {
  ControlSpec c;
  c.kind = ControlKind::kLever;
  c.joint = JointKind::kRevolute;
  c.q_min = 0.0;
  c.q_max = 1.0;
  c.gates = {{0.2, 0.01}};
  ControlState s;
  s.q = 0.5;
  for (int i = 0; i < 1000; ++i) integrate_control(c, 1e-3, -1.0, 1e-3, 0u, s);
  EXPECT_NEAR(s.q, 0.2, 1e-6) << "held at the gate";
  EXPECT_GT(s.q, 0.2) << "on the side it came from";
  EXPECT_EQ(s.qd, 0.0);
  for (int i = 0; i < 1000; ++i) integrate_control(c, 1e-3, -1.0, 1e-3, 1u, s);
  EXPECT_EQ(s.q, 0.0) << "lifted over it, the lever goes on to its stop";
  // a grasping hand's lift opens it: the held point pulled 12 mm out along the lever
  c.X_GJ = Eigen::Isometry3d::Identity();  // pivot at the origin, axis z
  ControlState held;
  held.X_GH_grasp = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d p_held_H(0.1, 0, 0);  // 10 cm out along x
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  X_GH.translation() = Eigen::Vector3d(0.012, 0, 0);
  EXPECT_NEAR(grasped_lift_m(c, held, X_GH, p_held_H), 0.012, 1e-12);
  // a lever set exactly in the gate's notch (its initial position, or commanded there) leaves it
  // neither way without the lift
  for (double push : {-1.0, 1.0}) {
    ControlState notched;
    notched.q = 0.2;
    for (int i = 0; i < 100; ++i) integrate_control(c, 1e-3, push, 1e-3, 0u, notched);
    EXPECT_EQ(notched.q, 0.2) << push;
    EXPECT_EQ(reachable_q(c, 0.2, 0.2 + 0.1 * push, 1u), 0.2 + 0.1 * push) << "lifted, it goes";
  }
}

TEST(ControlModel, APositionChangesOnceWhenTheCoordinateHoversAtAThreshold) {
  ControlSpec c = toggle();
  ControlState s;
  s.q = c.q_min;
  s.position = 0;
  int changes = 0;
  // from down up to the "up" interval's edge, then hovering +-0.5 deg about it
  for (int i = 0; i <= 400; ++i) {
    s.q = std::min(10 * kDeg + 0.5 * kDeg * std::sin(i * 0.3), -20 * kDeg + i * 0.2 * kDeg);
    if (update_position(c, s)) ++changes;
  }
  EXPECT_EQ(changes, 1);
  EXPECT_EQ(s.position, 1);
  // and back down past the middle: nothing until it enters "down"
  s.q = 0.0;
  EXPECT_FALSE(update_position(c, s));
  s.q = -15 * kDeg;
  EXPECT_TRUE(update_position(c, s));
  EXPECT_EQ(s.position, 0);
}

TEST(ControlModel, ALatchingButtonTogglesOnEachPressAndRestsAtItsLatch) {
  ControlSpec c;
  c.kind = ControlKind::kPushButton;
  c.joint = JointKind::kPrismatic;
  c.q_min = 0.0;
  c.q_max = 0.004;
  c.q_rest = -0.001;
  c.stiffness = 1000.0;
  c.damping = 2.0;
  c.latching = true;
  c.latch_q = 0.0015;
  c.positions = {{"off", 0.0, -1.0, 0.002}, {"on", 0.004, 0.003, 1.0}};
  ControlState s;
  auto press_and_let_go = [&] {
    for (int i = 0; i < 100; ++i) {  // 10 N for 0.1 s: to the bottom
      integrate_control(c, 0.005, 10.0, 1e-3, 0u, s);
      update_position(c, s);
    }
    for (int i = 0; i < 200; ++i) {
      integrate_control(c, 0.005, 0.0, 1e-3, 0u, s);
      update_position(c, s);
    }
  };
  press_and_let_go();
  EXPECT_TRUE(s.latched);
  EXPECT_EQ(s.position, 1);
  EXPECT_NEAR(s.q, c.latch_q, 1e-6) << "held in at its latch";
  press_and_let_go();
  EXPECT_FALSE(s.latched);
  EXPECT_EQ(s.position, 0);
  EXPECT_EQ(s.q, 0.0) << "back out on its stop";
}

// A knob on a panel, its axis along x; the hand that grasped it turns 30 deg about that axis,
// and also swings 20 deg about another axis and moves 3 cm: the knob turns by the 30 deg only.
TEST(ControlModel, AGraspedKnobTurnsWithTheHandsRotationAboutItsAxisOnly) {
  ControlSpec c;
  c.kind = ControlKind::kRotary;
  c.joint = JointKind::kRevolute;
  c.limited = false;
  c.X_GJ.linear() = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  c.X_GJ.translation() = Eigen::Vector3d(0.6, -0.1, 1.0);
  const Eigen::Vector3d axis = c.X_GJ.linear().col(2);
  ASSERT_NEAR(axis.x(), 1.0, 1e-12);
  ControlState s;
  s.q = 0.7;
  s.q_grasp = 0.7;
  s.X_GH_grasp = Eigen::Isometry3d::Identity();
  s.X_GH_grasp.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.2, 0.5, 0.8).normalized()).toRotationMatrix();
  s.X_GH_grasp.translation() = Eigen::Vector3d(0.5, -0.1, 1.05);
  // turn = twist about the axis, then a swing about an axis perpendicular to it
  const Eigen::Matrix3d twist = Eigen::AngleAxisd(30 * kDeg, axis).toRotationMatrix();
  const Eigen::Matrix3d swing = Eigen::AngleAxisd(20 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Eigen::Isometry3d X_GH = s.X_GH_grasp;
  X_GH.linear() = swing * twist * s.X_GH_grasp.linear();
  X_GH.translation() += Eigen::Vector3d(0.03, 0.01, -0.02);
  const double q = grasped_q(c, s, X_GH, Eigen::Vector3d(0.1, 0, 0));
  // the twist of swing * twist about the axis: for a swing about z (perpendicular to x) and a
  // twist about x, the swing-twist decomposition returns the twist exactly
  EXPECT_NEAR(q, 0.7 + 30 * kDeg, 1e-12);
}

}  // namespace
}  // namespace vcockpit::physics

namespace vcockpit::physics {
namespace {

// A continuous heading knob with a click every 10 deg: its positions repeat with the detent, so
// turning it 100 deg one way clicks 10 times (click -> between -> click ... 20 changes, the
// last back to click), and turning it back gives the same changes in reverse order.
TEST(ControlModel, AContinuousKnobsPositionsRepeatWithItsDetent) {
  ControlSpec c;
  c.kind = ControlKind::kRotary;
  c.joint = JointKind::kRevolute;
  c.limited = false;
  c.detents = {{0.0, 0.01, 5 * kDeg}};
  c.detent_period = 10 * kDeg;
  c.positions = {{"click", 0.0, -2 * kDeg, 2 * kDeg}, {"between", 5 * kDeg, 3 * kDeg, 7 * kDeg}};
  ControlState s;
  std::vector<int> entered;
  auto turn_to = [&](double deg) {
    const double step = deg > s.q / kDeg ? 0.1 : -0.1;
    for (double q = s.q / kDeg; std::abs(q - deg) > 1e-9; q += step) {
      s.q = (std::abs(q + step - deg) < 1e-9 ? deg : q + step) * kDeg;
      if (update_position(c, s)) entered.push_back(s.position);
      if (std::abs(s.q / kDeg - deg) < 1e-9) break;
    }
  };
  turn_to(100.0);
  ASSERT_EQ(entered.size(), 20u);
  for (std::size_t i = 0; i < entered.size(); ++i) EXPECT_EQ(entered[i], i % 2 == 0 ? 1 : 0) << i;
  entered.clear();
  turn_to(-30.0);  // back through 0 and on: 13 clicks
  ASSERT_EQ(entered.size(), 26u);
  EXPECT_EQ(s.position, 0);
  // halfway between clicks, in neither interval, it keeps the position it had
  s.q = 2.5 * kDeg;
  EXPECT_FALSE(update_position(c, s));
}

}  // namespace
}  // namespace vcockpit::physics

namespace vcockpit::physics {
namespace {

// joint_motion_G carries the body from one coordinate to another: a lever's handle 12 cm above
// a pivot on a tilted axis turns round the pivot (which stays), its centroid moving by the chord
// 2 r sin(dq / 2); a prismatic body slides along the axis. The wrong way round (from q_to to
// q_from) fails the first check.
TEST(ControlModel, TheJointMotionTakesTheBodyFromOneCoordinateToAnother) {
  ControlSpec lever;
  lever.joint = JointKind::kRevolute;
  lever.X_GJ.linear() = Eigen::AngleAxisd(-kPi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix() *
                        Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  lever.X_GJ.translation() = Eigen::Vector3d(0.45, 0.33, 0.70);
  lever.X_JO.translation() = Eigen::Vector3d(0.0, -0.12, 0.0);
  const double q_from = -20 * kDeg, q_to = 25 * kDeg;
  const Eigen::Isometry3d X = joint_motion_G(lever, q_from, q_to);
  const Eigen::Isometry3d moved = X * control_body_pose(lever, q_from);
  const Eigen::Isometry3d there = control_body_pose(lever, q_to);
  EXPECT_TRUE(moved.isApprox(there, 1e-12)) << moved.matrix() << "\n" << there.matrix();
  EXPECT_TRUE((X * lever.X_GJ.translation()).isApprox(lever.X_GJ.translation(), 1e-12)) << "the pivot stays";
  const double chord_m = (there.translation() - control_body_pose(lever, q_from).translation()).norm();
  EXPECT_NEAR(chord_m, 2 * 0.12 * std::sin((q_to - q_from) / 2), 1e-12);
  EXPECT_TRUE(joint_motion_G(lever, q_to, q_from).isApprox(X.inverse(), 1e-12));

  ControlSpec slider = lever;
  slider.joint = JointKind::kPrismatic;
  const Eigen::Isometry3d S = joint_motion_G(slider, 0.01, 0.04);
  EXPECT_TRUE(S.linear().isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_TRUE(S.translation().isApprox(0.03 * joint_axis_G(slider), 1e-12)) << S.translation().transpose();
  EXPECT_TRUE((S * control_body_pose(slider, 0.01)).isApprox(control_body_pose(slider, 0.04), 1e-12));
}

}  // namespace
}  // namespace vcockpit::physics

namespace vcockpit::physics {
namespace {

// The panel's heading knob: 8 g on a 1 cm radius (4e-7 kg m^2), firm clicks every 10 deg (0.06 N m
// within 5 deg). Its stiffest detent rings at sqrt(k / M) = 2300 rad/s, past what one explicit
// step of 1 ms holds (omega h = 2.3): spun and let go, the step's held detent force pushed it on
// through clicks it had already passed, and it spun on by itself (a knob brushed by a fingertip
// clicked ten times in 26 ms). In its mechanism's own steps it loses energy to its damper from
// the first step and stops in a click.
ControlSpec heading_knob() {
  ControlSpec c;
  c.kind = ControlKind::kRotary;
  c.joint = JointKind::kRevolute;
  c.limited = false;
  c.damping = 1e-4;
  c.detents = {{0.0, 0.06, 5 * kDeg}};
  c.detent_period = 10 * kDeg;
  c.positions = {{"click", 0.0, -2 * kDeg, 2 * kDeg}, {"between", 5 * kDeg, 3 * kDeg, 7 * kDeg}};
  return c;
}

// Kinetic energy plus the click's potential (the integral of its restoring torque).
double knob_energy(const ControlSpec& c, double M, const ControlState& s) {
  const Detent& d = c.detents.front();
  const double x = std::remainder(s.q - d.q, c.detent_period);
  const double w = d.half_width;
  const double V = std::abs(x) < w ? d.strength * w / kPi * (1.0 - std::cos(kPi * x / w))
                                   : 2.0 * d.strength * w / kPi;
  return 0.5 * M * s.qd * s.qd + V;
}

TEST(ControlModel, ALightKnobSpunAndLetGoStopsInAClickWithoutGainingEnergy) {
  const ControlSpec c = heading_knob();
  const double M = 4e-7, dt = 1e-3;
  EXPECT_EQ(mechanism_steps(c, M, 0.0, dt), 5) << "omega h = 2.3 in steps of omega h <= 0.5";
  EXPECT_EQ(mechanism_steps(c, M, 100.0, dt), 5) << "100 rad/s is 1.3 quarter half-widths a step";
  EXPECT_EQ(mechanism_steps(c, M, 1000.0, dt), 32) << "at most kMaxMechanismSteps";
  ControlSpec bare = c;
  bare.detents.clear();
  EXPECT_EQ(mechanism_steps(bare, M, 1000.0, dt), 1) << "no detent: the spring is exact already";

  for (const double spin_radps : {60.0, 200.0, -300.0}) {
    ControlState s;
    s.qd = spin_radps;
    double energy = knob_energy(c, M, s);
    int clicks = 0;
    for (int k = 0; k < 300; ++k) {
      integrate_control(c, M, 0.0, dt, 0u, s);
      if (update_position(c, s)) ++clicks;
      const double now = knob_energy(c, M, s);
      ASSERT_LE(now, energy * (1.0 + 1e-9) + 1e-15) << spin_radps << " rad/s, step " << k;
      energy = now;
    }
    const double off_deg = std::remainder(s.q, c.detent_period) / kDeg;
    EXPECT_LT(std::abs(off_deg), 0.5) << spin_radps << " rad/s: at rest in a click";
    EXPECT_LT(std::abs(s.qd), 1e-3) << spin_radps << " rad/s";
    // its kinetic energy carries it over a few clicks at most (each a barrier of 2 S w / pi =
    // 3.3 mJ; 300 rad/s is 18 mJ), two position changes each
    EXPECT_LE(clicks, 2 * static_cast<int>(std::ceil(0.5 * M * spin_radps * spin_radps /
                                                       (2.0 * 0.06 * 5 * kDeg / kPi))) + 2)
        << spin_radps << " rad/s";
  }
}

}  // namespace
}  // namespace vcockpit::physics
