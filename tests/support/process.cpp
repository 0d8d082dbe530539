#include "tests/support/process.hpp"

#include <gtest/gtest.h>

#include <signal.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>
#include <utility>

#include "common/fast_dds_shm.hpp"

extern char** environ;

namespace vcockpit::test {
namespace fs = std::filesystem;

ChildProcess::ChildProcess(const std::vector<std::string>& argv,
                           const std::map<std::string, std::string>& env,
                           const std::string& log_path) {
  std::vector<std::string> env_strings;
  for (char** e = environ; *e; ++e) {
    const std::string entry(*e);
    const std::string key = entry.substr(0, entry.find('='));
    if (!env.count(key)) env_strings.push_back(entry);
  }
  for (const auto& [key, value] : env) env_strings.push_back(key + "=" + value);

  std::vector<char*> c_argv;
  for (const auto& a : argv) c_argv.push_back(const_cast<char*>(a.c_str()));
  c_argv.push_back(nullptr);
  std::vector<char*> c_env;
  for (const auto& e : env_strings) c_env.push_back(const_cast<char*>(e.c_str()));
  c_env.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!log_path.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(),
                                     O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  const int rc = posix_spawn(&pid_, c_argv[0], &actions, nullptr, c_argv.data(), c_env.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(rc));
  }
}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept
    : pid_(other.pid_), status_(other.status_), reaped_(other.reaped_) {
  other.pid_ = -1;
  other.reaped_ = true;
}

ChildProcess::~ChildProcess() {
  if (pid_ > 0 && !reaped_) stop(1'000'000'000);
}

bool ChildProcess::running() { return wait(0) == -1; }

int ChildProcess::wait(int64_t timeout_ns) {
  if (reaped_) return status_;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::nanoseconds(timeout_ns);
  while (true) {
    int raw = 0;
    const pid_t r = waitpid(pid_, &raw, WNOHANG);
    if (r == pid_) {
      reaped_ = true;
      status_ = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
      return status_;
    }
    if (std::chrono::steady_clock::now() >= deadline) return -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

void ChildProcess::signal(int sig) {
  if (pid_ > 0 && !reaped_) ::kill(pid_, sig);
}

int ChildProcess::stop(int64_t grace_ns) {
  signal(SIGTERM);
  int status = wait(grace_ns);
  if (status == -1) {
    signal(SIGKILL);
    status = wait(5'000'000'000);
  }
  return status;
}

std::vector<std::string> list_dds_shm() {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/dev/shm", ec)) {
    std::string name = entry.path().filename().string();
    if (is_fast_dds_shm_name(name)) out.push_back(std::move(name));
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> new_entries(const std::vector<std::string>& before,
                                     const std::vector<std::string>& after) {
  std::vector<std::string> out;
  std::set_difference(after.begin(), after.end(), before.begin(), before.end(),
                      std::back_inserter(out));
  return out;
}

void remove_dds_shm(const std::vector<std::string>& names) {
  std::error_code ec;
  for (const auto& name : names) fs::remove(fs::path("/dev/shm") / name, ec);
}

std::string bin_dir() {
  const char* dir = std::getenv("VCOCKPIT_BIN_DIR");
  if (!dir) throw std::runtime_error("VCOCKPIT_BIN_DIR is not set (run the test through ctest)");
  return dir;
}

std::string make_temp_dir(const std::string& name) {
  const char* base = std::getenv("VCOCKPIT_TEST_TMP");
  // one directory per test: ctest runs the tests of one binary in parallel processes
  std::string leaf = name;
  if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info()) {
    leaf += std::string("-") + info->test_suite_name() + "." + info->name();
  }
  fs::path dir = fs::path(base ? base : fs::temp_directory_path().string()) / leaf;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

}  // namespace vcockpit::test
