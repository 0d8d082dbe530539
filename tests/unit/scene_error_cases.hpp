#pragma once
// Bad scene files for the scene tests (scene_config_test, control_config_test): a valid text with
// one piece replaced must fail to load with an error naming the file, the line of a marker and
// the key path.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "physics_node/config/scene_config.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit {

inline std::string write_file(const std::string& name, const std::string& text) {
  return test::write_test_file("scene_config_test", name, text);
}

inline std::size_t line_of(const std::string& text, std::size_t pos) {
  return 1 + static_cast<std::size_t>(
                 std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

struct BadCase {
  std::string name;  // file name and test label
  std::string find;  // text of the valid scene to replace (must occur exactly once)
  std::string replace;
  std::string marker;   // text starting on the line the error must name (first occurrence)
  std::string key;      // key path the error must name
  std::string message;  // part of the message
};

// Loads `text` from a file and returns the error message ("(no error)" if it loaded).
inline std::string load_error(const std::string& path) {
  try {
    load_scene(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

inline void expect_error_at(const std::string& msg, const std::string& file, std::size_t line,
                            const std::string& key, const std::string& message) {
  const std::string where = file + ":" + std::to_string(line) + ":";
  EXPECT_NE(msg.find(where), std::string::npos) << "want " << where << " in: " << msg;
  EXPECT_NE(msg.find(": " + key + ": "), std::string::npos) << "want key " << key << " in: " << msg;
  EXPECT_NE(msg.find(message), std::string::npos) << "want '" << message << "' in: " << msg;
}

// `valid` with the case's replacement made fails as the case says.
inline void expect_error(const BadCase& c, const std::string& valid) {
  SCOPED_TRACE(c.name);
  std::string text = valid;
  const auto at = text.find(c.find);
  ASSERT_NE(at, std::string::npos) << c.find;
  ASSERT_EQ(text.find(c.find, at + 1), std::string::npos) << "ambiguous: " << c.find;
  text.replace(at, c.find.size(), c.replace);
  const auto marker_at = text.find(c.marker);
  ASSERT_NE(marker_at, std::string::npos) << c.marker;
  const std::string path = write_file(c.name + ".yaml", text);
  expect_error_at(load_error(path), path, line_of(text, marker_at), c.key, c.message);
}

}  // namespace vcockpit
