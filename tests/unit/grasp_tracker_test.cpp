// The grasp tracker's attach/release decision, driven step by step with stable-grasp test
// outcomes: attach (eq. 28), minimum hold, release delay, re-grab cooldown, glove lost, and the
// release velocity from the held poses (a throw's over 20 ms, a setting down's over 0.1 s).

#include "physics_node/physics/grasp_tracker.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <vector>

namespace vcockpit::physics {
namespace {

constexpr double kStep_s = 0.001;
constexpr int64_t kStep_ns = 1'000'000;
constexpr int kHand = 0;

// The paper's hold rule: the contact test, at its held thresholds, decides a release (the tests
// below drive it with its outcomes); the tracked grip's tests set kTrackedGrip.
GraspParams params() {
  GraspParams p;
  p.hold_rule = HoldRule::kContactTest;
  p.min_hold_s = 0.2;
  p.release_delay_s = 0.03;
  p.regrab_cooldown_s = 0.3;
  p.velocity_window_s = 0.02;
  return p;
}

GraspCheck holding() {
  GraspCheck c;
  c.links_in_contact = 4;
  c.thumb = true;
  c.min_thumb_angle_deg = 150.0;
  c.residual_force_N = 0.5;
  c.residual_torque_Nm = 0.01;
  c.verdict = GraspReason::kStableGrasp;
  return c;
}

GraspCheck failing(GraspReason why = GraspReason::kTooFewContacts) {
  GraspCheck c;
  c.links_in_contact = 1;
  c.thumb = false;
  c.min_thumb_angle_deg = 180.0;
  c.residual_force_N = 1.96;
  c.verdict = why;
  return c;
}

// One object and the hand, stepped the way the world does: decide, move a held object with the
// hand (eq. 29), record its pose.
struct Rig {
  GraspTracker tracker;
  ObjectSpec cup;
  GraspHold hold;
  BodyState body;
  std::vector<GraspEvent> events;
  int64_t t_ns = 0;
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  Eigen::Vector3d hand_v_G = Eigen::Vector3d::Zero();
  JointAngles glove_q_rad{};  // the tracked (glove) joints the decisions see
  double jitter_m = 0.0;
  Eigen::Vector3d jitter_G = Eigen::Vector3d::Zero();
  std::mt19937 rng{7};
  std::normal_distribution<double> noise{0.0, 1.0};

  explicit Rig(const GraspParams& p = params()) : tracker(p, kStep_s, {0.0, 0.0, -9.81}) {
    cup.dynamic = true;
    cup.mass_kg = 0.2;
    hold = tracker.initial_hold(cup);
    body.X_GO.translation() = Eigen::Vector3d(0.1, 0.0, 0.05);
  }

  // Steps until t_s, every step with the same test outcome; returns the events of those steps.
  // `jitter_m` (if set) adds a tracker's noise to the wrist: a new offset every 1/60 s.
  std::vector<GraspEvent> run_until(double t_s, const GraspCheck& check, bool tracking = true) {
    std::vector<GraspEvent> out;
    while (t_ns < std::llround(t_s * 1e9)) {
      t_ns += kStep_ns;
      X_GH.translation() += hand_v_G * kStep_s;
      if (jitter_m > 0.0 && t_ns % 16'000'000 == 0) {
        X_GH.translation() -= jitter_G;
        jitter_G = jitter_m * Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
        X_GH.translation() += jitter_G;
      }
      if (body.held_by == kHand) body.X_GO = X_GH * hold.X_HO;  // eq. 29
      events.clear();
      tracker.decide(0, check, HandNow{t_ns, tracking, X_GH, &glove_q_rad}, hold, body, events);
      if (body.held_by != kNotHeld) tracker.record_held_pose(hold, body);
      out.insert(out.end(), events.begin(), events.end());
    }
    return out;
  }
};

TEST(GraspTracker, StableTestAttachesWithTheHandFrameOfEq28) {
  Rig rig;
  rig.X_GH.translation() = Eigen::Vector3d(0.05, 0.0, 0.1);
  const auto events = rig.run_until(0.001, holding());
  ASSERT_EQ(events.size(), 1u);
  const GraspEvent& e = events[0];
  EXPECT_TRUE(e.grasp);
  EXPECT_EQ(e.object, 0);
  EXPECT_EQ(e.hand_id, kHand);
  EXPECT_EQ(e.t_ns, 1'000'000);
  EXPECT_EQ(e.reason, GraspReason::kStableGrasp);
  EXPECT_EQ(e.contacts, 4);
  EXPECT_TRUE(e.thumb_touching);
  EXPECT_DOUBLE_EQ(e.min_thumb_angle_deg, 150.0);
  EXPECT_DOUBLE_EQ(e.residual_force_N, 0.5);
  EXPECT_DOUBLE_EQ(e.residual_torque_Nm, 0.01);
  EXPECT_EQ(rig.body.held_by, kHand);
  EXPECT_TRUE(rig.hold.X_HO.translation().isApprox(Eigen::Vector3d(0.05, 0.0, -0.05), 1e-15));
  // holding on gives no more events
  EXPECT_TRUE(rig.run_until(1.0, holding()).empty());
}

TEST(GraspTracker, NoGraspWhileTheGloveIsLost) {
  Rig rig;
  EXPECT_TRUE(rig.run_until(0.1, holding(), /*tracking=*/false).empty());
  EXPECT_EQ(rig.body.held_by, kNotHeld);
}

TEST(GraspTracker, MinimumHoldKeepsAFailingGraspUntilItHasHeld200ms) {
  Rig rig;
  rig.run_until(0.001, holding());  // grasped at 1 ms
  const auto events = rig.run_until(1.0, failing());
  ASSERT_EQ(events.size(), 1u);
  EXPECT_FALSE(events[0].grasp);
  EXPECT_EQ(events[0].reason, GraspReason::kTooFewContacts);
  EXPECT_EQ(events[0].t_ns, 201'000'000) << "failing since 2 ms, but held only from 1 ms";
  EXPECT_EQ(events[0].contacts, 1);
  EXPECT_FALSE(events[0].thumb_touching);
  EXPECT_EQ(rig.body.held_by, kNotHeld);
}

TEST(GraspTracker, ReleaseWaitsForTheTestToFail30msInARow) {
  Rig rig;
  rig.run_until(0.001, holding());
  rig.run_until(0.5, holding());  // well past the minimum hold
  // failing for 20 ms, then holding once: the delay starts over
  EXPECT_TRUE(rig.run_until(0.520, failing()).empty());
  EXPECT_TRUE(rig.run_until(0.521, holding()).empty());
  EXPECT_TRUE(rig.run_until(0.551, failing()).empty()) << "failing since 522 ms: 29 ms";
  const auto events = rig.run_until(0.6, failing(GraspReason::kForceResidual));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].t_ns, 552'000'000) << "failing since 522 ms: released at 552 ms";
  EXPECT_EQ(events[0].reason, GraspReason::kForceResidual);
}

