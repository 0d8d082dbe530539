#pragma once
// hand.yaml -> hand::HandModel. The schema is documented at the top of config/hand.yaml.
//
// Every bad value throws vcockpit::ConfigError "file:line:col: key.path: message": unknown keys,
// missing fields, unknown joint/link names, min > max, rest outside [min, max], negative sizes,
// bad Euler axes, unknown tracker mount. The file always describes a right hand; `side: left`
// yields its mirror image (hand::mirrored).

#include <string>

#include "common/config_error.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit {

hand::HandModel load_hand_model(const std::string& path);
hand::HandModel parse_hand_model(const ConfigNode& root);

}  // namespace vcockpit
