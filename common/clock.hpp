#pragma once
// Monotonic time in nanoseconds: the one clock every node stamps with, so stamps from different
// processes on the same machine compare directly.

#include <cstdint>
#include <ctime>

namespace vcockpit {

inline int64_t monotonic_now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

// Sleeps until an absolute monotonic time (no drift accumulates over a periodic loop).
inline void sleep_until_ns(int64_t deadline_ns) {
  timespec ts{};
  ts.tv_sec = deadline_ns / 1'000'000'000;
  ts.tv_nsec = deadline_ns % 1'000'000'000;
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) != 0) {
  }
}

constexpr int64_t seconds_to_ns(double s) { return static_cast<int64_t>(s * 1e9 + (s >= 0 ? 0.5 : -0.5)); }
constexpr double ns_to_seconds(int64_t ns) { return static_cast<double>(ns) * 1e-9; }

}  // namespace vcockpit