TEST(GraspTracker, CooldownBlocksARegrabFor300msAfterARelease) {
  Rig rig;
  rig.run_until(0.001, holding());
  rig.run_until(0.5, holding());
  const auto released = rig.run_until(0.6, failing());
  ASSERT_EQ(released.size(), 1u);
  const int64_t release_ns = released[0].t_ns;
  const auto regrabbed = rig.run_until(2.0, holding());
  ASSERT_FALSE(regrabbed.empty());
  EXPECT_TRUE(regrabbed[0].grasp);
  EXPECT_EQ(regrabbed[0].t_ns, release_ns + 300'000'000);
}

TEST(GraspTracker, LostGloveReleasesAtOnceEvenBeforeTheMinimumHold) {
  Rig rig;
  rig.run_until(0.001, holding());
  const auto events = rig.run_until(0.002, holding(), /*tracking=*/false);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_FALSE(events[0].grasp);
  EXPECT_EQ(events[0].reason, GraspReason::kGloveLost);
  EXPECT_EQ(events[0].t_ns, 2'000'000);
  EXPECT_EQ(rig.body.held_by, kNotHeld);
}

TEST(GraspTracker, ReleasedObjectLeavesWithTheHandsVelocity) {
  Rig rig;
  rig.run_until(0.001, holding());
  rig.hand_v_G = {0.5, 0.0, 0.2};  // m/s
  rig.run_until(0.3, holding());
  rig.run_until(0.4, failing());
  ASSERT_EQ(rig.body.held_by, kNotHeld);
  EXPECT_TRUE(rig.body.v_G.isApprox(rig.hand_v_G, 1e-9)) << rig.body.v_G.transpose();
  EXPECT_LT(rig.body.w_G.norm(), 1e-9);
}

// A still hand with a tracker's jitter (0.5 mm, 60 Hz) sets the object down: over 20 ms the
// jitter reads as a velocity of several cm/s, over the 0.1 s settle window it averages out.
TEST(GraspTracker, AnObjectSetDownByAJitteryStillHandLeavesNearlyAtRest) {
  auto release_speed = [](double settle_speed_mps) {
    GraspParams p = params();
    p.settle_speed_mps = settle_speed_mps;
    p.settle_window_s = 0.1;
    Rig rig(p);
    rig.jitter_m = 0.5e-3;
    rig.run_until(0.001, holding());
    rig.run_until(0.5, holding());
    rig.run_until(0.6, failing());
    EXPECT_EQ(rig.body.held_by, kNotHeld);
    return rig.body.v_G.norm();
  };
  const double settled = release_speed(0.15);
  const double raw = release_speed(0.0);  // off: the 20 ms window alone
  std::printf("release speed of a still hand with jitter: %.4f m/s (20 ms alone: %.4f)\n",
              settled, raw);
  EXPECT_LT(settled, 0.015);
  EXPECT_GT(raw, 2.0 * settled);
}

// A hand faster than settle_speed_mps over the settle window throws: the 20 ms velocity, so a
// throw that speeds up toward the release leaves at the speed it reached.
TEST(GraspTracker, AThrowLeavesWithTheLast20msVelocityNotTheSettleWindowsMean) {
  Rig rig;
  rig.run_until(0.001, holding());
  rig.run_until(0.3, holding());
  rig.hand_v_G = {0.3, 0.0, 0.0};
  rig.run_until(0.36, holding());
  rig.hand_v_G = {1.5, 0.0, 0.5};
  rig.run_until(0.4, holding());
  rig.run_until(0.5, failing());  // the hand keeps its speed through the release delay
  ASSERT_EQ(rig.body.held_by, kNotHeld);
  EXPECT_TRUE(rig.body.v_G.isApprox(rig.hand_v_G, 1e-9)) << rig.body.v_G.transpose();
}

TEST(GraspTracker, StaticObjectsAndUntouchedFreeOnesAreLeftAlone) {
  Rig rig;
  std::vector<GraspEvent> events;
  ObjectSpec panel;  // static
  GraspHold panel_hold = rig.tracker.initial_hold(panel);
  EXPECT_TRUE(panel_hold.history.empty());
  BodyState panel_body;
  rig.tracker.update(1, panel, nullptr, 0, HandNow{}, 0, panel_hold, panel_body, events);
  rig.tracker.update(0, rig.cup, nullptr, 0, HandNow{}, 0, rig.hold, rig.body, events);
  EXPECT_TRUE(events.empty());
  EXPECT_EQ(rig.body.held_by, kNotHeld);
}

