#pragma once
// Whether a replayed grip holds (grip_fit replays each candidate scene, grip_choice.hpp): what a
// user expects of a scene where a recorded hand closes on an object standing on a pedestal.
//
// A replay (physics_io::GripReplay) holds when
//   1. the object is grasped (a GRASP event) within grasp_within_s (0.5 s) of the candidate's
//      moment and before the hand starts to open (below): the grip placed at the moment is what
//      takes it, not a hand that has moved on or is letting go;
//   2. its first RELEASE, if one comes before the log ends, is for the hand letting go -- hand
//      opened, thumb left the object or fingers left the object -- and comes after the hand has
//      started to open: after ClosedStretch::opening of the first closed stretch
//      (steady_moment.hpp rule 5: its flexion stays more than 5 % of the log's range below the
//      stretch's highest from there on; a release while the recorded fist is still closed is a
//      grip that slipped);
//   3. until settle_s (0.3 s) after that release (the end if none) its lowest point never goes
//      more than max_below_support_m (1 cm) below the top of its pedestal (not pushed off it
//      before the grasp, not carried down off it while held, not dropped from high when let go);
//   4. while no hand holds it (before the grasp, after the release, to the replay's end) it never
//      moves faster than max_free_horizontal_mps (0.5 m/s) horizontally (not flung, not knocked
//      away by the hand later in the log);
//   5. no hand link goes more than max_link_depth_m (1 mm) into it or into a static object.
// The reason given is that of the first broken rule in the order 3, 4, 2, 5, 1 (rule 1 last: a
// replay stopped early has not had its chance to grasp), with its figures when it broke: a replay
// stops there (hold_already_failed).

#include <string>

#include "physics_node/io/grip_replay.hpp"

namespace vcockpit::fit {

struct HoldRule {
  double grasp_within_s = 0.5;
  double settle_s = 0.3;
  double max_below_support_m = 0.01;
  double max_free_horizontal_mps = 0.5;
  double max_link_depth_m = 1e-3;
};

// The times the rules refer to, in the replay's world time (s).
struct HoldTimes {
  double moment_s = 0.0;   // the candidate's moment
  double opening_s = 0.0;  // the hand starts to open
};

struct HoldVerdict {
  bool holds = false;
  std::string why;  // what failed (empty when it holds)
};

// The verdict on a whole replay.
HoldVerdict judge_hold(const physics_io::GripReplay& run, const HoldTimes& times,
                       const HoldRule& rule = {});

// Whether a replay so far, at world time t_s, has already broken a rule that no later step can
// mend (rule 1 once its time is past without a grasp): replay_grip's stop, so a failing candidate
// costs a fraction of the log.
bool hold_already_failed(const physics_io::GripReplay& run, double t_s, const HoldTimes& times,
                         const HoldRule& rule = {});

// The figures of a replay on one line: grasp and release (and why), depth below the support,
// fastest free motion, deepest links.
std::string replay_figures(const physics_io::GripReplay& run);

}  // namespace vcockpit::fit
