#pragma once
// One node of the rig as a child process: started with the rig's environment, its stdout and
// stderr read through a pipe and written line by line, prefixed with its name, to its own log
// file and the rig's combined log.

#include <sys/types.h>

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "launcher/rig_config.hpp"

namespace vcockpit::rig {

class NodeProcess {
 public:
  // `restart_argv`: the command when it is started again (empty: `argv` again)
  NodeProcess(NodeSpec spec, std::vector<std::string> argv, std::string log_path,
              std::vector<std::string> restart_argv = {});
  ~NodeProcess();
  NodeProcess(const NodeProcess&) = delete;
  NodeProcess& operator=(const NodeProcess&) = delete;

  // Starts (or restarts) the process; throws std::runtime_error naming the executable.
  void start(const std::map<std::string, std::string>& env);
  bool running() const { return pid_ > 0; }
  // Reaps the process if it ended: true once, with the status in exit_status().
  bool reap();
  void signal(int sig) const;
  // Reads what the process wrote and logs complete lines. Returns false at end of output.
  void pump(std::FILE* combined);

  const NodeSpec& spec() const { return spec_; }
  pid_t pid() const { return pid_; }
  int fd() const { return fd_; }
  int exit_status() const { return exit_status_; }  // exit code, or 128 + signal
  int64_t started_at_ns() const { return started_at_ns_; }
  int64_t ended_at_ns() const { return ended_at_ns_; }
  int restarts() const { return restarts_; }

 private:
  void write_line(const std::string& line, std::FILE* combined);

  NodeSpec spec_;
  std::vector<std::string> argv_;
  std::vector<std::string> restart_argv_;
  std::FILE* log_ = nullptr;
  pid_t pid_ = -1;
  int fd_ = -1;
  int exit_status_ = 0;
  int64_t started_at_ns_ = 0;
  int64_t ended_at_ns_ = 0;
  int starts_ = 0;
  int restarts_ = 0;
  std::string partial_;
};

}  // namespace vcockpit::rig
