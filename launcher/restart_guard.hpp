#pragma once
// When to stop restarting a node. A node that cannot start (a scene with a typo, a missing model
// file) dies again at once on every restart: restarted forever, the rig looks alive while its log
// fills with the same error. A node that died soon after it started, several times in a row, is
// not restarted again; a death after a good run (a kill -9 in the middle of a session) starts
// the count over, so a node that runs and is killed now and then is always restarted.

#include <cstdint>

namespace vcockpit::rig {

class RestartGuard {
 public:
  static constexpr int64_t kSoon_ns = 2'000'000'000;  // died within 2 s of its start
  static constexpr int kInARow = 5;                    // that many times in a row: given up

  // A death of the node (exit `status`, 128 + signal when killed). True: restart it.
  bool allows_restart(int64_t started_ns, int64_t ended_ns, int status) {
    const bool soon = status != 0 && ended_ns - started_ns < kSoon_ns;
    quick_deaths_ = soon ? quick_deaths_ + 1 : 0;
    return quick_deaths_ < kInARow;
  }
  int quick_deaths() const { return quick_deaths_; }

 private:
  int quick_deaths_ = 0;
};

}  // namespace vcockpit::rig
