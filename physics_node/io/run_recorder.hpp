#pragma once
// What a run writes as it steps (run_outputs.hpp): a trajectory row at the start and every
// output interval, each step's grasp and control events, and a control frame every frame
// interval after the start (control_frames.csv, systems/control_frames_file.hpp: the aircraft
// systems' input, as cockpit/control_frame carries it in a rig). The offline runner and a lockstep
// node both record through it, so a lockstep replay's trajectories.csv and events.jsonl are the
// offline runner's byte for byte.

#include <cstdint>
#include <string>

#include "physics_node/io/control_frames.hpp"
#include "physics_node/io/run_outputs.hpp"
#include "physics_node/physics/world.hpp"
#include "systems/control_frames_file.hpp"

namespace vcockpit::physics_io {

// Trajectory rows per second as whole steps; throws std::invalid_argument when not positive or
// not a whole number of the scene's steps.
int64_t output_interval_ns(double output_hz, const physics::Scene& scene);

class RunRecorder {
 public:
  // Creates `out_dir`; the files appear there (renamed from .partial) on commit().
  // `frame_interval_ns`: control_frames.csv's period (the node's --control-frame-hz: the same
  // frames as cockpit/control_frame whatever --output-hz is).
  RunRecorder(const std::string& out_dir, int64_t interval_ns, int64_t frame_interval_ns,
              const physics::Scene& scene);

  void start(const physics::World& world) { trajectories_.write(world); }  // the first row
  void after_step(const physics::World& world) {
    events_.write(world);
    if (world.time_ns() % interval_ns_ == 0) trajectories_.write(world);
    if (world.time_ns() % frame_interval_ns_ == 0 && physics_io::control_frame(world, frame_))
      control_frames_.write(frame_);
  }
  void commit() {
    trajectories_.commit();
    events_.commit();
    control_frames_.commit();
  }

  const EventWriter& events() const { return events_; }
  uint64_t refused() const { return trajectories_.refused() + events_.refused(); }

 private:
  int64_t interval_ns_;
  int64_t frame_interval_ns_;
  TrajectoryWriter trajectories_;
  EventWriter events_;
  systems::ControlFramesWriter control_frames_;
  systems::ControlFrame frame_;
};

}  // namespace vcockpit::physics_io
