#pragma once
// The topics' lists of names in one bounded string, each name ended by '|' (ControlInfo
// .position_names, SystemInfo.state_names): fastddsgen 2.3 does not read back arrays of bounded
// strings (cockpit.idl).

#include <string>
#include <vector>

namespace vcockpit {

// The names of "a|b|c|" in order; text after the last '|' is not a name.
inline std::vector<std::string> split_bar_list(const std::string& text) {
  std::vector<std::string> names;
  std::size_t start = 0;
  for (std::size_t bar = text.find('|'); bar != std::string::npos; bar = text.find('|', start)) {
    names.push_back(text.substr(start, bar - start));
    start = bar + 1;
  }
  return names;
}

}  // namespace vcockpit
