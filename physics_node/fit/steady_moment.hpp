#pragma once
// The moments of a glove recording where grip_fit places an object in the recorded grip
// (grip_fit.hpp): the first closed stretch, the closing that leads into it and where the hand
// starts to open (rules 1, 3, 5-7, ClosedStretch; grip_choice.hpp tries the moments across it and
// replays each placement), and the stretch's steadiest moment, the hand closed and still (rules
// 1-4; what grip_fit took before it replayed its placements: there the recorded fist has often
// swept through the object's place already).
//
// The rule, over the samples of the log (joints clamped to the hand's ranges):
// 1. Closure: a sample's flexion is the sum of every finger's flexion channels (thumb rotation,
//    MCP and IP; MCP, PIP and DIP of the four fingers; no abduction, palm arch or wrist), rad.
//    A sample is closed when its flexion is at least lo + closed_share (hi - lo), lo and hi the
//    least and the most flexion of the log (closed_share 0.85).
// 2. Motion: a sample's motion is the largest change, from it to any sample within +-window_s
//    (50 ms) of its stamp, of
//        max over the 22 joints |dq| (rad) + wrist rotation angle (rad) + wrist travel / 0.1 m
//    (the wrist pose X_GH from the tracker, eqs. 26-27): 1 cm of travel counts as 0.1 rad, what a
//    0.1 rad turn moves a point 10 cm out (a fingertip).
// 3. The first closed stretch: from the log's first closed sample up to the first sample after it
//    whose flexion falls below lo + (closed_share - reopen_margin) (hi - lo) (0.75: a hysteresis,
//    so a one-sample dip of a noisy glove does not end it). Only it counts: in a replay the hand
//    that grasps the object is the first to close on it, and a later grip is where the earlier
//    one passes through the object (the Leap grab's second fist, the steadier one, lies 24 mm
//    into the first one's thumb).
// 4. The moment is the sample of that stretch of least motion whose window lies whole within the
//    log (none such: any of the stretch); a tie goes to the earlier sample.

#include <cstdint>
#include <optional>
#include <vector>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit::fit {

struct MomentRule {
  double closed_share = 0.85;   // of the log's flexion range, from its least
  double reopen_margin = 0.10;  // the closed stretch ends below closed_share - this
  double window_s = 0.05;       // each side of the sample
  double wrist_length_m = 0.1;  // travel that counts as 1 rad
  // the hand has started to open once its flexion stays below the stretch's highest by this
  // share of the log's range (ClosedStretch::opening)
  double opening_margin = 0.05;
  // the closing that leads into the stretch starts where the hand was last this near (share of
  // the log's range) its most open before the stretch, at most closing_s before the stretch
  // (ClosedStretch::closing)
  double closing_margin = 0.05;
  double closing_s = 0.3;
  // the moments grip_fit tries end this long after the stretch's start (ClosedStretch::last_moment)
  double search_s = 0.5;
};

struct Moment {
  std::size_t index = 0;  // into the samples
  int64_t t_ns = 0;
  double flexion_rad = 0.0;
  double closure_share = 0.0;  // (flexion - lo) / (hi - lo); 1 for a log of one flexion
  double motion = 0.0;         // rule 2's figure (rad)
  bool window_whole = false;   // the +-window lay within the log
};

// The first closed stretch (rule 3), as samples: the moments grip_fit tries lie in it, and a
// replayed grasp must not be let go before the hand starts to open (hold_check.hpp).
//
// 5. The hand starts to open after the stretch's last sample whose flexion is within
//    opening_margin (5 %) of the log's range of the stretch's highest: from there to the stretch's
//    end it stays lower (the Leap grab: the fist at 98-100 % until 0.68 s, then opening; its last
//    sample at 95 % at 0.73 s, below the closed level 85 % after 0.81 s, below 75 % at 0.87 s).
struct ClosedStretch {
  // 6. The closing that leads into it: from the last sample before it whose flexion is within
  //    closing_margin (5 %) of the log's range of the least flexion before it (the hand at its
  //    most open), but at most closing_s (0.3 s) before it (a hand closes on an object in about
  //    that; a long reach with the hand half open is not where it takes it), up to it (the Leap
  //    grab: from 0.017 s, 41 %, to 0.21 s). A larger object is taken here, before the fist
  //    closes past it.
  std::size_t closing = 0;
  // 7. The last moment grip_fit tries: the last sample up to search_s (0.5 s) after the
  //    stretch's first, and not after its opening (a hand that has started to open closes on
  //    nothing; the Leap grab: 0.70 s).
  std::size_t last_moment = 0;
  std::size_t first = 0;        // its first sample (closed)
  std::size_t last_closed = 0;  // its last closed sample
  std::size_t opening = 0;      // rule 5's sample: after it the hand opens
  // the first sample after it (below the reopen level); samples.size() when it lasts to the end
  std::size_t end = 0;
  std::vector<std::size_t> closed;  // its closed samples, in order (a dip is not one)
  double lo_rad = 0.0, hi_rad = 0.0;  // the log's least and most flexion
};

// Rule 3's stretch. Empty only for no samples.
std::optional<ClosedStretch> first_closed_stretch(const hand::HandModel& model,
                                                  const std::vector<hand::GloveSample>& samples,
                                                  const MomentRule& rule = {});

// The moments to try, earliest first: the closing's first sample, then every step_s (the first
// sample at least step_s after the one before; step_s <= 0: every sample) over the closing's
// samples and the stretch's closed ones up to its last moment (rules 6-7).
std::vector<std::size_t> moments_across(const ClosedStretch& stretch,
                                        const std::vector<hand::GloveSample>& samples,
                                        double step_s);

// A sample's figures as a moment (motion, closure share within the stretch's lo and hi).
Moment describe_moment(const hand::HandModel& model, const std::vector<hand::GloveSample>& samples,
                       std::size_t index, const ClosedStretch& stretch, const MomentRule& rule = {});

// The sum of every finger's flexion channels (rule 1), rad.
double hand_flexion_rad(const hand::JointAngles& q_rad);

// Rule 2's motion of sample i.
double sample_motion(const hand::HandModel& model, const std::vector<hand::GloveSample>& samples,
                     std::size_t i, const MomentRule& rule);

// The steadiest moment of the first closed stretch (rules 1-4). Empty only for no samples.
std::optional<Moment> steadiest_closed_moment(const hand::HandModel& model,
                                              const std::vector<hand::GloveSample>& samples,
                                              const MomentRule& rule = {});

// The sample nearest t_ns (the earlier on a tie), with its figures: a moment the user forces.
std::optional<Moment> moment_at(const hand::HandModel& model,
                                const std::vector<hand::GloveSample>& samples, int64_t t_ns,
                                const MomentRule& rule = {});

}  // namespace vcockpit::fit
