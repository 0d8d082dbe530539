#include "launcher/rig_config.hpp"

#include <filesystem>

#include "common/yaml_config.hpp"

namespace vcockpit::rig {
namespace {

namespace fs = std::filesystem;

std::string relative_to(const std::string& dir, const std::string& path) {
  return fs::path(path).is_absolute() ? path : (fs::path(dir) / path).lexically_normal().string();
}

NodeSpec parse_node(const ConfigNode& node) {
  node.expect_keys({"name", "command", "required", "restart_delay_s", "ends_run", "start_delay_s",
                    "with_left_log", "with_ui", "ui_args", "restart_args"});
  NodeSpec spec;
  spec.name = node.get_string("name");
  if (spec.name.empty() || spec.name.find_first_of("/ ") != std::string::npos) {
    node["name"].fail("a node name must be non-empty, without spaces or '/'");
  }
  for (const ConfigNode& arg : node["command"].elements()) spec.command.push_back(arg.as_string());
  if (spec.command.empty()) node["command"].fail("needs at least the executable");
  spec.required = node.get_bool("required", true);
  spec.ends_run = node.get_bool("ends_run", false);
  if (auto delay = node.find("restart_delay_s")) {
    spec.restart_delay_s = delay->as_double();
    if (*spec.restart_delay_s < 0) delay->fail("must be >= 0");
  }
  spec.start_delay_s = node.get_double("start_delay_s", 0.0);
  if (spec.start_delay_s < 0) node["start_delay_s"].fail("must be >= 0");
  spec.with_left_log = node.get_bool("with_left_log", false);
  spec.with_ui = node.get_bool("with_ui", false);
  if (auto args = node.find("ui_args"))
    for (const ConfigNode& arg : args->elements()) spec.ui_args.push_back(arg.as_string());
  if (auto args = node.find("restart_args")) {
    for (const ConfigNode& arg : args->elements()) spec.restart_args.push_back(arg.as_string());
    if (!spec.restart_delay_s) args->fail("a node that is never restarted (no restart_delay_s)");
  }
  return spec;
}

}  // namespace

RigConfig load_rig_config(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  root.expect_keys({"domain", "qos", "participant", "scene", "log", "left_log", "nodes"});
  RigConfig rig;
  rig.path = path;
  rig.config_dir = fs::absolute(fs::path(path)).parent_path().lexically_normal().string();
  rig.domain_id = static_cast<int>(root.get_int("domain", rig.domain_id));
  if (rig.domain_id < 0 || rig.domain_id > 232) root["domain"].fail("must be in 0..232");
  rig.qos_file = relative_to(rig.config_dir, root.get_string("qos", "qos.xml"));
  // the error_code form: a path the system refuses (too long, ...) is a bad value, not a crash
  std::error_code ec;
  if (!fs::exists(rig.qos_file, ec)) {
    root["qos"].fail("no such file: " + rig.qos_file + (ec ? " (" + ec.message() + ")" : ""));
  }
  rig.participant_profile = root.get_string("participant", rig.participant_profile);
  rig.scene_path = relative_to(rig.config_dir, root.get_string("scene", "cockpit.yaml"));
  if (auto log = root.find("log")) rig.log_path = relative_to(rig.config_dir, log->as_string());
  if (auto log = root.find("left_log"); log && !log->as_string().empty())
    rig.left_log_path = relative_to(rig.config_dir, log->as_string());
  const ConfigNode nodes = root["nodes"];
  for (const ConfigNode& node : nodes.elements()) {
    NodeSpec spec = parse_node(node);
    for (const auto& other : rig.nodes) {
      if (other.name == spec.name) node["name"].fail("duplicate node name '" + spec.name + "'");
    }
    rig.nodes.push_back(std::move(spec));
  }
  if (rig.nodes.empty()) nodes.fail("the rig needs at least one node");
  return rig;
}

std::vector<std::string> expand_command(const NodeSpec& node, const RigConfig& rig,
                                        const std::string& out_dir, bool restart) {
  std::vector<std::string> out;
  std::vector<std::string> args = node.command;
  if (rig.ui_port > 0) args.insert(args.end(), node.ui_args.begin(), node.ui_args.end());
  if (restart) args.insert(args.end(), node.restart_args.begin(), node.restart_args.end());
  for (std::string arg : args) {
    for (const auto& [key, value] : {std::pair<std::string, std::string>{"{log}", rig.log_path},
                                     {"{left_log}", rig.left_log_path},
                                     {"{scene}", rig.scene_path},
                                     {"{hands}", rig.left_log_path.empty() ? "right" : "right,left"},
                                     {"{out}", out_dir},
                                     {"{config}", rig.config_dir},
                                     {"{ui_port}", std::to_string(rig.ui_port)},
                                     {"{start_at_ns}", std::to_string(rig.start_at_ns)}}) {
      for (std::size_t at = arg.find(key); at != std::string::npos; at = arg.find(key, at)) {
        arg.replace(at, key.size(), value);
        at += value.size();
      }
    }
    out.push_back(arg);
  }
  return out;
}

bool node_starts(const NodeSpec& node, const RigConfig& rig) {
  return (!node.with_left_log || !rig.left_log_path.empty()) && (!node.with_ui || rig.ui_port > 0);
}

}  // namespace vcockpit::rig
