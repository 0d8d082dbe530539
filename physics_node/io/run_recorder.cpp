#include "physics_node/io/run_recorder.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace vcockpit::physics_io {

int64_t output_interval_ns(double output_hz, const physics::Scene& scene) {
  if (!(output_hz > 0) || !std::isfinite(output_hz)) {
    throw std::invalid_argument("--output-hz must be positive");
  }
  const int64_t step_ns = std::llround(scene.step_s * 1e9);
  const int64_t interval = std::llround(1e9 / output_hz);
  if (interval % step_ns != 0) {
    throw std::invalid_argument("--output-hz " + std::to_string(output_hz) +
                                " is not a whole number of steps of " +
                                std::to_string(scene.step_s) + " s");
  }
  return interval;
}

namespace {
const std::string& created(const std::string& dir) {
  std::filesystem::create_directories(dir);
  return dir;
}
}  // namespace

RunRecorder::RunRecorder(const std::string& out_dir, int64_t interval_ns,
                         int64_t frame_interval_ns, const physics::Scene& scene)
    : interval_ns_(interval_ns),
      frame_interval_ns_(frame_interval_ns),
      trajectories_(created(out_dir) + "/trajectories.csv"),
      events_(out_dir + "/events.jsonl"),
      control_frames_(out_dir + "/control_frames.csv", control_specs(scene)) {}

}  // namespace vcockpit::physics_io
