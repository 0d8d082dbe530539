#pragma once
// One cell of the grasp matrix: a gesture script for one object, played by a hand of one size,
// degraded one way, replayed through the physics library exactly as the offline runner does
// (ReplayDriver, dropout rows skipped as the log reader skips them), and measured:
//   - the grasp events (GRASP and RELEASE of the object, and of anything else);
//   - the object's fastest speed from the start until the GRASP (the fingers closing on it
//     must not knock it away);
//   - how high the object rose while held (it was carried, not left where it lay);
//   - where the object ends, 1 s after the log, against where the script sets it down;
//   - the deepest any link of the drawn hand goes into a static object, every 10 ms
//     (hand_static_clearance.hpp, independent of the physics).

#include <Eigen/Geometry>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "glove_driver/degrade/degrade.hpp"
#include "glove_driver/glove/gesture_script.hpp"
#include "physics_node/physics/world.hpp"
#include "tests/scenario/grasp_matrix/hand_static_clearance.hpp"

namespace vcockpit::test {

struct GraspCase {
  std::string object;       // scene object name
  std::string script;       // gesture script, relative to config/gestures/
  Eigen::Vector3d place_G;  // where the script sets the object's centre down (m, world)
};

struct ScenarioResult {
  int grasps = 0;        // of the object
  int releases = 0;      // of the object
  int other_events = 0;  // grasps or releases of anything else
  int64_t first_grasp_ns = -1;
  int64_t first_release_ns = -1;
  double max_speed_before_grasp_mps = 0.0;
  double max_lift_held_m = 0.0;  // highest rise above its start while held
  Eigen::Vector3d final_p_G = Eigen::Vector3d::Zero();
  double place_error_m = 0.0;
  Penetration deepest_static;
  int64_t deepest_static_ns = 0;
  std::size_t samples_fed = 0;
  std::string events;  // one line per event, for failure messages
};

using glove::script_samples;  // glove_driver/glove/gesture_script.hpp

// Paths relative to the source tree (config/...). Throws on bad files. `observe`, if given, sees
// the world after every step (for diagnosing a failing cell).
ScenarioResult run_grasp_scenario(const std::string& source_dir, const GraspCase& grasp_case,
                                  const std::string& hand_yaml, const degrade::DegradeSpec& spec,
                                  const std::function<void(const physics::World&)>& observe = {});

}  // namespace vcockpit::test