// The glove opening releases a held object that the proxy's fingers still touch (the test holds
// on): when the gripping fingers' flexion, averaged, has fallen by release_opening_share (0.2) of
// what it was at the grasp, and by at least release_opening_deg (15). Closing tighter after the
// grasp does not move that mark: a squeeze relaxed back to the grip still holds. The thumb counts
// only when it grips alone: it opens by rotation and abduction, and a thumb curling further while
// the fingers open wide must not keep the hold.
TEST(GraspTracker, TheGloveOpeningReleasesWhatTheFingersStillTouch) {
  Rig rig;
  const auto set_flexion_deg = [&](double index_deg, double thumb_deg) {
    for (hand::Joint j : {hand::Joint::kIndexMcp, hand::Joint::kIndexPip, hand::Joint::kIndexDip})
      rig.glove_q_rad[static_cast<std::size_t>(j)] = index_deg / 3.0 * M_PI / 180.0;
    for (hand::Joint j : {hand::Joint::kThumbMcp, hand::Joint::kThumbIp})
      rig.glove_q_rad[static_cast<std::size_t>(j)] = thumb_deg / 2.0 * M_PI / 180.0;
  };
  GraspCheck grip = holding();
  grip.fingers = (1u << static_cast<int>(Finger::kThumb)) | (1u << static_cast<int>(Finger::kIndex));
  set_flexion_deg(120.0, 80.0);
  ASSERT_EQ(rig.run_until(0.01, grip).size(), 1u);  // GRASP: the mark is 0.2 x 120 = 24 deg
  set_flexion_deg(170.0, 90.0);                      // a squeeze
  EXPECT_TRUE(rig.run_until(0.3, grip).empty());
  set_flexion_deg(100.0, 60.0);                      // the index opened 20 deg: still held
  EXPECT_TRUE(rig.run_until(0.5, grip).empty());
  set_flexion_deg(97.0, 60.0);                       // 23 deg: not yet beyond
  EXPECT_TRUE(rig.run_until(0.6, grip).empty());
  set_flexion_deg(94.0, 130.0);                      // 26 deg, the thumb curled: let go after the
                                                     // release delay
  const auto events = rig.run_until(0.7, grip);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_FALSE(events[0].grasp);
  EXPECT_EQ(events[0].reason, GraspReason::kHandOpened);
  EXPECT_NEAR(static_cast<double>(events[0].t_ns) * 1e-9, 0.6 + 0.03, 1.5e-3);
  EXPECT_EQ(rig.body.held_by, kNotHeld);
}

// A pinch with nearly straight fingers has little flexion to lose: at least release_opening_deg
// of opening lets go, not the share alone (a tracker's jitter would).
TEST(GraspTracker, AStraightFingeredGripNeedsTheFloorOfOpening) {
  Rig rig;
  GraspCheck grip = holding();
  grip.fingers = 1u << static_cast<int>(Finger::kIndex);
  rig.glove_q_rad[static_cast<std::size_t>(hand::Joint::kIndexMcp)] = 20.0 * M_PI / 180.0;
  ASSERT_EQ(rig.run_until(0.01, grip).size(), 1u);  // the share would be 4 deg
  rig.glove_q_rad[static_cast<std::size_t>(hand::Joint::kIndexMcp)] = 8.0 * M_PI / 180.0;
  EXPECT_TRUE(rig.run_until(0.5, grip).empty()) << "12 deg of opening is under the floor";
  rig.glove_q_rad[static_cast<std::size_t>(hand::Joint::kIndexMcp)] = 4.0 * M_PI / 180.0;
  const auto events = rig.run_until(0.6, grip);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].reason, GraspReason::kHandOpened);
}

// A thumb gripping alone (with the palm, say) is the finger whose opening counts.
TEST(GraspTracker, AThumbGrippingAloneIsWatchedForOpening) {
  Rig rig;
  GraspCheck grip = holding();
  grip.fingers = 1u << static_cast<int>(Finger::kThumb);
  for (hand::Joint j : {hand::Joint::kThumbMcp, hand::Joint::kThumbIp})
    rig.glove_q_rad[static_cast<std::size_t>(j)] = 40.0 * M_PI / 180.0;
  ASSERT_EQ(rig.run_until(0.01, grip).size(), 1u);  // GRASP at 80 deg: the mark is 16 deg
  EXPECT_TRUE(rig.run_until(0.3, grip).empty());
  for (hand::Joint j : {hand::Joint::kThumbMcp, hand::Joint::kThumbIp})
    rig.glove_q_rad[static_cast<std::size_t>(j)] = 30.0 * M_PI / 180.0;  // opened 20 deg
  const auto events = rig.run_until(0.4, grip);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].reason, GraspReason::kHandOpened);
}

// ---- the tracked hand's grip (HoldRule::kTrackedGrip) ----------------------------------------

// One held object under the project's hold rule: each step the tracked hand's links near the
// object's surface (HandOnObject::tracked_links_near) and the contact test's outcome.
struct GripRig {
  GraspTracker tracker;
  ObjectSpec bar;
  GraspHold hold;
  BodyState body;
  std::vector<GraspEvent> events;
  int64_t t_ns = 0;
  JointAngles glove_q_rad{};
  bool tracking = true;

