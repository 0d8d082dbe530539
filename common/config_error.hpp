#pragma once
// The error every config loader throws: "file:line:col: key.path: message" (common/yaml_config.hpp
// builds it). A header of its own so that the loaders' callers, which catch it, do not parse
// yaml-cpp.

#include <stdexcept>

namespace vcockpit {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A node of a parsed YAML file (common/yaml_config.hpp); loaders take it by reference.
class ConfigNode;

}  // namespace vcockpit
