#pragma once
// Choosing grip_fit's scene: an object placed in a recorded grip that, replayed, the recorded hand
// grasps and holds (not only a pose the hand's geometry fits at one moment: a hand that sweeps
// through the object's place on its way to that moment pushes it off its pedestal first).
//
// The candidates, in the order they are tried:
//   - moments: the samples of the closing that leads into the log's first closed stretch and the
//     stretch's closed ones up to its last moment (steady_moment.hpp rules 6-7: from where the
//     hand was last at its most open, at most 0.3 s before the stretch, to 0.5 s into it and no
//     later than where the hand starts to open), each the first at least moment_step_s (30 ms)
//     after the one before (earliest first: the hand that takes the object is the first to close
//     round it, before it sweeps anywhere else; a larger object is taken before the fist closes
//     past it); a forced moment (at_ns) alone instead;
//   - at each moment, the placement search's accepted results (grip_fit.hpp: every resting
//     orientation tried, lying and standing alike, each distinct pose once), best first, at most
//     per_orientation (4) of each resting orientation.
// Each is laid out on its pedestal (grip_scene_layout.hpp: as wide as the grip at the moment
// leaves room for, so that what the recorded wrist carries about stays on it), built into a scene
// by the caller (scene_for: grip_fit builds the very text it writes) and the log replayed on it
// (physics_io::replay_grip); the first that holds (hold_check.hpp) is chosen. A failing replay
// stops as soon as a rule is broken. Without verification the first candidate is chosen
// unreplayed. Deterministic: the same log, hand and shape give the same trials and choice.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"
#include "physics_node/fit/grip_fit.hpp"
#include "physics_node/fit/grip_hand.hpp"
#include "physics_node/fit/grip_scene_layout.hpp"
#include "physics_node/fit/hand_approach.hpp"
#include "physics_node/fit/hold_check.hpp"
#include "physics_node/fit/steady_moment.hpp"
#include "physics_node/io/grip_replay.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::fit {

struct GripChoiceOptions {
  std::optional<int64_t> at_ns;  // only the sample nearest this (--at)
  bool verify = true;            // replay each candidate (false: the first is chosen)
  double moment_step_s = 0.03;
  // at each moment, at most this many of the search's results of each resting orientation (the
  // best; lying and standing alike tried)
  int per_orientation = 4;
  // the recorded hands before a moment (the placement search's approach, hand_approach.hpp) at
  // least this far apart in time
  double approach_spacing_s = 0.005;
  FitLimits limits;
  MomentRule moment_rule;
  LayoutRule layout_rule;
  HoldRule hold;
  std::string object_name = "object";  // in the scene scene_for builds
  std::string support_name = "pedestal";
  bool trace_replays = false;  // physics_io::GripReplayOptions::trace for every replay
};

// One candidate (or one moment without any placement) and what became of it.
struct GripTrial {
  Moment moment;
  GripHand grip;        // the hand at the moment
  bool placed = false;  // an accepted placement (false: `placement` is the moment's best miss)
  Placement placement;
  int rank = 0;                           // its place among the moment's accepted results, from 1
  int of = 0;                             // how many the moment has
  int starts = 0;                         // the search's starts at the moment
  std::optional<GripSceneLayout> layout;  // none: no scene (why says so)
  HandApproach approach;                  // the recorded hand before the moment
  bool replayed = false;
  bool holds = false;  // chosen (replayed and held, or the first unverified)
  std::string why;     // why not
  physics_io::GripReplay run;
};

struct GripChoice {
  std::optional<ClosedStretch> stretch;
  double opening_s = 0.0;         // the log's time the hand starts to open (ClosedStretch::opening)
  std::vector<GripTrial> trials;  // in the order tried
  int chosen = -1;                // into trials; -1: none holds (or none placed)
  int placed = 0;                 // trials with a placement
};

// The scene of a candidate with the object named options.object_name on a static object named
// options.support_name. May throw: the exception ends the choice.
using SceneFor = std::function<physics::Scene(const GripTrial&)>;
// Told of each trial as it ends (grip_fit prints a line).
using TrialReport = std::function<void(const GripTrial&)>;

GripChoice choose_grip(const hand::HandModel& model, const std::vector<hand::GloveSample>& samples,
                       const physics::Shape& shape, const GripChoiceOptions& options,
                       const SceneFor& scene_for, const TrialReport& report = {});

// The trial on one line: moment, orientation, rank, and held / why not.
std::string trial_line(const GripTrial& trial);

}  // namespace vcockpit::fit
