#pragma once
// spdlog set up the same way in every node: "[time] [node] [level] message" on stderr.

#include <string>

namespace vcockpit {

// level: trace, debug, info, warn, error, critical, off. Throws std::invalid_argument otherwise.
void setup_logging(const std::string& node_name, const std::string& level = "info");

}  // namespace vcockpit
