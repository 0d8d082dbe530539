#pragma once
// A real hand recording replayed offline on a scene file with one object to grasp, measured the
// way a user judges a grip (physics_node/io/grip_replay.hpp: grasp and release and why, the depth
// below the support, the fastest free motion, the deepest links). Shared by the real-recording
// tests (the Leap "grab" on its scene, and the scenes grip_fit builds from it).

#include <string>
#include <vector>

#include "hand/glove_sample.hpp"
#include "physics_node/io/grip_replay.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::real_grip {

using RealGripRun = physics_io::GripReplay;

// Replays `log_path` (read with the scene's hand) on `scene_path`, watching object `object_name`;
// `support_name` is the static object it stands on. Throws on a bad file or name.
// VCOCKPIT_REAL_GRIP_TRACE=1: the object's pose every 10 ms on stderr.
RealGripRun replay_real_grip(const std::string& scene_path, const std::string& log_path,
                             const std::string& object_name, const std::string& support_name);

// A replay of `samples` on `scene` (objects `object` on `support`) with the free object's fastest
// horizontal speed until settle_s after the first release: what the tests of a recording varied
// (degraded, or its object placed otherwise) judge of a let-go object, while it settles.
struct SettlingRun {
  RealGripRun run;
  double fastest_free_settling_mps = 0.0;
};
SettlingRun replay_settling(const physics::Scene& scene, const std::vector<hand::GloveSample>& samples,
                            int object, int support, double settle_s = 0.3);

}  // namespace vcockpit::real_grip
