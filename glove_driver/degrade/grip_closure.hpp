#pragma once
// Faster grip closures: people close a grip on an object in 0.25-0.5 s, often faster than a
// scripted gesture does. The segments where the grip closes are found in the log and
// time-warped to last `duration_s`: the closure starts when it did, runs faster, and the hand
// then holds the closed grip until the original closure's end, so everything after is unchanged.
//
// A grip closure is a stretch where the aperture — the mean distance from the thumb tip to the
// index and middle fingertips, by the hand model's forward kinematics — keeps falling (it may
// rise by no more than `hysteresis_m` on the way) by at least `min_closure_m` while the wrist
// tracker moves less than `max_wrist_travel_m`: the hand closes on something, not curling while
// it travels. Only closures longer than duration_s are changed (never slowed down). Meant for
// the smooth motion of a recording, before noise is added (degrade.hpp applies it first).

#include <cstdint>
#include <vector>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit::degrade {

struct GripClosureOptions {
  double min_closure_m = 0.005;
  double hysteresis_m = 0.0005;
  double max_wrist_travel_m = 0.02;
};

struct GripClosure {
  std::size_t first = 0;  // rows: the aperture falls from samples[first] to samples[last]
  std::size_t last = 0;
  double closure_m = 0.0;  // how far it fell
};

// Thumb tip to index and middle tips, mean (m).
double grip_aperture_m(const hand::HandModel& hand, const hand::JointAngles& q);

std::vector<GripClosure> find_grip_closures(const std::vector<hand::GloveSample>& samples,
                                            const hand::HandModel& hand,
                                            const GripClosureOptions& options = {});

// Time-warps every closure longer than duration_s; returns how many it changed.
int speed_up_grip_closures(std::vector<hand::GloveSample>& samples, const hand::HandModel& hand,
                           double duration_s, const GripClosureOptions& options = {});

}  // namespace vcockpit::degrade
