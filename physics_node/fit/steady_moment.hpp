#pragma once
// The steadiest closed moment of a glove recording: where an object placed in the recorded grip
// (grip_fit.hpp) is best placed, the hand closed and still.
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
};

struct Moment {
  std::size_t index = 0;  // into the samples
  int64_t t_ns = 0;
  double flexion_rad = 0.0;
  double closure_share = 0.0;  // (flexion - lo) / (hi - lo); 1 for a log of one flexion
  double motion = 0.0;         // rule 2's figure (rad)
  bool window_whole = false;   // the +-window lay within the log
};

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
