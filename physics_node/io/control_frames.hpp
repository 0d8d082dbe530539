#pragma once
// The cockpit's controls as the aircraft systems see them (systems/): each control's name, joint
// and positions, and a frame of their positions and coordinates at the world's time. The run
// recorder writes the frames as control_frames.csv; the physics node publishes the same frames on
// cockpit/control_frame, so systems_node gets the same inputs offline and in a rig.

#include <cstdint>
#include <vector>

#include "physics_node/physics/world.hpp"
#include "systems/systems_engine.hpp"

namespace vcockpit::physics_io {

std::vector<systems::ControlSpec> control_specs(const physics::Scene& scene);
// The period of control frames `hz` a second (--control-frame-hz) in ns; throws
// std::invalid_argument unless it is positive and a whole number of the scene's steps.
int64_t control_frame_interval_ns(double hz, const physics::Scene& scene);
// The world's controls now (q in m or rad). False when a coordinate is not finite (the frame is
// then not written: the physics' own checks report the body).
bool control_frame(const physics::World& world, systems::ControlFrame& frame);

}  // namespace vcockpit::physics_io
