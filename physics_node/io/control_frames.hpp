#pragma once
// The cockpit's controls as the aircraft systems see them (systems/): each control's name, joint
// and positions, and a frame of their positions and coordinates at the world's time. The run
// recorder writes the frames as control_frames.csv; the physics node publishes the same frames on
// cockpit/control_frame, so systems_node gets the same inputs offline and in a rig.

#include <vector>

#include "physics_node/physics/world.hpp"
#include "systems/systems_engine.hpp"

namespace vcockpit::physics_io {

std::vector<systems::ControlSpec> control_specs(const physics::Scene& scene);
// The world's controls now (q in m or rad). False when a coordinate is not finite (the frame is
// then not written: the physics' own checks report the body).
bool control_frame(const physics::World& world, systems::ControlFrame& frame);

}  // namespace vcockpit::physics_io
