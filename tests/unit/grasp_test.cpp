// The stable-grasp rule (paper §4.4): gesture (more than 2 links, the thumb, thumb-finger normal
// angles above alpha0), in the project's reading and the paper's literal one, and equilibrium
// (eqs. 30-31).

#include <gtest/gtest.h>

#include <vector>

#include "physics_node/physics/grasp.hpp"

namespace vcockpit::physics {
namespace {

const Eigen::Vector3d kCentroid(0, 0, 0);
const Eigen::Vector3d kGravity(0, 0, -9.81);
constexpr double kMass = 0.2;  // weight 1.962 N

// A contact at p pressing with `normal_N` along n (into the object) plus `lift_N` upward.
HandContact touch(Link link, Eigen::Vector3d p, Eigen::Vector3d n, double normal_N, double lift_N) {
  HandContact c;
  c.link = link;
  c.p_G = p;
  c.n_G = n.normalized();
  c.F_G = normal_N * c.n_G + Eigen::Vector3d(0, 0, lift_N);
  return c;
}

GraspCheck check(const std::vector<HandContact>& contacts, bool held = false,
                 GestureRule rule = GestureRule::kProject) {
  GraspParams params;
  params.gesture_rule = rule;
  return evaluate_grasp(contacts.data(), contacts.size(), kCentroid, kMass, kGravity, params, held);
}

// Thumb on -x pressing +x; index and middle on +x pressing -x; friction carries the weight.
std::vector<HandContact> balanced_three_point() {
  const double w = kMass * 9.81;
  return {touch(Link::kThumbDistal, {-0.04, 0, 0}, {1, 0, 0}, 4.0, w / 2),
          touch(Link::kIndexDistal, {0.04, 0, 0.01}, {-1, 0, 0}, 2.0, w / 4),
          touch(Link::kMiddleDistal, {0.04, 0, -0.01}, {-1, 0, 0}, 2.0, w / 4)};
}

TEST(GraspRule, BalancedThreePointGraspWithTheThumbHolds) {
  const GraspCheck c = check(balanced_three_point());
  EXPECT_EQ(c.verdict, GraspReason::kStableGrasp) << grasp_reason_name(c.verdict);
  EXPECT_EQ(c.links_in_contact, 3);
  EXPECT_TRUE(c.thumb);
  EXPECT_NEAR(c.min_thumb_angle_deg, 180.0, 1e-9);
  EXPECT_NEAR(c.residual_force_N, 0.0, 1e-12);
  EXPECT_NEAR(c.residual_torque_Nm, 0.0, 1e-12);
}

TEST(GraspRule, TwoContactsAreNoGrasp) {
  auto contacts = balanced_three_point();
  contacts.pop_back();
  EXPECT_EQ(check(contacts).verdict, GraspReason::kTooFewContacts);
}

TEST(GraspRule, AHeldObjectStaysHeldByAnOpposedPinchButNotByOneLink) {
  // thumb and index opposed, carrying the weight: no grasp, but it goes on holding (exit_min_contacts)
  const double w = kMass * 9.81;
  const std::vector<HandContact> pinch = {
      touch(Link::kThumbDistal, {-0.04, 0, 0}, {1, 0, 0}, 3.0, w / 2),
      touch(Link::kIndexDistal, {0.04, 0, 0}, {-1, 0, 0}, 3.0, w / 2)};
  EXPECT_EQ(check(pinch).verdict, GraspReason::kTooFewContacts);
  EXPECT_EQ(check(pinch, /*held=*/true).verdict, GraspReason::kStableGrasp);
  // the thumb alone does not hold
  const std::vector<HandContact> thumb = {pinch[0]};
  EXPECT_EQ(check(thumb, /*held=*/true).verdict, GraspReason::kTooFewContacts);
  // and a pinch that does not carry the weight lets go (eq. 30 at the held scale)
  std::vector<HandContact> slipping = pinch;
  for (auto& c : slipping) c.F_G.z() = 0.0;
  slipping[0].F_G.z() -= 15.0;  // |sum F| 17 N, above exit_scale * xi (12 N)
  EXPECT_EQ(check(slipping, /*held=*/true).verdict, GraspReason::kForceResidual);
}

TEST(GraspRule, SeveralPointsOnOneLinkCountOnce) {
  auto contacts = balanced_three_point();
  contacts[2].link = Link::kIndexDistal;  // two points on the index tip
  EXPECT_EQ(check(contacts).verdict, GraspReason::kTooFewContacts);
}

TEST(GraspRule, NoThumbIsNoGrasp) {
  auto contacts = balanced_three_point();
  contacts[0].link = Link::kRingDistal;
  EXPECT_EQ(check(contacts).verdict, GraspReason::kNoThumb);
}

// A power grasp: the fingers wrap the object against the palm, the thumb elsewhere. The palm's
// normal stands for the thumb's (alpha0 applies to it), unless palm_opposition is off.
TEST(GraspRule, ThePalmOpposesTheFingersWhenTheThumbIsOff) {
  auto contacts = balanced_three_point();
  contacts[0].link = Link::kPalm;
  GraspCheck c = check(contacts);
  EXPECT_EQ(c.verdict, GraspReason::kStableGrasp) << grasp_reason_name(c.verdict);
  EXPECT_FALSE(c.thumb);
  EXPECT_TRUE(c.palm_opposes);
  EXPECT_NEAR(c.min_thumb_angle_deg, 180.0, 1e-9);
  EXPECT_EQ(c.opposed_fingers, 0b00110);
  // a finger beside the palm, not opposite it: the paper's reading vetoes; the project's does
  // not count it, which leaves the palm and one finger (two links, no grasp)
  const double a = 100.0 * M_PI / 180.0;
  contacts[2] = touch(Link::kMiddleDistal, {0, 0.04, 0}, {std::cos(a), std::sin(a), 0}, 2.0, 0.5);
  EXPECT_EQ(check(contacts, false, GestureRule::kPaper).verdict, GraspReason::kFingersNotOpposed);
  EXPECT_EQ(check(contacts).verdict, GraspReason::kTooFewContacts);
  // with the thumb on as well and opposing, the thumb is the opposer
  contacts = balanced_three_point();
  contacts.push_back(touch(Link::kPalm, {0, 0, 0.04}, {0, 0, -1}, 0.0, 0.0));
  c = check(contacts);
  EXPECT_TRUE(c.thumb);
  EXPECT_FALSE(c.palm_opposes);
  EXPECT_EQ(c.verdict, GraspReason::kStableGrasp);
  // palm opposition off: the paper's rule, the thumb or nothing
  contacts = balanced_three_point();
  contacts[0].link = Link::kPalm;
  GraspParams paper;
  paper.palm_opposition = false;
  EXPECT_EQ(evaluate_grasp(contacts.data(), contacts.size(), kCentroid, kMass, kGravity, paper,
                           false)
                .verdict,
            GraspReason::kNoThumb);
}

TEST(GraspRule, ThumbFingerAngleUnderAlpha0IsNoGrasp) {
  auto contacts = balanced_three_point();
  // the middle finger presses at 100 deg from the thumb's normal (alpha0 is 120)
  const double a = 100.0 * M_PI / 180.0;
  contacts[2] = touch(Link::kMiddleDistal, {0, 0.04, 0}, {std::cos(a), std::sin(a), 0}, 2.0, 0.5);
  const GraspCheck c = check(contacts, false, GestureRule::kPaper);
  EXPECT_EQ(c.verdict, GraspReason::kFingersNotOpposed);
  EXPECT_NEAR(c.min_thumb_angle_deg, 100.0, 1e-6);
  // the project's reading: the middle finger does not count, leaving two links
  EXPECT_EQ(check(contacts).verdict, GraspReason::kTooFewContacts);
  EXPECT_EQ(check(contacts).opposed_fingers, 0b00010);
}

// A real fist round a 3 cm bar: thumb, index and middle opposed, the ring finger wrapping round
// at 105 deg from the thumb. The paper's literal reading refuses the grasp; the project's counts
// the opposed fingers and lets the ring finger neither count nor veto.
TEST(GraspRule, AWrappingFingerNeitherCountsNorVetoesInTheProjectsReading) {
  auto contacts = balanced_three_point();
  const double a = 105.0 * M_PI / 180.0;
  contacts.push_back(touch(Link::kRingDistal, {0, 0.04, 0}, {std::cos(a), std::sin(a), 0}, 0.5, 0.0));
  // (its 0.5 N along its normal, balanced by the thumb's)
  contacts[0].F_G += 0.5 * Eigen::Vector3d(-std::cos(a), -std::sin(a), 0);
  const GraspCheck project = check(contacts);
  EXPECT_EQ(project.verdict, GraspReason::kStableGrasp) << grasp_reason_name(project.verdict);
  EXPECT_EQ(project.links_in_contact, 4);
  EXPECT_EQ(project.opposed_fingers, 0b00110);  // index, middle
  EXPECT_NEAR(project.min_thumb_angle_deg, 180.0, 1e-9);
  const GraspCheck paper = check(contacts, false, GestureRule::kPaper);
  EXPECT_EQ(paper.verdict, GraspReason::kFingersNotOpposed);
  EXPECT_NEAR(paper.min_thumb_angle_deg, 105.0, 1e-6);
}

// A power grasp whose thumb lies on the fingers: in the project's reading the palm, which
// opposes more links than the thumb, is the opposer.
TEST(GraspRule, TheProjectsReadingTakesThePalmWhenItOpposesMoreThanTheThumb) {
  const double w = kMass * 9.81;
  const std::vector<HandContact> contacts = {
      touch(Link::kPalm, {-0.04, 0, 0}, {1, 0, 0}, 4.0, w / 2),
      touch(Link::kIndexMiddle, {0.04, 0, 0.01}, {-1, 0, 0}, 2.0, w / 4),
      touch(Link::kMiddleMiddle, {0.04, 0, -0.01}, {-1, 0, 0}, 2.0, w / 4),
      // the thumb across the fingers' backs, along them: not opposed to them
      touch(Link::kThumbDistal, {0.0, 0.04, 0}, {0, -1, 0}, 0.0, 0.0)};
  const GraspCheck c = check(contacts);
  EXPECT_EQ(c.verdict, GraspReason::kStableGrasp) << grasp_reason_name(c.verdict);
  EXPECT_TRUE(c.thumb);
  EXPECT_TRUE(c.palm_opposes);
  EXPECT_EQ(c.opposed_fingers, 0b00110);
  // the paper's reading asks the thumb, which opposes no finger
  EXPECT_EQ(check(contacts, false, GestureRule::kPaper).verdict, GraspReason::kFingersNotOpposed);
}

// Without the gesture rule (GraspParams::gesture_rule kNone) eqs. 30-31 alone decide: a palm
// under the object carrying its weight grasps it, as does a thumb-less pair in equilibrium, but
// no contact, or an unbalanced one, does not.
TEST(GraspRule, WithoutTheGestureRuleEquilibriumAloneDecides) {
  GraspParams params;
  params.gesture_rule = GestureRule::kNone;
  const auto check_without = [&](const std::vector<HandContact>& contacts) {
    return evaluate_grasp(contacts.data(), contacts.size(), kCentroid, kMass, kGravity, params,
                          false);
  };
  const double w = kMass * 9.81;
  const std::vector<HandContact> palm_under = {
      touch(Link::kPalm, {0, 0, -0.03}, {0, 0, 1}, w, 0.0)};
  EXPECT_EQ(check(palm_under).verdict, GraspReason::kTooFewContacts);
  EXPECT_EQ(check_without(palm_under).verdict, GraspReason::kStableGrasp);
  const std::vector<HandContact> index_and_middle = {
      touch(Link::kIndexDistal, {0.04, 0, 0}, {-1, 0, 0}, 2.0, w / 2),
      touch(Link::kMiddleDistal, {-0.04, 0, 0}, {1, 0, 0}, 2.0, w / 2)};
  EXPECT_EQ(check(index_and_middle).verdict, GraspReason::kTooFewContacts);
  EXPECT_EQ(check_without(index_and_middle).verdict, GraspReason::kStableGrasp);
  EXPECT_EQ(check_without({}).verdict, GraspReason::kTooFewContacts);
  const std::vector<HandContact> resting_finger = {
      touch(Link::kIndexDistal, {0.0, 0, 0.03}, {0, 0, -1}, 2.0, 0.0)};  // |sum F| 3.96 N
  EXPECT_EQ(check_without(resting_finger).verdict, GraspReason::kForceResidual);
  // the thresholds still apply: xi below the residual's 0.5 N refuses the unbalanced pair
  std::vector<HandContact> unbalanced = index_and_middle;
  unbalanced[0].F_G.z() -= 0.5;
  EXPECT_EQ(check_without(unbalanced).verdict, GraspReason::kStableGrasp);
  params.xi_N = 0.4;
  EXPECT_EQ(check_without(unbalanced).verdict, GraspReason::kForceResidual);
}

TEST(GraspRule, AHoldLastsWhileAnyFingerIsOpposed) {
  // the middle finger wraps round the object's end at 100 deg from the thumb: in the paper's
  // reading no new grasp (every finger must oppose), but its held test (hold_rule test) stays
  // held, the index still opposing
  auto contacts = balanced_three_point();
  const double a = 100.0 * M_PI / 180.0;
  contacts[2] = touch(Link::kMiddleDistal, {0, 0.04, 0}, {std::cos(a), std::sin(a), 0}, 2.0, 0.5);
  GraspParams params;
  params.gesture_rule = GestureRule::kPaper;
  const GraspCheck entry =
      evaluate_grasp(contacts.data(), contacts.size(), kCentroid, kMass, kGravity, params, false);
  EXPECT_EQ(entry.verdict, GraspReason::kFingersNotOpposed);
  const GraspCheck hold =
      evaluate_grasp(contacts.data(), contacts.size(), kCentroid, kMass, kGravity, params, true);
  EXPECT_NEAR(hold.min_thumb_angle_deg, 100.0, 1e-6);
  EXPECT_GT(hold.best_opposition_deg, params.alpha0_deg - params.exit_alpha_margin_deg);
  EXPECT_NE(hold.verdict, GraspReason::kFingersNotOpposed);
  // ... and is let go when no finger is opposed any more
  contacts[1] = touch(Link::kIndexDistal, {0, -0.04, 0}, {std::cos(a), -std::sin(a), 0}, 2.0, 0.5);
  const GraspCheck lost =
      evaluate_grasp(contacts.data(), contacts.size(), kCentroid, kMass, kGravity, params, true);
  EXPECT_NEAR(lost.best_opposition_deg, 100.0, 1e-6);
  EXPECT_EQ(lost.verdict, GraspReason::kFingersNotOpposed);
}

TEST(GraspRule, ThumbPalmAndThumbAloneOpposeNothing) {
  const double w = kMass * 9.81;
  const std::vector<HandContact> contacts = {
      touch(Link::kThumbDistal, {-0.04, 0, 0}, {1, 0, 0}, 2.0, w / 3),
      touch(Link::kThumbMiddle, {-0.04, 0, 0.02}, {1, 0, 0}, 2.0, w / 3),
      touch(Link::kPalm, {0.04, 0, 0}, {-1, 0, 0}, 4.0, w / 3)};
  EXPECT_EQ(check(contacts).verdict, GraspReason::kFingersNotOpposed);
}

TEST(GraspRule, UnbalancedForceOrTorqueIsNoGraspButLooserWhileHeld) {
  auto contacts = balanced_three_point();
  contacts[0].F_G.x() += 4.0;  // 4 N net push: above xi (3 N), below exit_scale xi
  EXPECT_EQ(check(contacts).verdict, GraspReason::kForceResidual);
  EXPECT_EQ(check(contacts, /*held=*/true).verdict, GraspReason::kStableGrasp);

  auto twisted = balanced_three_point();
  // equal and opposite vertical forces 10 cm apart: no net force, 0.5 N m of torque
  twisted[1].F_G.z() += 5.0;
  twisted[1].p_G = {0.05, 0, 0};
  twisted[0].F_G.z() -= 5.0;
  twisted[0].p_G = {-0.05, 0, 0};
  const GraspCheck c = check(twisted);
  EXPECT_LT(c.residual_force_N, 1e-9);
  EXPECT_EQ(c.verdict, GraspReason::kTorqueResidual) << c.residual_torque_Nm;
}

}  // namespace
}  // namespace vcockpit::physics
