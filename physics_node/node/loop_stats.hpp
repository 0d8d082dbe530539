#pragma once
// What the physics node measures about its own loop, for the glove -> physics latency benchmark
// (bench/dds_latency_floor measures the same two figures with nothing but Fast DDS around them):
//   dds_transit    SampleInfo reception - source timestamp: Fast DDS's own wall-clock stamps,
//                  written by the glove driver's writer and set when the reader's history got it.
//   age_at_step    monotonic now when the loop takes the sample - HandSample.source_stamp_ns:
//                  the transit plus the wait for the next step slot (up to one period).
//   step_compute   World::step, end - start.
//   hand_lag       real time, every tracked step: monotonic now at the step's end - the source
//                  stamp of the hand it shows (interpolated between the two samples' stamps, as
//                  the hand is). How far the world's hand trails the glove: the transit, the
//                  interpolation delay and any wait for a late sample.
// Histograms are allocated once here; recording in the loop never allocates.
// Header-only: the node's sources are listed in physics_node/CMakeLists.txt.

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "dds/dds_participant.hpp"
#include "common/json_file.hpp"
#include "common/latency_histogram.hpp"
#include "hand/input_counts.hpp"

namespace vcockpit::physics_node {

struct LoopStats {
  LatencyHistogram dds_transit;
  LatencyHistogram age_at_step;
  LatencyHistogram step_compute;
  LatencyHistogram hand_lag;

  void record_sample(const dds::SampleInfo& info, int64_t source_stamp_ns, int64_t take_ns) {
    dds_transit.record_ns(info.reception_timestamp.to_ns() - info.source_timestamp.to_ns());
    age_at_step.record_ns(take_ns - source_stamp_ns);
  }
};

// The --stats-out file: what applies to the mode (lockstep has no rate or late steps: it steps
// as fast as its input comes, and reports the simulated time instead).
struct StatsReport {
  std::string mode;  // "realtime" or "lockstep"
  double duration_s = 0.0;
  uint64_t steps = 0;
  std::optional<double> rate_hz;
  std::optional<uint64_t> late_steps;
  std::optional<double> simulated_s;
  uint64_t samples = 0;
  uint64_t rejected = 0;
  hand::InputCounts input;
  std::optional<int64_t> input_delay_ns;  // real time only
  double hand_peak_wrist_mps = 0.0;
  double hand_peak_joint_radps = 0.0;
};

// Written under a temporary name and renamed into place; throws FileError naming the path.
inline void write_stats_json(const std::string& path, const StatsReport& r, const LoopStats& s) {
  nlohmann::ordered_json j;
  j["mode"] = r.mode;
  j["duration_s"] = r.duration_s;
  j["steps"] = r.steps;
  if (r.rate_hz) j["rate_hz"] = *r.rate_hz;
  if (r.late_steps) j["late_steps"] = *r.late_steps;
  if (r.simulated_s) j["simulated_s"] = *r.simulated_s;
  j["samples"] = r.samples;
  j["rejected"] = r.rejected;
  j["dds_transit_us"] = latency_json_us(s.dds_transit);
  j["age_at_step_us"] = latency_json_us(s.age_at_step);
  j["step_compute_us"] = latency_json_us(s.step_compute);
  if (r.input_delay_ns) {
    j["input_delay_ms"] = static_cast<double>(*r.input_delay_ns) * 1e-6;
    j["hand_lag_us"] = latency_json_us(s.hand_lag);
  }
  j["hand_peak_wrist_speed_mps"] = r.hand_peak_wrist_mps;
  j["hand_peak_joint_speed_radps"] = r.hand_peak_joint_radps;
  j["input"] = hand::input_counts_json(r.input);
  write_json_file(path, j);
}

}  // namespace vcockpit::physics_node
