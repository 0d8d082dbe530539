#include "physics_node/node/control_frame_publisher.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "physics_node/io/control_frames.hpp"

namespace vcockpit::physics_node {

ControlFramePublisher::ControlFramePublisher(DdsParticipant& participant,
                                             const physics::Scene& scene, double hz)
    : writer_(participant.make_writer<cockpit::ControlFrame>("control_frames")) {
  if (hz == 0.0) return;
  const int64_t period_ns = physics_io::control_frame_interval_ns(hz, scene);
  if (scene.controls.size() > 64)
    throw std::invalid_argument("cockpit/control_frame carries at most 64 controls; the scene has " +
                                std::to_string(scene.controls.size()));
  period_ns_ = period_ns;
}

void ControlFramePublisher::after_step(const physics::World& world) {
  if (period_ns_ == 0 || world.time_ns() % period_ns_ != 0) return;
  publish(world);
}

void ControlFramePublisher::after_reset_to_start(const physics::World& world) {
  ++start_resets_;
  if (period_ns_ != 0) publish(world);
}

void ControlFramePublisher::publish(const physics::World& world) {
  if (!physics_io::control_frame(world, frame_)) return;
  msg_.seq(++seq_);
  msg_.sim_time_ns(world.time_ns());
  msg_.position().assign(frame_.position.begin(), frame_.position.end());
  msg_.coordinate().assign(frame_.q.begin(), frame_.q.end());
  msg_.start_resets(start_resets_);
  writer_.write(msg_);
}

}  // namespace vcockpit::physics_node
