#pragma once
// Placing an object inside a recorded grip: the pose where the tracked hand of one glove sample
// (grip_hand.hpp) holds the object, for a test scene where the recording grasps it.
//
// A placement is accepted when
//   - the thumb and at least `other_fingers` (2) other fingers each come within contact_m (1 mm)
//     of the object's surface (a finger's distance: the least signed distance of its three
//     phalanx capsules; an overlap counts as within),
//   - at least `opposing_fingers` (1) of those opposes the thumb: the object's surface normal
//     where the finger is nearest is more than opposition_deg (95) from the normal where the
//     thumb is (a flat hand laid on a bar touches it with every finger, all from the same side,
//     or with the thumb on its end, at 90 deg: no grip), and
//   - no hand link (the 15 phalanx capsules and the palm box) is deeper than max_depth_m (2 mm)
//     inside the object.
// Signed distances and normals as shape_distance.hpp defines them.
//
// The search: a deterministic multi-start Nelder-Mead (nelder_mead.hpp) over the object's
// position and, where it is free, its yaw, in the resting orientations of rest_orientation.hpp
// (the object must hold still on its pedestal: a bar lies, a box lies on a face), minimising, in
// mm,
//     h(d_thumb - c)^2 + h(d_a - c)^2 + h(d_b - c)^2      the thumb and the two nearest others
//   + min_f [h(d_f - c)^2 + 25 h(n_thumb . n_f - cos(opposition_deg + 15))^2]   one opposing
//   + 10 sum_links h(-d_link - e)^2                       no link deep inside
//   + 1e-3 sum_rest h(d_rest - c)^2                       and the remaining fingers, lightly
// with h(x) = max(x, 0), c = contact_m / 2 and e = max_depth_m / 2 (margins inside the limits;
// a result that does not pass is polished once more with c and e at 98 % of the limits, for
// grips too tight for the margins). Each start grows the object from 60 % of its size to all of it
// (a continuation: a small object settles inside the grip, then is pushed to where the whole fits).
// Starts: 7 positions inside the grip (the phalanges' centroid, the fingertips' centroid, the
// midpoints between the thumb's distal phalanx and each finger's middle one, the palm's face pushed
// out by the object's least half size) times each resting orientation times 6 yaws, every 30 deg
// from the one that lays the object across the fingers (along the hand's y axis on the floor);
// where the yaw changes nothing (a ball, a standing cylinder), the position and the position moved
// 8 mm either way along each of H's axes instead. Of the results that pass, the one with the most
// fingers gripping (touching and opposed) wins, then the most touching, then (given the recorded
// hands before the moment, hand_approach.hpp) one the hand does not pass through before the moment
// (no link deeper than max_depth_m), then the lower cost, then the earlier start; if none passes,
// the lowest cost (the figures of "no placement"). Every distinct accepted result is kept too, in
// that order (FitResult::accepted): grip_fit replays them in turn until one holds.

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <vector>

#include "hand/hand_joints.hpp"
#include "physics_node/fit/grip_hand.hpp"
#include "physics_node/fit/hand_approach.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::fit {

struct FitLimits {
  double contact_m = 1.0e-3;    // a finger this close to the surface (or in it) touches
  double max_depth_m = 2.0e-3;  // no link deeper inside the object
  int other_fingers = 2;        // fingers besides the thumb that must touch
  int opposing_fingers = 1;     // ... of which this many must oppose the thumb
  // a finger opposes the thumb beyond this normal-to-normal angle: past perpendicular by more
  // than rounding (a thumb on a bar's end and fingers on its side are at 90 deg exactly)
  double opposition_deg = 95.0;
};

struct Placement {
  Eigen::Isometry3d X_GO = Eigen::Isometry3d::Identity();
  // signed, palm included; a phalanx that cannot be its finger's nearest (a cheap bound beyond
  // it, outside the object) holds that bound instead: the search needs no more of it
  std::array<double, hand::kLinkCount> link_distance_m{};
  std::array<double, hand::kFingerCount> finger_distance_m{};  // least over its phalanges
  std::array<hand::Link, hand::kFingerCount> finger_link{};    // the phalanx that gives it
  hand::Link deepest_link = hand::Link::kPalm;                 // the link of least signed distance
  double deepest_m = 0.0;  // minus that distance: > 0 is inside the object
  // the object's outward normal where each finger is nearest, and its angle from the thumb's
  std::array<Eigen::Vector3d, hand::kFingerCount> finger_normal_G{};
  std::array<double, hand::kFingerCount> finger_opposition_deg{};
  int touching_fingers = 0;  // within contact_m, the thumb included
  int gripping_fingers = 0;  // touching and opposing the thumb, the thumb not included
  bool thumb_touches = false;
  bool accepted = false;  // the thumb, other_fingers, opposing_fingers, no link too deep
  double cost = 0.0;      // the search's cost (above, with its margins)
  // fit_object_in_grip with the hands before the moment, for an accepted placement: their least
  // link distance (< 0: the hand reaches into the object before gripping it); +inf otherwise
  double approach_m = INFINITY;
  // the resting orientation searched in (rest_orientation.hpp): its index and name
  int rest_index = 0;
  const char* rest_name = "any";
  bool yaw_free = false;  // ... whether its yaw is free, and the yaw about world z (rad) it has,
  double yaw_rad = 0.0;   // wrapped to (-pi, pi]
};

// The figures of one pose.
Placement evaluate_placement(const GripHand& hand, const physics::Shape& shape,
                             const Eigen::Isometry3d& X_GO, const FitLimits& limits = {});

struct FitResult {
  Placement best;  // accepted, or the nearest miss
  // every accepted result, best first (the order above; `best` is the first), each a distinct
  // pose: a result within same_position_m (1 mm) and same_turn_deg (2 deg) of a better one is
  // left out. The candidates grip_fit replays (grip_choice.hpp).
  std::vector<Placement> accepted;
  int starts = 0;
  int evaluations = 0;
};

FitResult fit_object_in_grip(const GripHand& hand, const physics::Shape& shape,
                             const FitLimits& limits = {},
                             const std::vector<RecordedHand>& before = {});

}  // namespace vcockpit::fit
