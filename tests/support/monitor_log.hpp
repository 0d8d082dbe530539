#pragma once
// Reading what tests/integration/cockpit_monitor wrote (and the offline runner's outputs) back
// into structs, plus small file helpers for tests that watch a running rig.

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "tests/support/test_files.hpp"

namespace vcockpit::test {

struct SeenEvent {
  int64_t t_ns = 0;
  std::string kind;  // grasp | release
  int object = -1;
  std::string reason;
};

struct SeenStatus {
  std::string node;
  double rate_hz = 0;
  double input_hz = 0;
  uint64_t received = 0, rejected = 0, nonfinite = 0, range = 0, stale = 0, late = 0;
  bool alive = false;
  int state = 0;
  // the input counts (hand::InputCounts)
  uint64_t clamped = 0, missing = 0, intervals = 0, interpolated = 0, bridged = 0, unbridged = 0,
           intervals_late = 0, lost = 0;
  double longest_s = 0, delay_ms = 0;
};

struct SeenHand {
  int id = -1;  // 0 right, 1 left
  uint64_t seq = 0;
  int64_t sample_time_ns = 0;
  int64_t sim_time_ns = 0;
  int64_t received_ns = 0;  // monotonic, when the monitor took it
  int64_t source_stamp_ns = 0;
  bool tracking = false;
  int held = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

struct SeenObject {
  int64_t sim_time_ns = 0;
  int64_t received_ns = 0;  // watched states: monotonic, when the monitor took it
  int held = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector4d quaternion_wxyz = Eigen::Vector4d::Zero();
};

struct SeenFrame {
  uint64_t seq = 0;
  int width = 0, height = 0;
  int64_t source_stamp_ns = 0, start_ns = 0, end_ns = 0, received_ns = 0;
};

struct MonitorLog {
  std::vector<SeenEvent> events;
  std::vector<SeenStatus> statuses;
  std::vector<SeenHand> hands;
  std::map<int, SeenObject> objects;
  std::vector<SeenObject> watched;  // every state of --watch-object's object
  std::vector<SeenFrame> frames;

  static MonitorLog read(const std::string& path);
  // events.jsonl of the offline runner, as events (object ids are not in it: -1); each line
  // parsed with nlohmann::json, which throws on a line that is not JSON
  static MonitorLog from_events_jsonl(const std::string& path);
};

// "final" block of a summary.json (the offline runner's or rig_launcher's): object name ->
// position. Empty if the file is missing or not JSON.
std::map<std::string, Eigen::Vector3d> read_final_poses(const std::string& summary_path);

// Polls a growing text file until a line containing `needle` appears (after the first line
// containing `after_line`, if given). False on timeout.
bool wait_for_line(const std::string& path, const std::string& needle, int64_t timeout_ns,
                   const std::string& after_line = "");

}  // namespace vcockpit::test
