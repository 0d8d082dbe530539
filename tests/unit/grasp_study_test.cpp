// The grasp study's parts (bench/study): the rules it compares, the trials' seeded variation and
// one trial measured end to end. scripts/study's own outputs are checked by study_quick
// (tests/scenario/study_check.py).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <string>

#include "bench/study/grasp_trial.hpp"
#include "bench/study/study_cases.hpp"
#include "bench/study/trial_variation.hpp"
#include "hand/config/hand_yaml.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::study {
namespace {

std::string source_dir() { return std::getenv("VCOCKPIT_SOURCE_DIR"); }

TEST(StudyRules, ThePapersRulesHaveNoneOfTheProjectsAdditions) {
  const physics::GraspParams shipped;
  const auto rules = compared_rules(shipped);
  ASSERT_EQ(rules.size(), 5u);
  EXPECT_EQ(rules[0].name, "strict");
  EXPECT_EQ(rules[0].params.gesture_rule, physics::GestureRule::kNone);
  EXPECT_EQ(rules[0].params.xi_N, kStrictXi_N);
  EXPECT_EQ(rules[0].params.eta_Nm, kStrictEta_Nm);
  EXPECT_EQ(rules[1].name, "relaxed");
  EXPECT_EQ(rules[1].params.gesture_rule, physics::GestureRule::kNone);
  EXPECT_EQ(rules[1].params.xi_N, shipped.xi_N);
  EXPECT_EQ(rules[2].name, "relaxed_gesture");
  EXPECT_EQ(rules[2].params.gesture_rule, physics::GestureRule::kPaper);
  EXPECT_EQ(rules[2].params.alpha0_deg, 120.0);
  for (int r = 0; r < 3; ++r) {
    const physics::GraspParams& p = rules[r].params;
    EXPECT_EQ(p.exit_scale, 1.0) << rules[r].name;
    EXPECT_EQ(p.exit_alpha_margin_deg, 0.0) << rules[r].name;
    EXPECT_EQ(p.exit_min_contacts, p.min_contacts) << rules[r].name;
    EXPECT_EQ(p.min_hold_s, 0.0) << rules[r].name;
    EXPECT_EQ(p.release_delay_s, 0.0) << rules[r].name;
    EXPECT_EQ(p.regrab_cooldown_s, 0.0) << rules[r].name;
    EXPECT_EQ(p.release_opening_share, 0.0) << rules[r].name;
    EXPECT_EQ(p.hold_rule, physics::HoldRule::kContactTest) << rules[r].name;
    EXPECT_FALSE(p.palm_opposition) << rules[r].name;
  }
  EXPECT_EQ(rules[3].name, "default");
  EXPECT_EQ(rules[3].params.exit_scale, shipped.exit_scale);
  EXPECT_EQ(rules[3].params.regrab_cooldown_s, shipped.regrab_cooldown_s);
  EXPECT_EQ(rules[3].params.gesture_rule, physics::GestureRule::kProject);
  EXPECT_EQ(rules[3].params.hold_rule, physics::HoldRule::kTrackedGrip);
  // the project's rule with the paper's reading of the gesture, beside it
  EXPECT_EQ(rules[4].name, "default_paper_gesture");
  EXPECT_EQ(rules[4].params.gesture_rule, physics::GestureRule::kPaper);
  EXPECT_EQ(rules[4].params.hold_rule, physics::HoldRule::kTrackedGrip);
  // the sweeps: alpha0 90..150 and xi 0.1..10 on rule (c), eta keeping the shipped ratio
  const auto alpha = alpha0_sweep(shipped);
  ASSERT_EQ(alpha.size(), 7u);
  EXPECT_EQ(alpha.front().params.alpha0_deg, 90.0);
  EXPECT_EQ(alpha.back().params.alpha0_deg, 150.0);
  const auto xi = xi_sweep(shipped);
  ASSERT_EQ(xi.size(), 5u);
  for (const Rule& r : xi) {
    EXPECT_EQ(r.params.gesture_rule, physics::GestureRule::kPaper);
    EXPECT_DOUBLE_EQ(r.params.eta_Nm / r.params.xi_N, shipped.eta_Nm / shipped.xi_N);
  }
}

TEST(StudyVariation, SeededWithinItsRangesAndCoveringEveryHandAndInput) {
  std::set<std::string> sizes, inputs;
  for (uint64_t seed = 1; seed <= 300; ++seed) {
    const TrialVariation v = draw_variation(seed);
    const TrialVariation again = draw_variation(seed);
    EXPECT_EQ(v.hand_size, again.hand_size);
    EXPECT_EQ(v.input, again.input);
    EXPECT_EQ(v.approach_offset_G[0], again.approach_offset_G[0]);
    EXPECT_EQ(v.aperture_scale, again.aperture_scale);
    sizes.insert(v.hand_size);
    inputs.insert(v.input);
    EXPECT_GE(v.grip_closure_s, 0.3);
    EXPECT_LT(v.grip_closure_s, 0.8);
    EXPECT_GE(v.aperture_scale, 0.85);
    EXPECT_LT(v.aperture_scale, 1.15);
    for (const auto& offset : v.approach_offset_G) {
      EXPECT_LE(offset.head<2>().norm(), 0.025 + 1e-12);
      EXPECT_GE(offset.z(), 0.0);
      EXPECT_LT(offset.z(), 0.02);
    }
  }
  EXPECT_EQ(sizes.size(), 3u);
  EXPECT_EQ(inputs.size(), 8u);
  EXPECT_NE(draw_variation(1).approach_offset_G[0], draw_variation(2).approach_offset_G[0]);
}

TEST(StudyVariation, TheApproachIsOffsetOnTheWayAndNotWhereTheHandArrives) {
  const hand::HandModel hand = load_hand_model(source_dir() + "/config/hand.yaml");
  std::vector<hand::GloveSample> samples(401);  // 4 s at 100 Hz, the hand still, half closed
  for (std::size_t k = 0; k < samples.size(); ++k) {
    samples[k].t_ns = static_cast<int64_t>(k) * 10'000'000;
    samples[k].joints_rad = hand.rest_pose();
    samples[k].joints_rad[static_cast<int>(hand::Joint::kIndexPip)] = 0.5;
  }
  TrialVariation v = plain_variation();
  v.approach_offset_G[0] = {0.02, -0.01, 0.015};
  v.aperture_scale = 0.9;
  const double approach_end_s = 2.0;
  const auto varied = vary_approach(samples, v, 0, approach_end_s, approach_end_s, hand);
  const auto offset_G = [&](std::size_t k) {
    return hand.tracker.X_GM.linear() * (varied[k].p_MT_m - samples[k].p_MT_m);
  };
  EXPECT_LT(offset_G(0).norm(), 1e-12);                           // at the start
  EXPECT_LT((offset_G(150) - v.approach_offset_G[0]).norm(), 1e-9);  // largest at 0.75 T
  EXPECT_LT(offset_G(200).norm(), 1e-12);                         // arrived
  EXPECT_LT(offset_G(400).norm(), 1e-12);
  const auto pip = static_cast<int>(hand::Joint::kIndexPip);
  EXPECT_NEAR(varied[100].joints_rad[pip], 0.45, 1e-12);  // the approach: x 0.9
  EXPECT_NEAR(varied[290].joints_rad[pip], 0.5, 1e-12);   // the grip closed: the script's

  // a hand beside the object at 1.2 s, sliding in until its grip closes at 2.0 s: no offset on
  // the slide, the aperture as before
  const auto slid = vary_approach(samples, v, 0, 1.2, approach_end_s, hand);
  const auto slid_offset_G = [&](std::size_t k) {
    return hand.tracker.X_GM.linear() * (slid[k].p_MT_m - samples[k].p_MT_m);
  };
  EXPECT_LT((slid_offset_G(90) - v.approach_offset_G[0]).norm(), 1e-9);  // largest at 0.75 x 1.2 s
  EXPECT_LT(slid_offset_G(120).norm(), 1e-12);
  EXPECT_LT(slid_offset_G(160).norm(), 1e-12);
  EXPECT_NEAR(slid[100].joints_rad[pip], 0.45, 1e-12);
}

// One trial end to end: the cup's gesture as scripted, under the project's rule and under the
// paper's relaxed rule without the gesture constraint.
TEST(StudyTrial, TheProjectsRuleGraspsTheCupOnceAndTheRelaxedRuleChatters) {
  const physics::GraspParams shipped;
  const auto rules = compared_rules(shipped);
  const StudyObject& cup = study_objects().front();
  ASSERT_EQ(cup.object, "cup");
  const TrialResult d = run_trial(source_dir(), cup, rules[3], plain_variation());
  EXPECT_TRUE(d.success) << "lift " << d.lift_m << " error " << d.place_error_m;
  EXPECT_EQ(d.grasps, 1);
  EXPECT_EQ(d.releases, 1);
  EXPECT_GT(d.first_contact_s, 1.0);
  EXPECT_GT(d.convergence_s, 0.0);
  EXPECT_LT(d.convergence_s, 1.5);
  EXPECT_LE(d.switches_closed, 2);  // the grasp, and the release if the fingers were still closed
  EXPECT_GT(d.closed_s, 2.0);
  EXPECT_EQ(d.drops, 0);
  EXPECT_GT(d.hand_pen_max_m, 0.0);
  EXPECT_LT(d.hand_pen_max_m, 0.005);
  EXPECT_GT(d.object_pen_max_m, 0.0);  // it rests on the console
  const TrialResult b = run_trial(source_dir(), cup, rules[1], plain_variation());
  EXPECT_GT(b.switches_closed, 20) << "the paper's chatter";
  EXPECT_GT(b.switch_rate_hz, 10 * d.switch_rate_hz);
  // the same trial twice: the same figures
  const TrialResult again = run_trial(source_dir(), cup, rules[3], plain_variation());
  EXPECT_EQ(again.hand_pen_max_m, d.hand_pen_max_m);
  EXPECT_EQ(again.place_error_m, d.place_error_m);
}

// A control case: the knobs' gesture as scripted makes exactly its 22 changes under the
// project's rule (the selector's two detents, the heading knob's ten clicks).
TEST(StudyTrial, TheKnobsGestureMakesExactlyItsChanges) {
  const auto rules = compared_rules(physics::GraspParams{});
  const StudyObject* knobs = nullptr;
  for (const StudyObject& o : study_objects())
    if (o.object == "knobs") knobs = &o;
  ASSERT_NE(knobs, nullptr);
  ASSERT_TRUE(knobs->is_control());
  const TrialResult d = run_trial(source_dir(), *knobs, rules[3], plain_variation());
  EXPECT_TRUE(d.control_case);
  EXPECT_TRUE(d.success);
  EXPECT_EQ(d.control_changes, 22);
  EXPECT_EQ(d.grasps, 3);  // the selector once, the heading knob twice
  EXPECT_EQ(d.drops, 0);
  EXPECT_EQ(d.object_pen_max_m, 0.0);  // not measured for a control's part
}

}  // namespace
}  // namespace vcockpit::study
