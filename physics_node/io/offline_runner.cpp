#include "physics_node/io/offline_runner.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "common/clock.hpp"
#include "common/terminal_progress.hpp"
#include "hand/glove_log.hpp"
#include "hand/sample_validator.hpp"
#include "physics_node/io/hand_motion_peak.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "physics_node/io/run_recorder.hpp"

namespace vcockpit::physics_io {


RunSummary run_offline(physics::Scene scene, const OfflineOptions& options) {
  check_input_timing(options.timing);
  std::vector<hand::GloveSample> samples;
  hand::InputCounts input_counts;
  if (!options.log_path.empty()) {
    if (!scene.has_hands()) {
      throw std::invalid_argument(options.scene_path + ": the scene has no hand, so a glove log "
                                                       "cannot drive it");
    }
    hand::GloveLog log = hand::read_glove_log(options.log_path, scene.hands[0]);
    for (const std::string& warning : hand::glove_log_warnings(log)) spdlog::warn("{}", warning);
    // the checks a live node makes (the reader has already refused what a file cannot hold)
    hand::SampleValidator validator(scene.hands[0]);
    for (hand::GloveSample& s : log.samples) {
      if (validator.accept(s)) samples.push_back(s);
    }
    input_counts = log.counts;
    input_counts += validator.counts();
  }
  if (!options.duration_s && samples.empty()) {
    throw std::invalid_argument("give --log GLOVE.csv or --duration S");
  }
  if (options.duration_s && !(*options.duration_s > 0)) {
    throw std::invalid_argument("--duration must be positive");
  }
  const int64_t end_ns = options.duration_s ? std::llround(*options.duration_s * 1e9)
                                            : samples.back().t_ns - samples.front().t_ns;
  const int64_t interval_ns = output_interval_ns(options.output_hz, scene);

  RunRecorder recorder(options.out_dir, interval_ns);

  RunSummary summary;
  summary.scene_path = options.scene_path;
  summary.log_path = options.log_path;
  summary.stage_total_s.assign(physics::kStageCount, 0.0);
  summary.timing = options.timing;
  HandMotionPeak hand_peak;
  physics::World world(std::move(scene));
  TerminalProgress progress;
  const auto wall_start = std::chrono::steady_clock::now();
  auto step = [&] {
    world.step();
    recorder.after_step(world);
    for (const auto& f : world.step_faults()) {
      spdlog::warn("object '{}' (#{}): {} at {:.3f} s, put back where it was at the step's start, "
                   "at rest (further faults of it are counted, not logged)",
                   world.scene().objects[f.object].name, f.object,
                   physics::body_fault_name(f.what), ns_to_seconds(f.first_t_ns));
    }
    const auto& pen = world.hand_penetration();
    summary.penetration_max_m = std::max(summary.penetration_max_m, pen.max_m);
    summary.penetration_sum_m += pen.sum_m;
    summary.penetration_points += static_cast<uint64_t>(pen.points);
    for (int s = 0; s < physics::kStageCount; ++s) {
      summary.stage_total_s[s] += static_cast<double>(world.stage_times().ns[s]) * 1e-9;
    }
    summary.substeps = std::max(summary.substeps, world.substeps());
    summary.substeps_total += static_cast<uint64_t>(world.substeps());
    hand_peak.record(world);
    if (world.step_count() % 100 == 0) {
      const double wall_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
      const double sim_s = ns_to_seconds(world.time_ns());
      progress.update(monotonic_now_ns(), sim_s, ns_to_seconds(end_ns),
                      wall_s > 0 ? sim_s / wall_s : 0.0, world.step_count());
    }
  };
  if (samples.empty()) {
    recorder.start(world);
    while (world.time_ns() < end_ns) step();
  } else {
    // the first sample sets the hand before the first row; the world then steps through each
    // interval with the hand interpolated, up to the last sample or the end
    ReplayDriver driver(world, world.scene().hands[0], options.timing);
    driver.feed(samples.front(), step);
    recorder.start(world);
    for (std::size_t i = 1; i < samples.size(); ++i) {
      if (driver.world_time_of(samples[i]) > end_ns) {
        driver.push(samples[i]);  // the interval that holds the end
        break;
      }
      driver.feed(samples[i], step);
    }
    // without --duration the run ends where a lockstep replay of the log ends: at the last step
    // that ends by the last sample
    if (options.duration_s) driver.step_until(end_ns, step);
    input_counts += driver.counts();
    summary.have_input = true;
    summary.input = input_counts;
    spdlog::info("{}: {}", options.log_path, hand::input_counts_text(input_counts));
  }
  progress.finish();
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  summary.steps = world.step_count();
  summary.simulated_s = ns_to_seconds(world.time_ns());
  summary.grasps = recorder.events().grasps();
  summary.releases = recorder.events().releases();
  summary.control_events = recorder.events().control_events();
  summary.hand_peak_wrist_mps = hand_peak.wrist_mps();
  summary.hand_peak_joint_radps = hand_peak.joint_radps();
  summary.non_finite_refused = recorder.refused();
  recorder.commit();
  write_summary(options.out_dir + "/summary.json", summary, world);
  return summary;
}

}  // namespace vcockpit::physics_io
