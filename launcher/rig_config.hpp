#pragma once
// config/rig.yaml: which nodes the launcher starts, how, and what happens when one ends.
// Every bad value is a ConfigError naming file, line and key.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vcockpit::rig {

struct NodeSpec {
  std::string name;
  std::vector<std::string> command;  // command[0] is an executable in the build's bin directory
  bool required = true;
  std::optional<double> restart_delay_s;
  bool ends_run = false;
  double start_delay_s = 0.0;
  bool with_left_log = false;  // started only when the rig has a left hand's log ({left_log})
  bool with_ui = false;        // started only with the instructor station (rig_launcher --ui)
  std::vector<std::string> ui_args;  // added to the command with the instructor station
  // added when the launcher starts it again after it died (physics_node: --resume)
  std::vector<std::string> restart_args;
};

struct RigConfig {
  std::string path;
  std::string config_dir;  // directory of the rig file: {config}
  int domain_id = 7;
  std::string qos_file;
  std::string participant_profile = "loopback";
  std::string pki_dir;  // a secured profile's files (rig_launcher --pki); empty: none
  std::string scene_path;     // {scene}: the cockpit's scene file (default: cockpit.yaml)
  std::string log_path;       // {log}: the right hand's glove log
  std::string left_log_path;  // {left_log}: the left hand's, or empty (no left glove driver)
  int ui_port = 0;            // {ui_port}: the instructor station's page; 0: no station
  // {start_at_ns}: CLOCK_MONOTONIC time a few seconds after the launch, when the glove drivers
  // begin together (a lockstep world waits for every hand: one that began later would hold the
  // other's samples back for the whole run)
  int64_t start_at_ns = 0;
  std::vector<NodeSpec> nodes;
};

RigConfig load_rig_config(const std::string& path);
// The nodes this rig starts: those `with_left_log` only when it has a left log, those `with_ui`
// only with the instructor station.
bool node_starts(const NodeSpec& node, const RigConfig& rig);

// {scene}, {log}, {left_log}, {hands} ("right", or "right,left" with a left log), {out}, {config} and
// {ui_port} replaced in every argument; with the instructor station, the node's ui_args added;
// for a restart, its restart_args too.
std::vector<std::string> expand_command(const NodeSpec& node, const RigConfig& rig,
                                        const std::string& out_dir, bool restart = false);

}  // namespace vcockpit::rig
