#pragma once
// One trial of the grasp study: an object's gesture, varied (trial_variation.hpp), replayed
// through the physics exactly as `physics_node --offline` replays a glove log (the SampleValidator
// on every sample, dropout rows skipped as the log reader skips them, the offline runner's
// HandTimeline), under one grasp rule, and measured:
//   success      the object was lifted 5 cm while held, set down within 3 cm of where the
//                gesture puts it, and ends released;
//   convergence  first hand contact with it -> first GRASP (s);
//   chatter      switches of its grasp state (held by a hand or not) per second while the
//                pilot's fingers are closed (the glove's mean finger flexion above halfway
//                between its least and its most);
//   penetration  of the hand's links into it, and of it into other bodies (per step, the deepest
//                contact; max over the trial and mean over the steps in contact);
//   drops        releases after which it fell more than 2 cm within 0.5 s (not set down);
//   placement    its distance from where the gesture sets it down, 1 s after the log ends;
//   failure      where a failed trial failed: "never grasped"; "lost while held" (grasped but let
//                go or slipped before it was lifted 5 cm); "dropped" (lifted, then let go and
//                fallen 2 cm); "misplaced" (lifted and not dropped, but not set down within 3 cm,
//                or still held); a control case: "never grasped" or "wrong changes".
// A control case (the knobs, the levers) measures the grasped controls' moving parts the same way
// (convergence, chatter, the hand's penetration) and succeeds when the controls make exactly the
// gesture's changes, in order, nothing else is grasped, and none is left held.

#include <cstdint>
#include <functional>
#include <string>

#include "bench/study/study_cases.hpp"
#include "bench/study/trial_variation.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::study {

struct TrialResult {
  bool control_case = false;  // controls operated (no lift, placement, drops or object depth)
  int control_changes = 0;    // position changes of the controls
  std::vector<std::string> changes;  // ... each "control from->to @t_s", in order
  bool success = false;
  std::string failure;  // empty on success
  bool grasped = false;
  bool lifted = false;  // >= 5 cm while held
  bool placed = false;  // ends released within 3 cm of the target
  int grasps = 0;
  int releases = 0;
  int other_events = 0;  // grasps and releases of anything else
  double first_contact_s = -1.0;
  double first_grasp_s = -1.0;
  double convergence_s = -1.0;  // -1: never grasped after a contact
  double closed_s = 0.0;        // how long the fingers were closed
  int switches_closed = 0;      // grasp state switches of the object while they were
  double switch_rate_hz = 0.0;
  double hand_pen_max_m = 0.0;
  double hand_pen_mean_m = 0.0;
  double object_pen_max_m = 0.0;
  double object_pen_mean_m = 0.0;
  int drops = 0;
  double lift_m = 0.0;  // highest rise above its start while held
  double place_error_m = 0.0;
  double max_speed_before_grasp_mps = 0.0;
  double simulated_s = 0.0;
};

// One row of a trial's timeline (every 10 ms): what the grasp rule saw of the first hand.
struct TimelineRow {
  double t_s = 0.0;
  std::string target;  // the object or control part seen: a held one, else one a hand touches
  int links = 0;  // links of the first hand touching the object
  double residual_force_N = 0.0;
  double residual_torque_Nm = 0.0;
  bool held = false;
  std::string verdict;
  // the widest angle between the thumb's (or the palm's) contact normal and a finger's (deg)
  double opposition_deg = 0.0;
  double x_m = 0.0;  // the object's position (world frame)
  double y_m = 0.0;
  double z_m = 0.0;
  // the proxy's link farthest from its tracked one, any hand ("h0 thumb_distal"; empty when
  // none is off), and by how much (mm): what the world holds back
  double lag_mm = 0.0;
  std::string lag_link;
  std::string touching;  // the hand links touching the target ("h0 thumb_distal; h1 palm")
  std::string events;  // the target's grasp events since the last row ("grasp h0; release h1: why")
};

// Throws on a bad file or script. `timeline`, if given, gets a row every 10 ms.
TrialResult run_trial(const std::string& source_dir, const StudyObject& object, const Rule& rule,
                      const TrialVariation& variation,
                      const std::function<void(const TimelineRow&)>& timeline = {});

}  // namespace vcockpit::study
