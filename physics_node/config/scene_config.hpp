#pragma once
// Scene files (config/cockpit.yaml) -> physics::Scene. The schema is documented at the top of
// config/cockpit.yaml.
//
// Every bad value throws vcockpit::ConfigError "file:line:col: key.path: message": unknown keys,
// missing fields, non-positive sizes, masses, densities and stiffnesses, negative friction,
// rolling- or spinning-resistance coefficients, mu_d > mu_s, unknown
// shapes and kinds, duplicate object names, mass with density, mass on a static object, a step
// outside (0, 0.1] s. Errors inside the hand file come from the hand loader and name that file.

#include <string>

#include "common/config_error.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit {

// Loads a scene file; its `hand:` path is relative to the file's directory.
physics::Scene load_scene(const std::string& path);
// Parses a loaded scene; `base_dir` resolves a relative `hand:` path ("" = working directory).
physics::Scene parse_scene(const ConfigNode& root, const std::string& base_dir);

}  // namespace vcockpit
