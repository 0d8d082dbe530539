// Scene files (physics_node/config/scene_config.cpp, control_config.cpp): any text is either a
// scene or a ConfigError. Hand files resolve against config/, so `hand: hand.yaml` loads.

#include <cmath>

#include "common/yaml_config.hpp"
#include "fuzz/fuzz_support.hpp"
#include "physics_node/config/scene_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  try {
    const auto root = ConfigNode::load_string(std::string(fuzz::as_text(data, size)), "scene.yaml");
    const physics::Scene scene = parse_scene(root, fuzz::config_dir());
    // what the physics divides by: each dynamic body's mass and principal moments
    for (const physics::ObjectSpec& o : scene.objects) {
      if (!o.dynamic) continue;
      fuzz::require(std::isfinite(o.mass_kg) && o.mass_kg > 0.0, "a finite positive mass");
      fuzz::require(o.I_O.allFinite() && (o.I_O.diagonal().array() > 0.0).all(),
                    "finite positive moments of inertia");
    }
  } catch (const ConfigError&) {
  }
  return 0;
}
