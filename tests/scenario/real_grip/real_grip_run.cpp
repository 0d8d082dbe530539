#include "tests/scenario/real_grip/real_grip_run.hpp"

#include <cstdlib>
#include <stdexcept>

#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"

namespace vcockpit::real_grip {

RealGripRun replay_real_grip(const std::string& scene_path, const std::string& log_path,
                             const std::string& object_name, const std::string& support_name) {
  const physics::Scene scene = load_scene(scene_path);
  const int object = scene.find_object(object_name);
  const int support = scene.find_object(support_name);
  if (object < 0 || support < 0)
    throw std::invalid_argument(scene_path + ": no object '" + object_name + "' or '" +
                                support_name + "'");
  const auto log = hand::read_glove_log(log_path, scene.hands.at(0));
  physics_io::GripReplayOptions options;
  options.trace = std::getenv("VCOCKPIT_REAL_GRIP_TRACE") != nullptr;
  return physics_io::replay_grip(scene, log.samples, object, support, options);
}

}  // namespace vcockpit::real_grip
