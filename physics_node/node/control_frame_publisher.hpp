#pragma once
// cockpit/control_frame: every control's position and coordinate at each multiple of the frame
// period of the world's time (physics_node --control-frame-hz, default 100): the aircraft
// systems' input and clock (idl/systems.idl). The same frames as the run recorder's
// control_frames.csv (physics_io::control_frame), so systems_node computes the same in a rig as
// offline. Event profile: reliable, keep last 100, so publishing never blocks the loop.

#include <cstdint>

#include "dds/dds_participant.hpp"
#include "idl/topics/systems_topics.hpp"
#include "physics_node/physics/world.hpp"
#include "systems/systems_engine.hpp"

namespace vcockpit::physics_node {

class ControlFramePublisher {
 public:
  // `hz` 0: none. Throws std::invalid_argument unless the period is a whole number of steps.
  ControlFramePublisher(DdsParticipant& participant, const physics::Scene& scene, double hz);
  // After a step: a frame when the world's time is on the period.
  void after_step(const physics::World& world);
  // The world was reset to the scene's start (an instructor's reset): a frame at once, at the
  // world's time, with the reset counted, so the systems start again at that point of the stream.
  void after_reset_to_start(const physics::World& world);
  uint64_t published() const { return seq_; }
  // At a stop: until the systems nodes acknowledged the last frames, or the timeout.
  void flush(int64_t timeout_ns) const { writer_.wait_for_acknowledgments(timeout_ns); }
  // Lockstep with a systems node (--wait-frame-readers): until `count` readers have matched, or
  // the timeout; false on the timeout.
  bool wait_for_readers(int count, int64_t timeout_ns) const {
    return writer_.wait_for_matched(count, timeout_ns);
  }

 private:
  int64_t period_ns_ = 0;
  Writer<cockpit::ControlFrame> writer_;
  cockpit::ControlFrame msg_;
  systems::ControlFrame frame_;
  uint64_t seq_ = 0;
  uint32_t start_resets_ = 0;
  void publish(const physics::World& world);
};

}  // namespace vcockpit::physics_node
