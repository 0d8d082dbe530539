#pragma once
// A real hand recording replayed offline on a scene file with one object to grasp, measured the
// way a user judges a grip (physics_node/io/grip_replay.hpp: grasp and release and why, the depth
// below the support, the fastest free motion, the deepest links). Shared by the real-recording
// tests (the Leap "grab" on its scene, and the scenes grip_fit builds from it).

#include <string>

#include "physics_node/io/grip_replay.hpp"

namespace vcockpit::real_grip {

using RealGripRun = physics_io::GripReplay;

// Replays `log_path` (read with the scene's hand) on `scene_path`, watching object `object_name`;
// `support_name` is the static object it stands on. Throws on a bad file or name.
// VCOCKPIT_REAL_GRIP_TRACE=1: the object's pose every 10 ms on stderr.
RealGripRun replay_real_grip(const std::string& scene_path, const std::string& log_path,
                             const std::string& object_name, const std::string& support_name);

}  // namespace vcockpit::real_grip