  GripRig() : tracker(grip_params(), kStep_s, {0.0, 0.0, -9.81}) {
    bar.dynamic = true;
    bar.mass_kg = 0.06;
    hold = tracker.initial_hold(bar);
  }
  static GraspParams grip_params() {
    GraspParams p = params();
    p.hold_rule = HoldRule::kTrackedGrip;
    return p;
  }
  static uint32_t links(std::initializer_list<Link> ls) {
    uint32_t bits = 0;
    for (Link l : ls) bits |= 1u << static_cast<int>(l);
    return bits;
  }
  std::vector<GraspEvent> run_until(double t_s, const GraspCheck& check, uint32_t near) {
    std::vector<GraspEvent> out;
    while (t_ns < std::llround(t_s * 1e9)) {
      t_ns += kStep_ns;
      events.clear();
      HandOnObject h{HandNow{t_ns, tracking, Eigen::Isometry3d::Identity(), &glove_q_rad},
                     nullptr, 0, 0, body.held(), near, &hold};
      tracker.decide(0, check, h, body, events);
      if (body.held()) tracker.record_held_pose(hold, body);
      out.insert(out.end(), events.begin(), events.end());
    }
    return out;
  }
};

// Thumb, index and middle opposed at the grasp, the ring finger wrapping (not opposed).
GraspCheck fist_grip() {
  GraspCheck c = holding();
  c.fingers = 0b01111;
  c.opposed_fingers = 0b00110;
  return c;
}

const uint32_t kWholeFist = GripRig::links({Link::kThumbDistal, Link::kIndexDistal,
                                            Link::kMiddleMiddle, Link::kRingDistal});

// Attached, the proxy's fingers keep closing onto an object that cannot move to balance them: the
// contact test fails on eq. 30 or the opposition angle, and the object stays held while the
// tracked hand still grips it.
TEST(GraspTrackerGrip, TheContactTestFailingDoesNotLetGoWhileTheTrackedHandGrips) {
  GripRig rig;
  ASSERT_EQ(rig.run_until(0.001, fist_grip(), kWholeFist).size(), 1u);
  EXPECT_EQ(rig.hold.opposed_fingers, 0b00110);
  EXPECT_FALSE(rig.hold.palm_opposed);
  EXPECT_TRUE(rig.run_until(0.5, failing(GraspReason::kForceResidual), kWholeFist).empty());
  EXPECT_TRUE(rig.run_until(1.0, failing(GraspReason::kFingersNotOpposed), kWholeFist).empty());
  // one opposed finger is enough to go on holding
  EXPECT_TRUE(rig.run_until(1.5, failing(), GripRig::links({Link::kThumbDistal, Link::kMiddleDistal}))
                  .empty());
  EXPECT_EQ(rig.body.held_by, kHand);
}

TEST(GraspTrackerGrip, TheThumbLeavingLetsGoAfterTheReleaseDelay) {
  GripRig rig;
  rig.run_until(0.5, fist_grip(), kWholeFist);
  const auto events = rig.run_until(
      0.6, holding(), GripRig::links({Link::kIndexDistal, Link::kMiddleMiddle, Link::kRingDistal}));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_FALSE(events[0].grasp);
  EXPECT_EQ(events[0].reason, GraspReason::kThumbLeft);
  EXPECT_EQ(events[0].t_ns, 531'000'000) << "failing since 501 ms: 30 ms later";
}

// A fist grasps while still closing and closes on past the grasp. When it opens, its thumb leaves
// the object before the flexion falls by a share of the grasp's: the reason is the hand opening
// once the glove has opened by release_opening_deg from its tightest, not before.
TEST(GraspTrackerGrip, TheThumbLeavingAsTheGloveOpensFromItsTightestIsTheHandOpening) {
  const auto set_fingers_rad = [](GripRig& rig, double mcp_rad) {
    for (hand::Joint j : {hand::Joint::kIndexMcp, hand::Joint::kMiddleMcp, hand::Joint::kRingMcp})
      rig.glove_q_rad[static_cast<std::size_t>(j)] = mcp_rad;
  };
  const uint32_t no_thumb =
      GripRig::links({Link::kIndexDistal, Link::kMiddleMiddle, Link::kRingDistal});
  for (const double opened_deg : {10.0, 20.0}) {
    SCOPED_TRACE(opened_deg);
    GripRig rig;
    set_fingers_rad(rig, 1.0);  // grasped at 57 deg
    ASSERT_EQ(rig.run_until(0.1, fist_grip(), kWholeFist).size(), 1u);
    set_fingers_rad(rig, 1.4);  // closes on to 80 deg
    EXPECT_TRUE(rig.run_until(0.5, holding(), kWholeFist).empty());
    // opens: still closer than at the grasp, so well short of the share of the grasp's flexion
    set_fingers_rad(rig, 1.4 - opened_deg * M_PI / 180.0);
    const auto events = rig.run_until(0.6, holding(), no_thumb);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].reason, opened_deg > 15.0 ? GraspReason::kHandOpened : GraspReason::kThumbLeft)
        << "release_opening_deg 15 from the tightest";
  }
}

// The wrapping ring finger was not opposed at the grasp: it alone does not keep the hold.
TEST(GraspTrackerGrip, EveryOpposedFingerLeavingLetsGo) {
  GripRig rig;
  rig.run_until(0.5, fist_grip(), kWholeFist);
  const auto events =
      rig.run_until(0.6, holding(), GripRig::links({Link::kThumbDistal, Link::kRingDistal}));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].reason, GraspReason::kFingersLeft);
}

// A power grasp: the palm opposed the fingers, so it is the palm that must stay.
TEST(GraspTrackerGrip, APalmGraspLetsGoWhenThePalmLeaves) {
  GripRig rig;
  GraspCheck power = fist_grip();
  power.palm_opposes = true;
  const uint32_t wrapped = GripRig::links({Link::kPalm, Link::kIndexMiddle, Link::kMiddleMiddle});
  rig.run_until(0.5, power, wrapped);
  EXPECT_TRUE(rig.hold.palm_opposed);
  EXPECT_TRUE(rig.run_until(0.6, holding(), wrapped).empty()) << "no thumb needed";
  const auto events =
      rig.run_until(0.7, holding(), GripRig::links({Link::kIndexMiddle, Link::kMiddleMiddle}));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].reason, GraspReason::kThumbLeft);
}

