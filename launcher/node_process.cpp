#include "launcher/node_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <stdexcept>

#include "common/clock.hpp"

extern char** environ;

namespace vcockpit::rig {

NodeProcess::NodeProcess(NodeSpec spec, std::vector<std::string> argv, std::string log_path,
                         std::vector<std::string> restart_argv)
    : spec_(std::move(spec)), argv_(std::move(argv)), restart_argv_(std::move(restart_argv)) {
  if (restart_argv_.empty()) restart_argv_ = argv_;
  log_ = std::fopen(log_path.c_str(), "w");
  if (!log_) throw std::runtime_error(log_path + ": cannot create: " + std::strerror(errno));
}

NodeProcess::~NodeProcess() {
  if (fd_ >= 0) close(fd_);
  if (log_) std::fclose(log_);
}

void NodeProcess::start(const std::map<std::string, std::string>& env) {
  std::vector<std::string> env_strings;
  for (char** e = environ; *e; ++e) {
    const std::string entry(*e);
    if (!env.count(entry.substr(0, entry.find('=')))) env_strings.push_back(entry);
  }
  for (const auto& [key, value] : env) env_strings.push_back(key + "=" + value);
  std::vector<std::string>& argv = starts_ > 0 ? restart_argv_ : argv_;
  std::vector<char*> c_argv, c_env;
  for (auto& a : argv) c_argv.push_back(a.data());
  c_argv.push_back(nullptr);
  for (auto& e : env_strings) c_env.push_back(e.data());
  c_env.push_back(nullptr);

  int pipe_fds[2];
  if (pipe2(pipe_fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe: " + std::string(std::strerror(errno)));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
  const int rc = posix_spawn(&pid_, c_argv[0], &actions, nullptr, c_argv.data(), c_env.data());
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_fds[1]);
  if (rc != 0) {
    close(pipe_fds[0]);
    pid_ = -1;
    throw std::runtime_error("cannot start " + argv_[0] + ": " + std::strerror(rc));
  }
  if (fd_ >= 0) close(fd_);
  fd_ = pipe_fds[0];
  fcntl(fd_, F_SETFL, O_NONBLOCK);
  started_at_ns_ = monotonic_now_ns();
  if (starts_++ > 0) ++restarts_;
  std::fprintf(log_, "---- started pid %d:", static_cast<int>(pid_));
  for (const auto& a : argv) std::fprintf(log_, " %s", a.c_str());
  std::fprintf(log_, "\n");
  std::fflush(log_);
}

bool NodeProcess::reap() {
  if (pid_ <= 0) return false;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) != pid_) return false;
  exit_status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  ended_at_ns_ = monotonic_now_ns();
  pid_ = -1;
  return true;
}

void NodeProcess::signal(int sig) const {
  if (pid_ > 0) ::kill(pid_, sig);
}

void NodeProcess::pump(std::FILE* combined) {
  if (fd_ < 0) return;
  char buf[4096];
  while (true) {
    const ssize_t n = read(fd_, buf, sizeof buf);
    if (n <= 0) {
      if (n == 0) {  // the process closed its output
        if (!partial_.empty()) write_line(partial_, combined);
        partial_.clear();
        close(fd_);
        fd_ = -1;
      }
      return;
    }
    partial_.append(buf, static_cast<std::size_t>(n));
    for (std::size_t nl = partial_.find('\n'); nl != std::string::npos; nl = partial_.find('\n')) {
      write_line(partial_.substr(0, nl), combined);
      partial_.erase(0, nl + 1);
    }
  }
}

void NodeProcess::write_line(const std::string& line, std::FILE* combined) {
  std::fprintf(log_, "[%s] %s\n", spec_.name.c_str(), line.c_str());
  std::fflush(log_);
  if (combined) {
    std::fprintf(combined, "[%s] %s\n", spec_.name.c_str(), line.c_str());
    std::fflush(combined);
  }
}

}  // namespace vcockpit::rig
