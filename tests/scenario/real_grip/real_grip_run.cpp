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

SettlingRun replay_settling(const physics::Scene& scene, const std::vector<hand::GloveSample>& samples,
                            int object, int support, double settle_s) {
  SettlingRun out;
  physics_io::GripReplayOptions options;
  options.settle_s = settle_s;
  options.stop = [&](const physics_io::GripReplay& run, double t_s) {
    if (run.release_s < 0.0 || t_s <= run.release_s + settle_s)
      out.fastest_free_settling_mps = run.fastest_free_horizontal_mps;
    return false;
  };
  out.run = physics_io::replay_grip(scene, samples, object, support, options);
  return out;
}

}  // namespace vcockpit::real_grip