TEST(GraspTrackerGrip, TheGloveOpeningAndALostGloveStillLetGo) {
  GripRig rig;
  rig.glove_q_rad[static_cast<std::size_t>(hand::Joint::kIndexMcp)] = 1.5;
  rig.glove_q_rad[static_cast<std::size_t>(hand::Joint::kMiddleMcp)] = 1.5;
  rig.run_until(0.5, fist_grip(), kWholeFist);
  rig.glove_q_rad[static_cast<std::size_t>(hand::Joint::kIndexMcp)] = 0.0;
  rig.glove_q_rad[static_cast<std::size_t>(hand::Joint::kMiddleMcp)] = 0.0;
  auto events = rig.run_until(0.6, holding(), kWholeFist);  // the proxy's links still inside
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].reason, GraspReason::kHandOpened);

  GripRig lost;
  lost.run_until(0.01, fist_grip(), kWholeFist);
  lost.tracking = false;
  events = lost.run_until(0.011, holding(), kWholeFist);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].reason, GraspReason::kGloveLost);
  EXPECT_EQ(events[0].t_ns, 11'000'000) << "at once, before the minimum hold";
}

// The links that touched an object when it was let go stand off it until the regrab cooldown
// ends (GraspHold::resting_links; the proxy reads them), whatever touches it afterwards.
TEST(GraspTracker, TheLinksThatLetGoAreNamedUntilTheCooldownEnds) {
  GraspTracker tracker(params(), kStep_s, {0.0, 0.0, -9.81});
  ObjectSpec cup;
  cup.dynamic = true;
  cup.mass_kg = 0.2;
  GraspHold hold = tracker.initial_hold(cup);
  BodyState body;
  const Eigen::Vector3d c_G(0.1, 0.0, 0.05);
  body.X_GO.translation() = c_G;
  // thumb behind, index and middle in front, squeezing along x (|sum F| = the weight, 1.96 N)
  const auto contact = [&](Link link, double x, double y, double F_x) {
    HandContact c;
    c.link = link;
    c.p_G = c_G + Eigen::Vector3d(x, y, 0.0);
    c.n_G = Eigen::Vector3d(F_x > 0 ? 1.0 : -1.0, 0.0, 0.0);
    c.F_G = Eigen::Vector3d(F_x, 0.0, 0.0);
    return c;
  };
  const std::vector<HandContact> grip = {contact(Link::kThumbDistal, -0.03, 0.0, 2.0),
                                         contact(Link::kIndexDistal, 0.03, 0.01, -1.0),
                                         contact(Link::kMiddleDistal, 0.03, -0.01, -1.0)};
  const std::vector<HandContact> thumb_only = {grip[0]};
  const JointAngles glove{};
  std::vector<GraspEvent> events;
  int64_t t_ns = 0;
  // glove_inside: the glove's links that overlap the cup (the world finds them with FCL)
  const auto run_until = [&](double t_s, const std::vector<HandContact>& contacts,
                             uint32_t glove_inside = 0) {
    while (t_ns < std::llround(t_s * 1e9)) {
      t_ns += kStep_ns;
      tracker.update(0, cup, contacts.data(), contacts.size(),
                     HandNow{t_ns, true, Eigen::Isometry3d::Identity(), &glove}, glove_inside,
                     hold, body, events);
    }
  };
  const uint32_t thumb_bit = 1u << static_cast<int>(Link::kThumbDistal);
  run_until(0.3, grip);
  ASSERT_EQ(body.held_by, kHand);
  EXPECT_EQ(hold.resting_links, 0u);
  run_until(0.4, thumb_only);  // too few contacts: let go after the release delay
  ASSERT_EQ(body.held_by, kNotHeld);
  ASSERT_EQ(events.size(), 2u);
  const int64_t released_ns = events[1].t_ns;
  EXPECT_EQ(hold.resting_links, 1u << static_cast<int>(Link::kThumbDistal));
  run_until(static_cast<double>(released_ns) * 1e-9 + 0.29, grip);  // back on it: no grasp yet
  EXPECT_EQ(hold.resting_links, thumb_bit);
  EXPECT_EQ(events.size(), 2u);
  run_until(static_cast<double>(released_ns) * 1e-9 + 0.31, grip);  // the cooldown is over
  EXPECT_EQ(hold.resting_links, 0u);
  EXPECT_EQ(events.size(), 3u);  // grasped again
  EXPECT_TRUE(events[2].grasp);
}

