#pragma once
// The rig's nodes as child processes: started in the rig file's order on its DDS domain, their
// output prefixed and saved under OUT/logs/ (one file per node and the combined rig.log), watched
// until the run ends, restarted or the rig stopped when one dies (per its policy), and stopped on
// the way out (SIGINT in reverse order, SIGKILL for any still running after 3 s).

#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "launcher/node_process.hpp"
#include "launcher/restart_guard.hpp"
#include "launcher/rig_config.hpp"

namespace vcockpit::rig {

class RigMonitor;

class Supervisor {
 public:
  // Executables are looked up in `bin_dir`; logs go to `out_dir`/logs/, which must exist.
  Supervisor(RigConfig rig, std::string out_dir, std::string bin_dir);
  ~Supervisor();
  Supervisor(const Supervisor&) = delete;
  Supervisor& operator=(const Supervisor&) = delete;

  // Starts every node, each after the previous one's start delay. Throws std::runtime_error
  // naming the rig file and a node whose executable is missing.
  void start_nodes();
  // Until the run ends: every node with ends_run has exited 0 (then, once the physics node has
  // taken every sample they published or after 60 s, 1.5 s more for the others to show the
  // end), a required node dies, or Ctrl-C. Restarts a node that has a restart delay. Polls
  // `monitor` on the way; with `status_line`, shows its status line on stderr every 250 ms.
  void supervise(RigMonitor& monitor, bool status_line);
  void stop_nodes();

  const std::vector<std::unique_ptr<NodeProcess>>& nodes() const { return nodes_; }
  bool failed() const { return failed_; }                        // a required node died
  const std::string& end_reason() const { return end_reason_; }  // "glove_driver finished", ...

 private:
  void pump_all(int timeout_ms);

  RigConfig rig_;
  std::string out_dir_;
  std::string bin_dir_;
  std::map<std::string, std::string> env_;
  std::vector<std::unique_ptr<NodeProcess>> nodes_;
  std::map<NodeProcess*, int64_t> restart_at_ns_;
  std::map<NodeProcess*, RestartGuard> restart_guards_;
  std::FILE* combined_ = nullptr;  // OUT/logs/rig.log
  bool failed_ = false;
  std::string end_reason_ = "stopped";
};

}  // namespace vcockpit::rig
