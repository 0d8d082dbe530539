#include "common/yaml_config.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace vcockpit {
namespace {

std::string describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsMap()) return "a map";
  if (node.IsSequence()) return "a list";
  return "'" + node.Scalar() + "'";
}

ConfigError syntax_error(const std::string& file, const YAML::Exception& e) {
  std::ostringstream msg;
  msg << file << ':' << e.mark.line + 1 << ':' << e.mark.column + 1 << ": YAML syntax error: "
      << e.msg;
  return ConfigError(msg.str());
}

}  // namespace

ConfigNode ConfigNode::load_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open file");
  std::stringstream text;
  text << in.rdbuf();
  return load_string(text.str(), path);
}

ConfigNode ConfigNode::load_string(const std::string& text, const std::string& name) {
  auto file = std::make_shared<const std::string>(name);
  try {
    YAML::Node root = YAML::Load(text);
    if (!root.IsDefined() || root.IsNull()) throw ConfigError(name + ":1:1: the file is empty");
    return ConfigNode(root, file, "");
  } catch (const YAML::Exception& e) {
    throw syntax_error(name, e);
  }
}

std::string ConfigNode::child_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void ConfigNode::fail(const std::string& message) const {
  std::ostringstream msg;
  msg << file() << ':' << line() << ':' << column() << ": "
      << (path_.empty() ? std::string("(top level)") : path_) << ": " << message;
  throw ConfigError(msg.str());
}

bool ConfigNode::has(std::string_view key) const {
  return is_map() && node_[std::string(key)].IsDefined();
}

std::optional<ConfigNode> ConfigNode::find(std::string_view key) const {
  if (!is_map()) fail("expected a map, found " + describe(node_));
  YAML::Node child = node_[std::string(key)];
  if (!child.IsDefined()) return std::nullopt;
  return ConfigNode(child, file_, child_path(key));
}

ConfigNode ConfigNode::operator[](std::string_view key) const {
  auto child = find(key);
  if (!child) fail("missing required key '" + std::string(key) + "'");
  return *child;
}

std::size_t ConfigNode::size() const { return node_.size(); }

ConfigNode ConfigNode::at(std::size_t index) const {
  if (!is_sequence()) fail("expected a list, found " + describe(node_));
  if (index >= node_.size()) fail("list has no element " + std::to_string(index));
  return ConfigNode(node_[index], file_, path_ + "[" + std::to_string(index) + "]");
}

std::vector<ConfigNode> ConfigNode::elements() const {
  if (!is_sequence()) fail("expected a list, found " + describe(node_));
  std::vector<ConfigNode> out;
  out.reserve(node_.size());
  for (std::size_t i = 0; i < node_.size(); ++i) out.push_back(at(i));
  return out;
}

std::vector<std::string> ConfigNode::keys() const {
  if (!is_map()) fail("expected a map, found " + describe(node_));
  std::vector<std::string> out;
  for (const auto& kv : node_) out.push_back(kv.first.Scalar());
  return out;
}

void ConfigNode::expect_keys(std::initializer_list<std::string_view> allowed) const {
  if (!is_map()) fail("expected a map, found " + describe(node_));
  std::vector<std::string> seen;
  for (const auto& kv : node_) {
    const std::string key = kv.first.Scalar();
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
      ConfigNode(kv.first, file_, child_path(key)).fail("duplicate key '" + key + "'");
    }
    seen.push_back(key);
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string list;
    for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    ConfigNode(kv.first, file_, child_path(key))
        .fail("unknown key '" + key + "' (allowed: " + list + ")");
  }
}

double ConfigNode::as_double() const {
  if (!is_scalar()) fail("expected a number, found " + describe(node_));
  const std::string& text = node_.Scalar();
  double value = 0;
  std::size_t used = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) fail("expected a number, found '" + text + "'");
  if (!std::isfinite(value)) fail("expected a finite number, found '" + text + "'");
  return value;
}

int64_t ConfigNode::as_int() const {
  if (!is_scalar()) fail("expected an integer, found " + describe(node_));
  const std::string& text = node_.Scalar();
  int64_t value = 0;
  std::size_t used = 0;
  try {
    value = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) fail("expected an integer, found '" + text + "'");
  return value;
}

bool ConfigNode::as_bool() const {
  if (!is_scalar()) fail("expected true or false, found " + describe(node_));
  const std::string& text = node_.Scalar();
  if (text == "true") return true;
  if (text == "false") return false;
  fail("expected true or false, found '" + text + "'");
}

std::string ConfigNode::as_string() const {
  if (!is_scalar()) fail("expected a string, found " + describe(node_));
  return node_.Scalar();
}

std::vector<double> ConfigNode::as_double_list() const {
  std::vector<double> out;
  for (const auto& e : elements()) out.push_back(e.as_double());
  return out;
}

double ConfigNode::get_double(std::string_view key, double fallback) const {
  auto child = find(key);
  return child ? child->as_double() : fallback;
}

int64_t ConfigNode::get_int(std::string_view key, int64_t fallback) const {
  auto child = find(key);
  return child ? child->as_int() : fallback;
}

bool ConfigNode::get_bool(std::string_view key, bool fallback) const {
  auto child = find(key);
  return child ? child->as_bool() : fallback;
}

std::string ConfigNode::get_string(std::string_view key, const std::string& fallback) const {
  auto child = find(key);
  return child ? child->as_string() : fallback;
}

}  // namespace vcockpit
