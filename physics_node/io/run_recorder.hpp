#pragma once
// What a run writes as it steps (run_outputs.hpp): a trajectory row at the start and every
// output interval, and each step's grasp and control events. The offline runner and a lockstep
// node both record through it, so a lockstep replay's trajectories.csv and events.jsonl are the
// offline runner's byte for byte.

#include <cstdint>
#include <string>

#include "physics_node/io/run_outputs.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_io {

// Trajectory rows per second as whole steps; throws std::invalid_argument when not positive or
// not a whole number of the scene's steps.
int64_t output_interval_ns(double output_hz, const physics::Scene& scene);

class RunRecorder {
 public:
  // Creates `out_dir`; the files appear there (renamed from .partial) on commit().
  RunRecorder(const std::string& out_dir, int64_t interval_ns);

  void start(const physics::World& world) { trajectories_.write(world); }  // the first row
  void after_step(const physics::World& world) {
    events_.write(world);
    if (world.time_ns() % interval_ns_ == 0) trajectories_.write(world);
  }
  void commit() {
    trajectories_.commit();
    events_.commit();
  }

  const EventWriter& events() const { return events_; }
  uint64_t refused() const { return trajectories_.refused() + events_.refused(); }

 private:
  int64_t interval_ns_;
  TrajectoryWriter trajectories_;
  EventWriter events_;
};

}  // namespace vcockpit::physics_io
