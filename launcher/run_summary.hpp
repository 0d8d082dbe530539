#pragma once
// What a rig run did, gathered once when its nodes have stopped, and OUT/summary.json written
// from it with nlohmann::json (scripts/bench_report.py and tests/integration/rig_test read it;
// keep the keys). console_report prints the same figures.

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "launcher/rig_config.hpp"
#include "launcher/rig_monitor.hpp"

namespace vcockpit::rig {

class Supervisor;

struct RunSummary {
  struct FinalObject {  // the last state a dynamic object was published in
    std::string name;
    double sim_time_s = 0.0;
    std::array<double, 3> position{};
    std::array<double, 4> quaternion_wxyz{};
    int held_by = -1;  // hand id, or kNoObject
  };
  struct NodeOutcome {
    std::string name;
    int exit_status = 0;  // exit code, or 128 + signal
    int restarts = 0;
  };

  // One hand's input on the physics node (its last node_status).
  struct HandOutcome {
    int hand_id = 0;
    uint64_t samples = 0;
    uint64_t glove_lost = 0;
    uint32_t grasps = 0;
    bool tracking = false;
  };
  std::string rig_path;
  std::string log_path;
  std::string left_log_path;  // empty: no left hand's log
  std::vector<HandOutcome> hands;
  int domain_id = 0;
  std::string out_dir;
  std::string ended;  // why the run ended
  bool ok = true;     // no required node died
  double wall_s = 0.0;
  uint64_t samples_replayed = 0;  // the input nodes' last published counts (ends_run, glove_driver*)
  int grasps = 0;
  int releases = 0;
  std::vector<SeenEvent> events;
  std::vector<SeenControlEvent> control_events;
  std::map<std::string, std::string> controls;  // name -> last position
  std::vector<SeenSystemsEvent> systems_events;  // empty without a systems node
  std::map<std::string, std::string> systems;    // each system's last value as words
  std::vector<SeenProcedure> procedures;         // the lesson's score; empty without a lesson
  uint64_t frames_rendered = 0;  // the image generator's last published count
  int snapshots_written = 0;     // PNGs in OUT/frames
  double physics_step_rate_hz = 0.0;
  uint64_t late_steps = 0;
  // glove sample -> rendered frame (ms), and where it goes
  double latency_p50_ms = 0.0, latency_p99_ms = 0.0, latency_max_ms = 0.0;
  std::size_t latency_samples = 0;
  double age_at_render_start_p50_ms = 0.0, age_at_render_start_p99_ms = 0.0;
  double render_p50_ms = 0.0, render_p99_ms = 0.0;
  std::vector<FinalObject> final_objects;  // by name
  std::vector<NodeOutcome> nodes;          // in the rig file's order
};

RunSummary collect_run_summary(const RigConfig& rig, const std::string& out_dir,
                               const Supervisor& supervisor, const RigMonitor& monitor,
                               double wall_s);

// Written under a temporary name and renamed into place; throws FileError naming the path.
void write_run_summary(const std::string& path, const RunSummary& summary);

}  // namespace vcockpit::rig
