#pragma once
// YAML loading whose every error names the file, line, column and key.
//
// A ConfigNode is a yaml-cpp node that remembers which file it came from and the key path that
// led to it ("objects[2].shape.box"), so a bad value is reported as
//   config/cockpit.yaml:14:12: objects[2].mass: must be positive, got -1
// Unknown keys are errors (a typo must never be silently ignored): every map reader states the
// keys it accepts with expect_keys().

#include <yaml-cpp/yaml.h>

#include "common/config_error.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vcockpit {

class ConfigNode {
 public:
  // Parses a file; syntax errors and unreadable files throw ConfigError with file:line:col.
  static ConfigNode load_file(const std::string& path);
  // Parses text (tests, embedded defaults); `name` stands in for the file name in errors.
  static ConfigNode load_string(const std::string& text, const std::string& name);

  const std::string& file() const { return *file_; }
  const std::string& key_path() const { return path_; }
  int line() const { return node_.Mark().line + 1; }  // 1-based
  int column() const { return node_.Mark().column + 1; }

  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }
  bool has(std::string_view key) const;

  // Child of a map; a missing key is an error naming the map's location.
  ConfigNode operator[](std::string_view key) const;
  std::optional<ConfigNode> find(std::string_view key) const;
  // Element of a sequence.
  std::size_t size() const;
  ConfigNode at(std::size_t index) const;
  std::vector<ConfigNode> elements() const;  // the sequence's elements (error if not a sequence)
  std::vector<std::string> keys() const;      // the map's keys in file order

  // Errors unless this is a map whose keys are all in `allowed`.
  void expect_keys(std::initializer_list<std::string_view> allowed) const;

  // Scalars; numbers must be finite. Errors name the key and what was found.
  double as_double() const;
  int64_t as_int() const;
  bool as_bool() const;
  std::string as_string() const;
  template <std::size_t N>
  std::array<double, N> as_doubles() const;
  std::vector<double> as_double_list() const;

  // Shorthands for a child key.
  double get_double(std::string_view key) const { return (*this)[key].as_double(); }
  double get_double(std::string_view key, double fallback) const;
  int64_t get_int(std::string_view key, int64_t fallback) const;
  bool get_bool(std::string_view key, bool fallback) const;
  std::string get_string(std::string_view key) const { return (*this)[key].as_string(); }
  std::string get_string(std::string_view key, const std::string& fallback) const;

  // Throws ConfigError "file:line:col: key: message" at this node.
  [[noreturn]] void fail(const std::string& message) const;

  const YAML::Node& raw() const { return node_; }

 private:
  ConfigNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string path)
      : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {}
  std::string child_path(std::string_view key) const;

  YAML::Node node_;
  std::shared_ptr<const std::string> file_;
  std::string path_;
};

template <std::size_t N>
std::array<double, N> ConfigNode::as_doubles() const {
  if (!is_sequence() || size() != N) {
    fail("expected a list of " + std::to_string(N) + " numbers");
  }
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = at(i).as_double();
  return out;
}

}  // namespace vcockpit
