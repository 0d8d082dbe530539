#include "bench/study/study_cases.hpp"

#include <cmath>
#include <cstdio>

namespace vcockpit::study {

physics::GraspParams paper_test(const physics::GraspParams& shipped) {
  physics::GraspParams p = shipped;
  p.exit_scale = 1.0;
  p.exit_alpha_margin_deg = 0.0;
  p.exit_min_contacts = p.min_contacts;
  p.min_hold_s = 0.0;
  p.release_delay_s = 0.0;
  p.regrab_cooldown_s = 0.0;
  p.release_opening_share = 0.0;
  p.palm_opposition = false;
  p.gesture_rule = physics::GestureRule::kPaper;
  p.hold_rule = physics::HoldRule::kContactTest;
  return p;
}

std::vector<Rule> compared_rules(const physics::GraspParams& shipped) {
  std::vector<Rule> rules;
  physics::GraspParams strict = paper_test(shipped);
  strict.gesture_rule = physics::GestureRule::kNone;
  strict.xi_N = kStrictXi_N;
  strict.eta_Nm = kStrictEta_Nm;
  rules.push_back({"strict", "rules", 0.0, strict});
  physics::GraspParams relaxed = paper_test(shipped);
  relaxed.gesture_rule = physics::GestureRule::kNone;
  rules.push_back({"relaxed", "rules", 0.0, relaxed});
  rules.push_back({"relaxed_gesture", "rules", 0.0, paper_test(shipped)});
  rules.push_back({"default", "rules", 0.0, shipped});
  // the project's rule with the paper's literal reading of the gesture constraint
  physics::GraspParams default_paper = shipped;
  default_paper.gesture_rule = physics::GestureRule::kPaper;
  rules.push_back({"default_paper_gesture", "rules", 0.0, default_paper});
  return rules;
}

std::vector<Rule> alpha0_sweep(const physics::GraspParams& shipped) {
  std::vector<Rule> rules;
  for (double alpha0_deg : {90.0, 100.0, 110.0, 120.0, 130.0, 140.0, 150.0}) {
    physics::GraspParams p = paper_test(shipped);
    p.alpha0_deg = alpha0_deg;
    rules.push_back({"alpha0_" + std::to_string(static_cast<int>(alpha0_deg)), "alpha0", alpha0_deg, p});
  }
  return rules;
}

std::vector<Rule> xi_sweep(const physics::GraspParams& shipped) {
  std::vector<Rule> rules;
  const double eta_per_xi_m = shipped.eta_Nm / shipped.xi_N;
  for (double xi_N : {0.1, 0.3, 1.0, 3.0, 10.0}) {
    physics::GraspParams p = paper_test(shipped);
    p.xi_N = xi_N;
    p.eta_Nm = xi_N * eta_per_xi_m;
    char name[32];
    std::snprintf(name, sizeof name, "xi_%g", xi_N);
    rules.push_back({name, "xi", xi_N, p});
  }
  return rules;
}

namespace {

// The selector two detents (off -> vor -> gps), the heading knob ten clicks (two twists of five).
std::vector<ControlChange> knob_changes() {
  std::vector<ControlChange> out = {{"nav_mode", "off", "vor"}, {"nav_mode", "vor", "gps"}};
  for (int click = 0; click < 10; ++click) {
    out.push_back({"heading_bug", "click", "between"});
    out.push_back({"heading_bug", "between", "click"});
  }
  return out;
}

}  // namespace

const std::vector<StudyObject>& study_objects() {
  // place_G, approach_end_s and arrive_s from each script's keyframes (its comments say where it
  // sets the object down); the heavy bar is lifted 10 cm and set down where it lay. arrive_s is
  // the keyframe that puts the hand at the object, before it moves round, onto or in to it: 10 cm
  // over the cup, the ball, the flashlight and the bar; beside the checklist's edge at the
  // board's height (it then slides in under and over the board until 2.0 s); 4.7 cm back from
  // the knobs, aimed at them; over the levers.
  static const std::vector<StudyObject> kObjects = {
      {"cup", {{"cup_pick_place.yaml"}}, {0.36, -0.43, 0.75}, 2.0, {}, {}, 1.0},
      {"ball", {{"ball_pick_place.yaml"}}, {0.58, -0.44, 0.73}, 2.1, {}, {}, 1.1},
      {"flashlight", {{"flashlight_pick_place.yaml"}}, {0.565, -0.30, 0.718}, 2.1, {}, {}, 1.1},
      {"checklist", {{"checklist_pick_place.yaml"}}, {0.31, -0.228, 0.704}, 2.2, {}, {}, 1.4},
      {"heavy_bar",
       {{"two_hand_lift_right.yaml"}, {"two_hand_lift_left.yaml", true}},
       {0.72, 0.0, 1.096},
       2.2,
       {},
       {},
       1.2},
      // the grasped controls: what their gestures do (tests/scenario/control_logs_test.cpp pins
      // the same changes for the bundled logs)
      {"knobs", {{"panel_knobs.yaml"}}, Eigen::Vector3d::Zero(), 1.9, {"nav_mode", "heading_bug"},
       knob_changes(), 1.0},
      {"levers", {{"pedestal_levers.yaml"}}, Eigen::Vector3d::Zero(), 4.0, {"throttle", "flaps"},
       {{"throttle", "idle", "cutoff"},
        {"throttle", "cutoff", "idle"},
        {"throttle", "idle", "full"},
        {"throttle", "full", "idle"},
        {"flaps", "up", "approach"},
        {"flaps", "approach", "landing"},
        {"flaps", "landing", "approach"},
        {"flaps", "approach", "up"}},
       3.2},
  };
  return kObjects;
}

}  // namespace vcockpit::study
