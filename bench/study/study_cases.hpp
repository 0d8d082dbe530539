#pragma once
// What the grasp study (scripts/study, docs/study/results.md) compares: the grasp rules of the
// paper (§4.4) against the project's, and the trials it runs them on.
//
// Rules, each a physics::GraspParams built from the shipped scene's (config/cockpit.yaml):
//   strict           eqs. 30-31 with xi and eta near zero (kStrictXi_N, kStrictEta_Nm), no gesture
//                    rule: the "fully satisfied" equilibrium the paper starts from;
//   relaxed          eqs. 30-31 with the shipped xi and eta (the paper gives no values), no gesture
//                    rule: the paper's relaxed condition;
//   relaxed_gesture  relaxed + the gesture constraint (more than 2 links, the thumb, alpha0 = 120):
//                    the paper's stable-grasp condition;
//   default          the project's rule as shipped: the project's reading of the gesture
//                    constraint (GestureRule::kProject), held while the tracked hand's grip holds
//                    (HoldRule::kTrackedGrip), minimum hold, release delay, re-grab cooldown, palm
//                    opposition;
//   default_paper_gesture  the same with the paper's literal reading of the gesture constraint
//                    (GestureRule::kPaper): the two readings side by side.
// The paper's rules (the first three) have none of the project's additions: one test decides
// grasp and release, every step. The physics (contacts, proxy hand, release velocity) is the same
// for all four.
//
// Trials: every dynamic object of the default cockpit, picked up, lifted and set down by its
// gesture script (config/gestures), one hand or, for the heavy bar, two; and the controls that
// are grasped (the knobs and the pedestal levers), operated by their gestures.

#include <Eigen/Core>

#include <string>
#include <vector>

#include "physics_node/physics/scene.hpp"

namespace vcockpit::study {

inline constexpr double kStrictXi_N = 0.1;     // 5 % of the cup's weight
inline constexpr double kStrictEta_Nm = 0.01;

struct Rule {
  std::string name;   // strict, relaxed, relaxed_gesture, default; sweeps: alpha0_110, xi_1 ...
  std::string group;  // "rules", "alpha0" or "xi"
  double value = 0.0;  // the swept value (alpha0 deg or xi N); 0 for "rules"
  physics::GraspParams params;
};

// The paper's test alone (no hysteresis, hold time, delay, cooldown, hand-opening release or palm
// opposition), with the shipped thresholds.
physics::GraspParams paper_test(const physics::GraspParams& shipped);

// The five rules compared, in order.
std::vector<Rule> compared_rules(const physics::GraspParams& shipped);
// relaxed_gesture with alpha0 swept over 90-150 deg, and with xi swept (eta = xi x 0.1 m, the
// shipped ratio).
std::vector<Rule> alpha0_sweep(const physics::GraspParams& shipped);
std::vector<Rule> xi_sweep(const physics::GraspParams& shipped);

struct HandScript {
  std::string script;  // relative to config/gestures/
  bool left = false;
};

// A control's change from one named position to another.
struct ControlChange {
  std::string control;
  std::string from;
  std::string to;
};

struct StudyObject {
  std::string object;             // the scene's object, or the name of a control case
  std::vector<HandScript> hands;  // one hand, or two for a two-handed lift
  Eigen::Vector3d place_G;        // where the gesture sets the object's centre down (m, world)
  // when the script's hand has reached the object and its grip starts to close (s): the trial's
  // aperture varies before it
  double approach_end_s = 0.0;
  // A control case: the controls its gesture grasps, and the changes it makes, in order (a
  // trial succeeds when it makes exactly these).
  std::vector<std::string> controls;
  std::vector<ControlChange> changes;
  // when the script's hand is at the object, before it moves round, onto or in to it (s): the
  // trial's approach path is offset before it and not after (0: approach_end_s). A person
  // reaches from any side, but guides the last few centimetres round a cup, onto a knob or
  // along a board's edge by sight, clear of the object as the script is: an offset kept into
  // them (up to 2.5 cm) put a small hand's thumb on the cup's rim, pressing it over.
  double arrive_s = 0.0;
  double offset_gone_s() const { return arrive_s > 0.0 ? arrive_s : approach_end_s; }
  bool is_control() const { return !controls.empty(); }
};

const std::vector<StudyObject>& study_objects();

}  // namespace vcockpit::study
