#pragma once
// Per-step wall times inside a Google Benchmark loop, reported as p50/p99/max counters (us):
// a mean hides the slow steps a 1 kHz loop cares about.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

namespace vcockpit::bench {

class StepTiming {
 public:
  explicit StepTiming(std::size_t expected) { ns_.reserve(expected); }

  template <class Fn>
  void time(Fn&& fn) {
    const auto start = std::chrono::steady_clock::now();
    fn();
    ns_.push_back(std::chrono::duration_cast<std::chrono::nanoseconds>(
                      std::chrono::steady_clock::now() - start)
                      .count());
  }

  void report(benchmark::State& state) {
    if (ns_.empty()) return;
    std::sort(ns_.begin(), ns_.end());
    const auto at = [&](double q) {
      const auto i = static_cast<std::size_t>(q * static_cast<double>(ns_.size() - 1) + 0.5);
      return static_cast<double>(ns_[i]) * 1e-3;
    };
    state.counters["p50_us"] = at(0.50);
    state.counters["p99_us"] = at(0.99);
    state.counters["max_us"] = static_cast<double>(ns_.back()) * 1e-3;
  }

 private:
  std::vector<int64_t> ns_;
};

}  // namespace vcockpit::bench
