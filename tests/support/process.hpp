#pragma once
// Real child processes for integration tests: spawn with arguments and extra environment, wait
// with a timeout, signal, and never leave one running (the destructor kills what is left).

#include <sys/types.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace vcockpit::test {

class ChildProcess {
 public:
  // Starts `argv[0]` with its arguments. stdout and stderr go to `log_path` (appended) if given.
  ChildProcess(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env,
               const std::string& log_path = "");
  ~ChildProcess();
  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  bool running();
  // Exit code, 128 + signal if killed by one, or -1 if still running after the timeout.
  int wait(int64_t timeout_ns);
  void signal(int sig);
  // SIGTERM, then SIGKILL after `grace_ns`; returns the exit status as wait() does.
  int stop(int64_t grace_ns = 10'000'000'000);

 private:
  pid_t pid_ = -1;
  int status_ = -1;
  bool reaped_ = false;
};

// Fast DDS's files in /dev/shm (shared-memory segments, their semaphores, data-sharing pools),
// to check a test leaves none behind. Only these: other programs' files (a browser's, Python's
// semaphores) come and go with tests running beside it.
std::vector<std::string> list_dds_shm();
// Entries of `after` not in `before`.
std::vector<std::string> new_entries(const std::vector<std::string>& before,
                                     const std::vector<std::string>& after);
// Removes the given /dev/shm entries (cleanup after the assertion, so a failure does not leak).
void remove_dds_shm(const std::vector<std::string>& names);

// Directory of the test's own executables (build/bin), from VCOCKPIT_BIN_DIR set by ctest.
std::string bin_dir();
// A fresh empty directory under the build tree for this test's files (named after `name` and
// the running test, so tests of one binary running in parallel never share one).
std::string make_temp_dir(const std::string& name);

}  // namespace vcockpit::test
