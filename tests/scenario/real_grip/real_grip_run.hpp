#pragma once
// A real hand recording replayed offline on a scene with one object to grasp, measured the way a
// user judges a grip: when the object was taken and let go (and why), whether it sank below the
// top of what it stood on, how fast it moved while free, and how deep any link went into it or
// into the static world. Shared by the real-recording tests (the Leap "grab" on its scene, and
// the scenes grip_fit builds from it).

#include <string>
#include <vector>

#include "physics_node/physics/grasp.hpp"

namespace vcockpit::real_grip {

struct RealGripRun {
  double grasp_s = -1.0;    // the first GRASP of the object (-1: none)
  double release_s = -1.0;  // the first RELEASE after it (-1: none)
  physics::GraspReason release_reason = physics::GraspReason::kStableGrasp;
  int grasps = 0;
  int releases = 0;
  // From the start until 0.3 s after the release (the end if none): how far the object's lowest
  // point went below the top of its support (the static object under it at the start), m.
  double deepest_below_support_m = 0.0;
  // The object's horizontal speed while no hand held it, at its highest (m/s), and when.
  double fastest_free_horizontal_mps = 0.0;
  double fastest_free_at_s = 0.0;
  double deepest_link_in_object_m = 0.0;  // any hand link in the object (proxy contacts)
  double deepest_link_in_static_m = 0.0;  // any hand link in a static object
  double end_s = 0.0;
  std::string events;  // one line per grasp event of the object: "t_s GRASP|RELEASE reason"
};

// Replays `log_path` on `scene_path` (each sample through the checks the offline runner makes),
// watching object `object_name`; `support_name` is the static object it stands on. Throws on a
// bad file or name.
RealGripRun replay_real_grip(const std::string& scene_path, const std::string& log_path,
                             const std::string& object_name, const std::string& support_name);

}  // namespace vcockpit::real_grip
