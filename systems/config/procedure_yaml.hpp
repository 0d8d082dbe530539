#pragma once
// Procedure and lesson files -> systems::Procedure, systems::Lesson (schemas: docs/systems.md and
// the top of config/procedures/before_start.yaml and config/lessons/default.yaml). Errors throw
// vcockpit::ConfigError "file:line:col: key.path: message"; names in conditions are resolved
// later against the aircraft (systems::ProcedureRunner), with the same places named.

#include <string>

#include "common/config_error.hpp"
#include "systems/procedure.hpp"

namespace vcockpit {

systems::Procedure load_procedure(const std::string& path);
// A lesson; its procedure files are relative to the lesson's folder.
systems::Lesson load_lesson(const std::string& path);

}  // namespace vcockpit
