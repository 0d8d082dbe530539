#pragma once
// The CSV the project's logs are written in (glove logs, hand-joints logs): a line's fields split
// at commas, each without surrounding blanks.

#include <string>
#include <vector>

namespace vcockpit::hand {

// `s` without leading or trailing spaces, tabs and carriage returns.
std::string trim(const std::string& s);
// The comma-separated fields of a line, each trimmed; a trailing comma ends in an empty field.
std::vector<std::string> split_csv(const std::string& line);

}  // namespace vcockpit::hand
