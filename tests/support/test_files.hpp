#pragma once
// Files for tests: the source tree, reading a file whole, and writing small inputs into a
// directory of the test's own.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/support/process.hpp"

namespace vcockpit::test {

// The repository (VCOCKPIT_SOURCE_DIR from ctest, else found from this file's path).
inline std::string source_dir() {
  if (const char* dir = std::getenv("VCOCKPIT_SOURCE_DIR")) return dir;
  const std::string file = __FILE__;  // <repo>/tests/support/test_files.hpp
  return file.substr(0, file.rfind("/tests/support/"));
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// config/cockpit.yaml's text made to load from another directory: its looks' model files
// (`mesh: models/...`, relative to config/) named by their paths in the source tree.
inline std::string cockpit_yaml_models_absolute(std::string yaml) {
  const std::string relative = "mesh: models/";
  const std::string absolute = "mesh: " + source_dir() + "/config/models/";
  for (auto at = yaml.find(relative); at != std::string::npos; at = yaml.find(relative, at + absolute.size()))
    yaml.replace(at, relative.size(), absolute);
  return yaml;
}

// Writes `text` to <temp dir of `dir_name` for this test>/<name> and returns the path. The
// directory is made once per test (make_temp_dir empties it).
inline std::string write_test_file(const std::string& dir_name, const std::string& name,
                                   const std::string& text) {
  static std::string dir;
  static std::string made_for;
  const std::string key = dir_name + "|" +
                          ::testing::UnitTest::GetInstance()->current_test_info()->name();
  if (made_for != key) {
    dir = make_temp_dir(dir_name);
    made_for = key;
  }
  const std::string path = dir + "/" + name;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path) << text;
  return path;
}

}  // namespace vcockpit::test