// A glove that opened to let go, its thumb swinging back through the ball: the thumb's proxy
// rests off the ball after the cooldown until the glove's thumb is out of it. Within the
// cooldown any link the glove moves through it rests off it too. A glove still
// closed (the grip loosened by itself): the links rest only for the cooldown, so the same grip
// can take the ball again.
TEST(GraspTracker, ALinkStaysRestingWhileTheGlovesLinkIsStillInTheObject) {
  for (const bool glove_open : {true, false}) {
    SCOPED_TRACE(glove_open ? "the glove opened" : "the glove still closed");
  GraspTracker tracker{GraspParams{}, kStep_s, {0.0, 0.0, -9.81}};
  ObjectSpec ball;
  ball.dynamic = true;
  ball.mass_kg = 0.06;
  GraspHold hold = tracker.initial_hold(ball);
  BodyState body;
  hold.resting_links = (1u << static_cast<int>(Link::kThumbDistal)) |
                       (1u << static_cast<int>(Link::kIndexDistal));
  hold.released_at_ns = 0;
  hold.hand_clearing = true;
  // the index and middle gripped, curled 1.5 rad at their tightest; the glove now flat (open)
  // or still curled so (closed)
  hold.grip_fingers = (1u << static_cast<int>(Finger::kIndex)) |
                      (1u << static_cast<int>(Finger::kMiddle));
  JointAngles glove{};
  for (const Finger f : {Finger::kIndex, Finger::kMiddle})
    hold.grip_flexion_rad[static_cast<std::size_t>(f)] = 1.5;
  if (!glove_open) {
    glove[static_cast<std::size_t>(hand::Joint::kIndexPip)] = 1.5;
    glove[static_cast<std::size_t>(hand::Joint::kMiddlePip)] = 1.5;
  }
  ASSERT_NEAR(finger_flexion_rad(glove, Finger::kIndex), glove_open ? 0.0 : 1.5, 1e-12);
  std::vector<GraspEvent> events;
  const auto at = [&](double t_s, uint32_t glove_inside) {
    tracker.update(0, ball, nullptr, 0,
                   HandNow{std::llround(t_s * 1e9), true, Eigen::Isometry3d::Identity(), &glove},
                   glove_inside, hold, body, events);
  };
  const uint32_t thumb_bit = 1u << static_cast<int>(Link::kThumbDistal);
  at(0.1, 0);  // within the cooldown: both rest, whatever the glove does
  EXPECT_EQ(hold.resting_links, thumb_bit | (1u << static_cast<int>(Link::kIndexDistal)));
  // the glove's middle finger passes through the ball: it rests off it too
  const uint32_t middle_bit = 1u << static_cast<int>(Link::kMiddleMiddle);
  at(0.2, middle_bit);
  EXPECT_EQ(hold.resting_links,
            thumb_bit | (1u << static_cast<int>(Link::kIndexDistal)) | middle_bit);
  at(0.4, thumb_bit);  // after it: the index is out, the glove's thumb is still in the ball
  EXPECT_EQ(hold.resting_links, glove_open ? thumb_bit : 0u);
  at(0.6, thumb_bit);
  EXPECT_EQ(hold.resting_links, glove_open ? thumb_bit : 0u);
  at(0.7, 0);  // the thumb is out too
  EXPECT_EQ(hold.resting_links, 0u);
  at(0.8, thumb_bit);  // back in: it is an ordinary link again, and may push the ball
  EXPECT_EQ(hold.resting_links, 0u);
  EXPECT_TRUE(events.empty());
  }
}

}  // namespace
}  // namespace vcockpit::physics

// ---- two hands (GraspTracker::update_hands) ----------------------------------------------------

namespace vcockpit::physics {
namespace {
namespace two_hands {

// A pinch about the object's centroid: the thumb pushing +x, two fingers -x, each also lifting
// with `lift_N` / 3 (the friction that carries the object); its sum is 3 x lift_N / 3 up.
std::vector<HandContact> pinch(const Eigen::Vector3d& centre_G, double side_y_m, double lift_N) {
  std::vector<HandContact> c(3);
  const double up = lift_N / 3.0;
  c[0].link = Link::kThumbDistal;
  c[0].p_G = centre_G + Eigen::Vector3d(-0.03, side_y_m, 0.0);
  c[0].n_G = Eigen::Vector3d::UnitX();
  c[0].F_G = Eigen::Vector3d(4.0, 0.0, up);
  c[1].link = Link::kIndexDistal;
  c[1].p_G = centre_G + Eigen::Vector3d(0.03, side_y_m + 0.01, 0.0);
  c[1].n_G = -Eigen::Vector3d::UnitX();
  c[1].F_G = Eigen::Vector3d(-2.0, 0.0, up);
  c[2].link = Link::kMiddleDistal;
  c[2].p_G = centre_G + Eigen::Vector3d(0.03, side_y_m - 0.01, 0.0);
  c[2].n_G = -Eigen::Vector3d::UnitX();
  c[2].F_G = Eigen::Vector3d(-2.0, 0.0, up);
  return c;
}

// The project's hold rule: a hand lets go when its tracked grip leaves (the rig's gloves are near
// the object where they touch it).
GraspParams two_hand_params() {
  GraspParams p = params();
  p.hold_rule = HoldRule::kTrackedGrip;
  return p;
}

struct TwoHandRig {
  GraspTracker tracker;
  ObjectSpec box;
  BodyState body;
  std::array<GraspHold, 2> holds;
  std::vector<GraspEvent> events;
  int64_t t_ns = 0;
  std::array<bool, 2> tracking{true, true};
  std::array<JointAngles, 2> glove_q{};

