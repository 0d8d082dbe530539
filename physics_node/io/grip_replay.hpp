#pragma once
// A recorded hand replayed on a scene with one object to grasp, measured the way a user judges a
// grip: when the object was taken and let go (and why), whether it sank below the top of what it
// stood on, how fast it moved while free, and how deep any link went into it or into the static
// world. The offline runner's replay (ReplayDriver, each sample through the SampleValidator's
// checks, values past the hand's range clamped), in memory: grip_fit replays each candidate scene
// with it (fit/grip_choice.hpp), and the real-recording tests replay scene files with it
// (tests/scenario/real_grip).

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hand/glove_sample.hpp"
#include "physics_node/physics/grasp.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics_io {

struct GripReplay {
  // times in s of world time: 0 is the first accepted sample (t0_ns on the log's timeline)
  double grasp_s = -1.0;    // the first GRASP of the object (-1: none)
  double release_s = -1.0;  // the first RELEASE after it (-1: none)
  physics::GraspReason release_reason = physics::GraspReason::kStableGrasp;
  int grasps = 0;
  int releases = 0;
  // From the start until settle_s after the release (the end if none): how far the object's
  // lowest point went below the top of its support (the static object under it at the start), m,
  // and when it was deepest.
  double deepest_below_support_m = 0.0;
  double deepest_below_support_at_s = 0.0;
  // The object's horizontal speed while no hand held it, at its highest (m/s), and when.
  double fastest_free_horizontal_mps = 0.0;
  double fastest_free_at_s = 0.0;
  double deepest_link_in_object_m = 0.0;  // any hand link in the object (proxy contacts)
  double deepest_link_in_object_at_s = 0.0;  // ... when it was deepest
  double deepest_link_in_static_m = 0.0;  // any hand link in a static object
  double last_sample_s = 0.0;             // the last accepted sample: the log's end
  double end_s = 0.0;                     // the replay's (tail_steps past the log's end)
  int64_t t0_ns = 0;                      // the log's time at world time 0
  bool stopped = false;                   // ended early: options.stop said so
  std::string events;  // one line per grasp event of the object: "t_s GRASP|RELEASE reason"
};

struct GripReplayOptions {
  int tail_steps = 500;   // steps after the last sample, for what was let go to come to rest
  double settle_s = 0.3;  // the support's depth is watched until this long after the release
  // Asked after each sample's steps with the figures so far and the world time (s): true ends the
  // replay there (stopped; a candidate that has already failed need not be replayed to the end).
  std::function<bool(const GripReplay&, double)> stop;
  bool trace = false;  // the object's pose every 10 ms on stderr (finding out why a run fails)
};

// Replays `samples` (a log read with the scene's hand 0) on `scene`, driving its hand 0 and
// watching object `object` standing on the static object `support` (indices into
// scene.objects). Throws std::invalid_argument on a bad index or a scene without a hand.
GripReplay replay_grip(const physics::Scene& scene, const std::vector<hand::GloveSample>& samples,
                       int object, int support, const GripReplayOptions& options = {});

}  // namespace vcockpit::physics_io
