#pragma once
// The offline runner's outputs (a contract other tools rely on; keep the names):
//   trajectories.csv  t_s,object,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,held_by,control_q,
//                     control_position: one row per dynamic object per output interval; held_by
//                     empty when free; a control's moving part adds its coordinate (m or rad)
//                     and position name (both empty for other objects)
//   events.jsonl      one JSON object per line: t_s, event (grasp|release), hand, object, reason,
//                     contacts (+ residual_force_N, residual_torque_Nm); or t_s, event "control",
//                     control, from, to (position names), hand and link (null unless pushed or
//                     grasped), cause (pushed|grasped|commanded|mechanism|object)
//   summary.json      steps, simulated and wall seconds, grasp/release counts, hand-object
//                     penetration max and mean (m), the hand's peak wrist and joint speeds,
//                     "input": the glove log's counts (hand::InputCounts: clamped values, missing
//                     columns, rejected samples, intervals interpolated, gaps bridged and not,
//                     glove lost) with the max gap and glove timeout used, control_events and
//                     "controls" (name -> final position name), final pose per object,
//                     non_finite_refused
//   control_frames.csv every control's position and coordinate at every output interval after
//                     the start: the aircraft systems' input (systems/control_frames_file.hpp)
// Every file is written to "<name>.partial" and renamed when the run completes.
//
// Only finite numbers are written (non_finite_guard.hpp): a trajectory row with a NaN or an
// infinity is left out; a JSON member holding one is left out of its record (a residual, a
// final position); each refusal is counted (summary.json's non_finite_refused, all three files)
// and named once in the log.

#include <cstdint>
#include <array>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "hand/input_counts.hpp"
#include "physics_node/io/input_timing.hpp"
#include "physics_node/io/non_finite_guard.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_io {

std::string hand_name(int hand_id);

class TrajectoryWriter {
 public:
  explicit TrajectoryWriter(const std::string& path);
  void write(const physics::World& world);  // one row per dynamic object (finite ones)
  void commit() { file_.commit(); }
  uint64_t refused() const { return guard_.refused(); }  // rows left out

 private:
  AtomicFile file_;
  NonFiniteGuard guard_{"trajectories.csv"};
  std::string row_;  // one row's text, its capacity kept from row to row
  // What an object's row was made of (pose, velocities, control coordinate, all bit for bit;
  // its holders and control position) and its text after the time
  struct RowState {
    std::array<double, 19> values{};
    uint8_t holders = 0;
    int held_by = physics::kNotHeld;
    int position = -1;
    bool operator==(const RowState& o) const;
  };
  struct Memo {
    RowState state;
    std::string tail;
    bool valid = false;
  };
  std::vector<Memo> last_;  // per object (dynamic ones used)
};

class EventWriter {
 public:
  explicit EventWriter(const std::string& path);
  void write(const physics::World& world);  // the last step's events
  void write(const physics::GraspEvent& event, const std::string& object_name);
  void write(const physics::ControlEvent& event, const physics::Scene& scene);
  void commit() { file_.commit(); }
  int grasps() const { return grasps_; }
  // grasps and releases by hand id (0 right, 1 left)
  int grasps(int hand_id) const { return hand_id >= 0 && hand_id < 2 ? hand_grasps_[hand_id] : 0; }
  int releases(int hand_id) const { return hand_id >= 0 && hand_id < 2 ? hand_releases_[hand_id] : 0; }
  int releases() const { return releases_; }
  int control_events() const { return controls_; }
  uint64_t refused() const { return guard_.refused(); }  // members left out

 private:
  AtomicFile file_;
  NonFiniteGuard guard_{"events.jsonl"};
  int grasps_ = 0;
  int releases_ = 0;
  std::array<int, 2> hand_grasps_{};
  std::array<int, 2> hand_releases_{};
  int controls_ = 0;
};

// One hand's part in a run: its log's input counts, its grasps and releases.
struct HandRunSummary {
  int hand_id = 0;
  std::string log_path;
  hand::InputCounts input;
  int grasps = 0;
  int releases = 0;
};

struct RunSummary {
  std::string scene_path;
  std::vector<std::string> log_paths;
  uint64_t steps = 0;
  double simulated_s = 0.0;
  double wall_s = 0.0;
  int grasps = 0;
  int releases = 0;
  int control_events = 0;
  double penetration_max_m = 0.0;
  double penetration_sum_m = 0.0;
  uint64_t penetration_points = 0;
  std::vector<double> stage_total_s;  // per Stage
  int stage_timing_every = 1;          // the steps per timed one (World::set_stage_timing_every)
  double hand_peak_wrist_mps = 0.0;    // HandMotionPeak
  double hand_peak_joint_radps = 0.0;
  bool have_input = false;  // a glove log drove the hand: `input` and `timing` apply
  hand::InputCounts input;  // over every hand's log
  std::vector<HandRunSummary> hands;  // per log
  InputTiming timing;
  uint64_t non_finite_refused = 0;    // left out of trajectories.csv and events.jsonl
};

// Its own refusals are added to summary.non_finite_refused in the file's count.
void write_summary(const std::string& path, const RunSummary& summary, const physics::World& world);

}  // namespace vcockpit::physics_io
