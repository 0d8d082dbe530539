#include "physics_node/io/offline_runner.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <climits>
#include <stdexcept>

#include "common/clock.hpp"
#include "common/terminal_progress.hpp"
#include "hand/glove_log.hpp"
#include "hand/sample_validator.hpp"
#include "physics_node/io/hand_motion_peak.hpp"
#include "physics_node/io/hand_timeline.hpp"
#include "physics_node/io/control_frames.hpp"
#include "physics_node/io/run_recorder.hpp"

namespace vcockpit::physics_io {


namespace {

// One glove log, read and validated, and the world's hand it drives.
struct HandLog {
  std::string path;
  int hand = 0;  // World hand index
  std::vector<hand::GloveSample> samples;
  hand::InputCounts counts;
};

std::vector<HandLog> read_hand_logs(const physics::Scene& scene, const OfflineOptions& options) {
  std::vector<HandLog> logs;
  for (const std::string& path : options.log_paths) {
    if (!scene.has_hands()) {
      throw std::invalid_argument(options.scene_path + ": the scene has no hand, so a glove log "
                                                       "cannot drive it");
    }
    // the log's hand (its `# hand:` line; a log without one is a right hand's)
    const bool left = hand::glove_log_left_hand(path);
    int hand = -1;
    for (std::size_t h = 0; h < scene.hands.size(); ++h)
      if (scene.hands[h].left == left) hand = static_cast<int>(h);
    if (hand < 0) {
      throw std::invalid_argument(path + ": a " + (left ? "left" : "right") +
                                  " hand's log, and the scene " + options.scene_path +
                                  " has no such hand");
    }
    for (const HandLog& other : logs) {
      if (other.hand == hand)
        throw std::invalid_argument(path + ": the same hand as " + other.path + " (one log per hand)");
    }
    const hand::HandModel& model = scene.hands[static_cast<std::size_t>(hand)];
    hand::GloveLog log = hand::read_glove_log(path, model);
    for (const std::string& warning : hand::glove_log_warnings(log)) spdlog::warn("{}", warning);
    // the checks a live node makes (the reader has already refused what a file cannot hold)
    hand::SampleValidator validator(model);
    HandLog out{path, hand, {}, log.counts};
    for (hand::GloveSample& sample : log.samples) {
      if (validator.accept(sample)) out.samples.push_back(sample);
    }
    out.counts += validator.counts();
    if (out.samples.empty()) throw std::invalid_argument(path + ": no valid sample to drive the hand");
    logs.push_back(std::move(out));
  }
  return logs;
}

}  // namespace

RunSummary run_offline(physics::Scene scene, const OfflineOptions& options) {
  check_input_timing(options.timing);
  std::vector<HandLog> logs = read_hand_logs(scene, options);
  if (!options.duration_s && logs.empty()) {
    throw std::invalid_argument("give --log GLOVE.csv or --duration S");
  }
  if (options.duration_s && !(*options.duration_s > 0)) {
    throw std::invalid_argument("--duration must be positive");
  }
  // one timeline: the earliest first sample is world time 0 (hand_timeline.hpp)
  std::vector<HandSamples> inputs;
  for (HandLog& log : logs) inputs.push_back({log.hand, std::move(log.samples)});
  const int64_t end_ns = options.duration_s ? std::llround(*options.duration_s * 1e9)
                                          : HandTimeline::span_ns(inputs);
  const int64_t interval_ns = output_interval_ns(options.output_hz, scene);

  RunRecorder recorder(options.out_dir, interval_ns,
                       control_frame_interval_ns(options.control_frame_hz, scene), scene);

  RunSummary summary;
  summary.scene_path = options.scene_path;
  summary.log_paths = options.log_paths;
  summary.stage_total_s.assign(physics::kStageCount, 0.0);
  summary.timing = options.timing;
  HandMotionPeak hand_peak;
  physics::World world(std::move(scene));
  // a run as fast as it can go times one step in ten: the clock reads cost 3 % of a step
  summary.stage_timing_every = 10;
  world.set_stage_timing_every(summary.stage_timing_every);
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
    hand_peak.record(world);
    if (world.step_count() % 100 == 0) {
      const double wall_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
      const double sim_s = ns_to_seconds(world.time_ns());
      progress.update(monotonic_now_ns(), sim_s, ns_to_seconds(end_ns),
                      wall_s > 0 ? sim_s / wall_s : 0.0, world.step_count());
    }
  };
  if (logs.empty()) {
    recorder.start(world);
    while (world.time_ns() < end_ns) step();
  } else {
    // one driver per hand on one timeline (hand_timeline.hpp)
    HandTimeline timeline(world, inputs, options.timing, end_ns, options.duration_s.has_value());
    recorder.start(world);
    timeline.run(step);
    summary.have_input = true;
    hand::InputCounts input_counts;
    for (std::size_t k = 0; k < logs.size(); ++k) {
      hand::InputCounts counts = logs[k].counts;
      counts += timeline.counts(k);
      spdlog::info("{}: {}", logs[k].path, hand::input_counts_text(counts));
      input_counts += counts;
      const int id = world.hand_id(logs[k].hand);
      summary.hands.push_back({id, logs[k].path, counts, recorder.events().grasps(id),
                               recorder.events().releases(id)});
    }
    summary.input = input_counts;
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
