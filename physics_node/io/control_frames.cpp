#include "physics_node/io/control_frames.hpp"

#include <cmath>

namespace vcockpit::physics_io {

std::vector<systems::ControlSpec> control_specs(const physics::Scene& scene) {
  std::vector<systems::ControlSpec> out;
  for (const physics::ControlSpec& c : scene.controls) {
    systems::ControlSpec spec{c.name, c.joint == physics::JointKind::kRevolute, {}};
    for (const physics::ControlPosition& p : c.positions) spec.positions.push_back(p.name);
    out.push_back(std::move(spec));
  }
  return out;
}

bool control_frame(const physics::World& world, systems::ControlFrame& frame) {
  const auto& controls = world.state().controls;
  frame.time_ns = world.time_ns();
  frame.position.resize(controls.size());
  frame.q.resize(controls.size());
  for (std::size_t i = 0; i < controls.size(); ++i) {
    if (!std::isfinite(controls[i].q)) return false;
    frame.position[i] = controls[i].position;
    frame.q[i] = controls[i].q;
  }
  return true;
}

}  // namespace vcockpit::physics_io