  explicit TwoHandRig(double mass_kg, const GraspParams& params = two_hand_params())
      : tracker(params, kStep_s, {0.0, 0.0, -9.81}) {
    box.dynamic = true;
    box.mass_kg = mass_kg;
    for (auto& h : holds) h = tracker.initial_hold(box);
  }
  // one step with each hand's contacts (the right's pinch on the box's -y end, the left's on +y)
  void step(const std::vector<HandContact>& right, const std::vector<HandContact>& left) {
    t_ns += 1'000'000;
    std::array<HandOnObject, 2> on{};
    const std::array<const std::vector<HandContact>*, 2> contacts{&right, &left};
    for (int h = 0; h < 2; ++h) {
      on[h].hand = HandNow{t_ns, tracking[h], Eigen::Isometry3d::Identity(), &glove_q[h], h,
                           static_cast<uint8_t>(1u << h)};
      on[h].contacts = contacts[h]->data();
      on[h].count = contacts[h]->size();
      on[h].hold = &holds[h];
      // a glove closed on it has its links inside it (where the proxy's rest on its surface)
      for (const HandContact& c : *contacts[h]) on[h].glove_links_inside |= 1u << static_cast<int>(c.link);
      // ... and so near its surface (the tracked grip, for the project's hold rule)
      on[h].grip_known = (body.holders & (1u << h)) != 0;
      on[h].tracked_links_near = on[h].glove_links_inside;
    }
    tracker.update_hands(0, box, on.data(), on.size(), body, events);
    for (int h = 0; h < 2; ++h)
      if ((body.holders & (1u << h)) != 0) tracker.record_held_pose(holds[h], body);
  }
  std::string text() const {
    std::string t;
    for (const GraspEvent& e : events)
      t += std::string(e.grasp ? "grasp " : "release ") + (e.hand_id == 0 ? "right" : "left") +
           " (" + grasp_reason_name(e.reason) + ")" +
           (e.other_hand_id >= 0 ? std::string(" with ") + (e.other_hand_id == 0 ? "right" : "left") : "") +
           "\n";
    return t;
  }
};

const Eigen::Vector3d kCentre = Eigen::Vector3d::Zero();

TEST(GraspTrackerTwoHands, AHeavyBoxIsHeldByBothHandsTogetherNotByOneAlone) {
  TwoHandRig rig(3.0);  // 29.4 N
  const double weight_N = 3.0 * 9.81;
  // one hand alone carrying half the weight: its own test fails on eq. 30, nothing is taken
  for (int i = 0; i < 10; ++i) rig.step(pinch(kCentre, -0.15, weight_N / 2), {});
  EXPECT_EQ(rig.body.holders, 0u);
  EXPECT_TRUE(rig.events.empty());
  // both hands, each with its own gesture, carrying it together: held by both
  rig.step(pinch(kCentre, -0.15, weight_N / 2), pinch(kCentre, 0.15, weight_N / 2));
  EXPECT_EQ(rig.body.holders, 3u);
  EXPECT_EQ(rig.text(), "grasp right (stable grasp) with left\ngrasp left (stable grasp) with right\n");
  // the left glove is lost: the left lets go at once, and the right alone cannot carry 29 N
  for (int i = 0; i < 300; ++i)
    rig.step(pinch(kCentre, -0.15, weight_N / 2), pinch(kCentre, 0.15, weight_N / 2));
  rig.events.clear();
  rig.tracking[1] = false;
  rig.step(pinch(kCentre, -0.15, weight_N / 2), pinch(kCentre, 0.15, weight_N / 2));
  EXPECT_EQ(rig.body.holders, 0u);
  EXPECT_EQ(rig.text(),
            "release left (glove lost) with right\nrelease right (force residual too large) with left\n");
}

// A two-link pinch: the thumb and one finger across the object (a glove whose index and middle
// fingers fall short of a bar and only the ring finger reaches it).
std::vector<HandContact> two_link_pinch(double side_y_m, double lift_N) {
  std::vector<HandContact> c = pinch(kCentre, side_y_m, 0.0);
  c.pop_back();
  c[1].link = Link::kRingDistal;
  c[0].F_G = Eigen::Vector3d(4.0, 0.0, lift_N / 2);
  c[1].F_G = Eigen::Vector3d(-4.0, 0.0, lift_N / 2);
  return c;
}

// The gesture constraint's "more than 2 contact points" is the object's: two hands that each
// pinch it (thumb and an opposed finger) hold it with four. One such pinch alone, or two hands
// of which one does not oppose its thumb, do not.
TEST(GraspTrackerTwoHands, TwoTwoLinkPinchesMakeAGraspOfFourContactPoints) {
  const double weight_N = 2.5 * 9.81;
  {
    TwoHandRig rig(2.5);
    for (int i = 0; i < 5; ++i) rig.step(two_link_pinch(-0.15, weight_N / 2), {});
    EXPECT_EQ(rig.body.holders, 0u) << "one pinch is 2 contact points: " << rig.text();
    rig.step(two_link_pinch(-0.15, weight_N / 2), two_link_pinch(0.15, weight_N / 2));
    EXPECT_EQ(rig.body.holders, 3u);
    EXPECT_EQ(rig.text(), "grasp right (stable grasp) with left\ngrasp left (stable grasp) with right\n");
  }
  {
    TwoHandRig rig(2.5);
    std::vector<HandContact> unopposed = two_link_pinch(0.15, weight_N / 2);
    unopposed[1].n_G = Eigen::Vector3d::UnitZ();  // 90 deg from the thumb's: not beyond alpha0
    for (int i = 0; i < 5; ++i) rig.step(two_link_pinch(-0.15, weight_N / 2), unopposed);
    EXPECT_EQ(rig.body.holders, 0u) << rig.text();
  }
}

// A squeeze about the object's centroid that carries nothing yet (the panel under it does): the
// thumb pushing +x with `squeeze_N`, two fingers -x with half of it each, and the palm on top
// pressing down with `press_N`.
std::vector<HandContact> resting_squeeze(double side_y_m, double squeeze_N, double press_N) {
  std::vector<HandContact> c = pinch(kCentre, side_y_m, 0.0);
  c[0].F_G = Eigen::Vector3d(squeeze_N, 0.0, 0.0);
  c[1].F_G = Eigen::Vector3d(-squeeze_N / 2, 0.0, 0.0);
  c[2].F_G = Eigen::Vector3d(-squeeze_N / 2, 0.0, 0.0);
  HandContact palm;
  palm.link = Link::kPalm;
  palm.p_G = Eigen::Vector3d(0.0, side_y_m, 0.018);
  palm.n_G = -Eigen::Vector3d::UnitZ();
  palm.F_G = Eigen::Vector3d(0.0, 0.0, -press_N);
  c.push_back(palm);
  return c;
}

TEST(GraspTrackerTwoHands, TwoHandsSqueezingARestingHeavyBarTakeItWhenTheirFrictionCarriesIt) {
  // 2.5 kg (24.5 N) resting on a panel, both palms pressing 6 N on top: the hands' forces sum to
  // 36.5 N down with the weight. Their squeezes' static friction (mu = sqrt(1.0 x 0.8) = 0.89)
  // across it can take up 0.89 x 4 x squeeze: 48 N for 12 N squeezes, 11 N for 3 N ones.
  {
    TwoHandRig rig(2.5);
    rig.box.material.mu_s = 0.8;
    for (int i = 0; i < 5; ++i) rig.step(resting_squeeze(-0.15, 3.0, 6.0), resting_squeeze(0.15, 3.0, 6.0));
    EXPECT_EQ(rig.body.holders, 0u) << "a light touch does not carry 24.5 N: " << rig.text();
    rig.step(resting_squeeze(-0.15, 12.0, 6.0), resting_squeeze(0.15, 12.0, 6.0));
    EXPECT_EQ(rig.body.holders, 3u);
    EXPECT_EQ(rig.text(), "grasp right (stable grasp) with left\ngrasp left (stable grasp) with right\n");
  }
  // palms and fingers pressing from above with no squeeze across it: nothing to carry it with
  {
    TwoHandRig rig(2.5);
    rig.box.material.mu_s = 0.8;
    for (int i = 0; i < 5; ++i) rig.step(resting_squeeze(-0.15, 0.0, 20.0), resting_squeeze(0.15, 0.0, 20.0));
    EXPECT_EQ(rig.body.holders, 0u) << rig.text();
  }
}

// Both hands take the box, each carrying half its weight, and carry it 0.3 s.
void carry_together(TwoHandRig& rig, double weight_N) {
  rig.step(pinch(kCentre, -0.15, weight_N / 2), pinch(kCentre, 0.15, weight_N / 2));
  ASSERT_EQ(rig.body.holders, 3u);
  for (int i = 0; i < 300; ++i)
    rig.step(pinch(kCentre, -0.15, weight_N / 2), pinch(kCentre, 0.15, weight_N / 2));
  rig.events.clear();
}

// Set down and pressed into the panel for 0.2 s: the hands' forces no longer balance it.
void press_into_the_panel(TwoHandRig& rig) {
  for (int i = 0; i < 200; ++i)
    rig.step(resting_squeeze(-0.15, 2.0, 8.0), resting_squeeze(0.15, 2.0, 8.0));
}

TEST(GraspTrackerTwoHands, HeldByTwoTrackedGripsTheResidualsDoNotLetGo) {
  const double weight_N = 2.5 * 9.81;
  TwoHandRig rig(2.5);
  ASSERT_NO_FATAL_FAILURE(carry_together(rig, weight_N));
  // both tracked grips are still round it, so it stays held (issue: only the grip lets go)
  press_into_the_panel(rig);
  EXPECT_EQ(rig.body.holders, 3u) << rig.text();
  EXPECT_TRUE(rig.events.empty()) << rig.text();
  // under the paper's rule (eqs. 30-31 decide while held) the same lets go
  GraspParams p = two_hand_params();
  p.hold_rule = HoldRule::kContactTest;
  TwoHandRig paper(2.5, p);
  ASSERT_NO_FATAL_FAILURE(carry_together(paper, weight_N));
  press_into_the_panel(paper);
  EXPECT_EQ(paper.body.holders, 0u) << paper.text();
}

TEST(GraspTrackerTwoHands, WhenOneHandLetsGoTheOtherKeepsWhatItCanCarryAlone) {
  TwoHandRig rig(3.0);
  const double weight_N = 3.0 * 9.81;
  ASSERT_NO_FATAL_FAILURE(carry_together(rig, weight_N));
  // the left hand takes its fingers off while the right now carries the whole weight (its grip
  // shifted to the middle: held by one end, the box's weight would twist out of it, eq. 31)
  for (int i = 0; i < 50; ++i) rig.step(pinch(kCentre, 0.0, weight_N), {});
  EXPECT_EQ(rig.body.holders, 1u);
  EXPECT_EQ(rig.body.held_by, 0) << "the world names the holder; the tracker keeps it in step";
  EXPECT_EQ(rig.text(), "release left (thumb left the object) with right\n");
}

TEST(GraspTrackerTwoHands, ALightObjectGoesToTheOtherHandOnceAndNotBack) {
  TwoHandRig rig(0.2);
  rig.step(pinch(kCentre, 0.0, 1.96), {});
  ASSERT_EQ(rig.body.holders, 1u);
  for (int i = 0; i < 100; ++i) rig.step(pinch(kCentre, 0.0, 1.96), {});
  // the left closes its own grip round it: it is the left's in the same step
  rig.step(pinch(kCentre, 0.0, 0.0), pinch(kCentre, 0.0, 1.96));
  EXPECT_EQ(rig.body.holders, 2u);
  EXPECT_EQ(rig.text(), "grasp right (stable grasp)\nrelease right (handed over) with left\n"
                        "grasp left (stable grasp) with right\n");
  // the right's grip lingers past the cooldown: it does not take it back
  for (int i = 0; i < 600; ++i) rig.step(pinch(kCentre, 0.0, 1.0), pinch(kCentre, 0.0, 1.96));
  EXPECT_EQ(rig.body.holders, 2u);
  EXPECT_EQ(rig.events.size(), 3u);
}

}  // namespace two_hands
}  // namespace
}  // namespace vcockpit::physics
