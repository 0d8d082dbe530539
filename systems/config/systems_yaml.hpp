#pragma once
// An aircraft's systems file -> systems::SystemsModel (the schema: docs/systems.md and the top
// of config/aircraft.yaml). Every bad value throws vcockpit::ConfigError
// "file:line:col: key.path: message": unknown keys, a system of no kind or of two, bad numbers,
// expressions that do not parse (with the character). Names are resolved later, against the
// scene's controls (systems::Systems), and those errors name the same places.

#include <string>

#include "common/config_error.hpp"
#include "systems/system_model.hpp"

namespace vcockpit {

systems::SystemsModel load_systems_model(const std::string& path);
systems::SystemsModel parse_systems_model(const ConfigNode& root);

}  // namespace vcockpit
