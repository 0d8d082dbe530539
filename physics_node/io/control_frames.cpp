#include "physics_node/io/control_frames.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

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

int64_t control_frame_interval_ns(double hz, const physics::Scene& scene) {
  const int64_t step_ns = std::llround(scene.step_s * 1e9);
  const int64_t period_ns = std::isfinite(hz) && hz > 0.0 ? std::llround(1e9 / hz) : 0;
  if (period_ns <= 0 || step_ns <= 0 || period_ns % step_ns != 0)
    throw std::invalid_argument("--control-frame-hz " + std::to_string(hz) +
                                " is not a whole number of steps of " +
                                std::to_string(scene.step_s) + " s");
  return period_ns;
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
