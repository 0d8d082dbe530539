// physics_node: the central computer of the paper's prototype (§2). Over DDS it takes hand samples
// and publishes the virtual world (real time at a fixed rate, or lockstep with a replay);
// `--offline` runs the same world with no DDS from a glove log and writes trajectories, events and
// a summary.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/cli_finite.hpp"
#include "common/logging.hpp"
#include "common/signals.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/offline_runner.hpp"
#include "physics_node/node/node_loop.hpp"

namespace {

using namespace vcockpit;

// Model parts with triangles left out for having no area: said once, at load.
void report_model_parts(const physics::Scene& scene) {
  for (const physics::ObjectSpec& o : scene.objects) {
    for (const physics::Shape* shape : {&o.shape, o.look ? &*o.look : nullptr}) {
      if (!shape || shape->kind != physics::ShapeKind::kMesh || shape->mesh->degenerate_dropped == 0)
        continue;
      spdlog::warn("object '{}': {}: {} triangle(s) with no area left out (the first: triangle {})",
                   o.name, shape->mesh->source, shape->mesh->degenerate_dropped,
                   shape->mesh->first_degenerate);
    }
  }
}

int run_offline_mode(const physics_io::OfflineOptions& options) {
  if (options.out_dir.empty()) throw CLI::ValidationError("--offline needs --out DIR");
  physics::Scene scene = load_scene(options.scene_path);
  report_model_parts(scene);
  const auto summary = physics_io::run_offline(std::move(scene), options);
  spdlog::info("{} steps, {:.3f} s simulated in {:.3f} s wall ({:.1f}x real time); {} grasp(s), "
               "{} release(s); hand penetration max {:.2f} mm",
               summary.steps, summary.simulated_s, summary.wall_s,
               summary.wall_s > 0 ? summary.simulated_s / summary.wall_s : 0.0, summary.grasps,
               summary.releases, summary.penetration_max_m * 1e3);
  return 0;
}

// --stats-out is written when the node stops: a path that cannot be written must fail at start,
// not after a long run.
void check_stats_out(const std::string& path) {
  if (path.empty()) throw CLI::ValidationError("--stats-out: empty file name");
  const std::filesystem::path file(path);
  if (std::filesystem::is_directory(file)) {
    throw CLI::ValidationError("--stats-out: '" + path + "' is a directory, not a file");
  }
  const std::filesystem::path dir = file.has_parent_path() ? file.parent_path() : ".";
  if (!std::filesystem::is_directory(dir) || access(dir.c_str(), W_OK) != 0) {
    throw CLI::ValidationError("--stats-out: directory '" + dir.string() +
                               "' does not exist or is not writable");
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("physics_node: hand kinematics, collision, virtual forces, rigid-body motion and "
               "the stable grasp of the virtual cockpit. Over DDS by default; --offline without.");
  bool offline = false;
  physics_io::OfflineOptions offline_options;
  std::string scene_path = std::string(VCOCKPIT_CONFIG_DIR) + "/cockpit.yaml";
  physics_node::NodeOptions node_options;
  DdsFlags dds_flags;
  std::string log_level = "info";

  app.add_option("--scene", scene_path, "scene YAML (objects, materials, hand, grasp thresholds)")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  app.add_flag("--offline", offline,
               "no DDS: run --log (or --duration) as fast as possible and write --out DIR");
  app.add_option("--log", offline_options.log_paths,
                 "offline: glove log CSV driving a hand; repeat for each hand (--log right.csv --log "
                 "left.csv: each log's '# hand:' line names its hand)")
      ->check(CLI::ExistingFile);
  app.add_option("--duration", offline_options.duration_s,
                 "offline: simulated seconds (default: the log's span); DDS: stop by itself after "
                 "this many seconds of real time, as on SIGINT (default: run until a signal)")
      ->check(CLI::Range(0.001, 1e7) & kFinite);
  app.add_option("--out", offline_options.out_dir,
                 "offline: output directory for trajectories.csv, events.jsonl, summary.json; "
                 "lockstep: for trajectories.csv and events.jsonl (the offline runner's, written "
                 "at stop)");
  app.add_option("--output-hz", offline_options.output_hz,
                 "offline and lockstep --out: trajectory rows per second")
      ->check(CLI::PositiveNumber & kFinite)
      ->capture_default_str();
  app.add_flag("--lockstep", node_options.lockstep,
               "DDS: step to each hand sample's stamp (pairs with glove_driver --lockstep)");
  std::vector<std::string> lockstep_hands;
  app.add_option("--lockstep-hands", lockstep_hands,
                 "lockstep: hands whose samples every step waits for (right, left; one glove driver "
                 "each); default: whichever hands send samples")
      ->check(CLI::IsMember({"right", "left"}))
      ->delimiter(',');
  app.add_option("--rate-hz", node_options.rate_hz, "DDS real time: physics steps per second")
      ->check(CLI::Range(1.0, 10000.0) & kFinite)
      ->capture_default_str();
  app.add_option("--control-frame-hz", node_options.control_frame_hz,
                 "cockpit/control_frame (the aircraft systems' input) per second of world time, and "
                 "control_frames.csv's with --out (0: no topic; the file at 100)")
      ->check(CLI::Range(0.0, 10000.0) & kFinite)
      ->capture_default_str();
  app.add_option("--wait-frame-readers", node_options.wait_frame_readers,
                 "lockstep: wait (at most 30 s) for this many cockpit/control_frame readers (a "
                 "systems node) before the first step")
      ->check(CLI::Range(0, 16));
  app.add_option("--publish-hz", node_options.publish_hz,
                 "DDS: hand_state/object_state publications per second")
      ->check(CLI::Range(1.0, 10000.0) & kFinite)
      ->capture_default_str();
  // 1 s: real gloves and trackers drop out for up to 0.66 s (a Leap losing the hand, a
  // CyberGlove's serial hiccup), which is a gap to hold across, not a glove to give up on
  double glove_timeout_s = static_cast<double>(physics_io::kDefaultGloveTimeout_ns) * 1e-9;
  app.add_option("--glove-timeout", glove_timeout_s,
                 "seconds without a hand sample before the glove counts as lost (real time: of "
                 "wall time; lockstep and offline: of the samples' timeline)")
      ->check(CLI::PositiveNumber & kFinite)
      ->capture_default_str();
  double max_gap_s = 0.25;
  app.add_option("--max-gap", max_gap_s,
                 "longest interval between hand samples the hand is moved across; over it the "
                 "hand holds its last sample (0: never interpolate, each sample taken in one step)")
      ->check(CLI::NonNegativeNumber & kFinite)
      ->capture_default_str();
  std::optional<double> input_delay_s;
  app.add_option("--input-delay", input_delay_s,
                 "DDS real time: show the hand this many seconds behind its source, interpolated "
                 "(default: adaptive, one usual sample interval + 2 ms; 0: the newest sample at "
                 "once, no interpolation)")
      ->check(CLI::NonNegativeNumber & kFinite);
  app.add_option("--node-name", node_options.node_name, "name on cockpit/node_status")
      ->capture_default_str();
  std::optional<std::string> stats_out;
  app.add_option("--stats-out", stats_out,
                 "DDS: at stop, write loop statistics to this JSON file (mode, duration, steps, "
                 "rate, late steps, samples, DDS transit, sample age at step, step compute time)");
  app.add_option("--checkpoint", node_options.checkpoint_path,
                 "DDS: save the world (bodies, controls, grasps, time) to this file as it runs, "
                 "atomically, so a node restarted with --resume goes on from it");
  app.add_option("--checkpoint-every", node_options.checkpoint_every_s,
                 "DDS: seconds of simulated time between checkpoints")
      ->check(CLI::Range(0.01, 3600.0) & kFinite)
      ->capture_default_str();
  app.add_flag("--resume", node_options.resume,
               "DDS: start from --checkpoint's world if the file is there (the rig launcher's "
               "restart of a killed node), else from the scene");
  add_dds_flags(app, dds_flags);
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  try {
    setup_logging("physics_node", log_level);
    install_shutdown_handlers();
    physics_io::InputTiming timing;
    timing.max_gap_ns = std::llround(max_gap_s * 1e9);
    timing.glove_timeout_ns = std::llround(glove_timeout_s * 1e9);
    try {
      physics_io::check_input_timing(timing);
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError(e.what());
    }
    offline_options.timing = timing;
    node_options.timing = timing;
    if (offline) {
      if (!node_options.checkpoint_path.empty() || node_options.resume)
        throw CLI::ValidationError("--checkpoint and --resume belong to the DDS modes");
      if (stats_out) {
        throw CLI::ValidationError("--stats-out belongs to the DDS modes (--offline writes "
                                   "DIR/summary.json)");
      }
      if (input_delay_s) throw CLI::ValidationError("--input-delay belongs to DDS real time");
      offline_options.scene_path = scene_path;
      return run_offline_mode(offline_options);
    }
    if (!offline_options.log_paths.empty()) throw CLI::ValidationError("--log belongs to --offline");
    if (node_options.resume && node_options.checkpoint_path.empty())
      throw CLI::ValidationError("--resume needs --checkpoint FILE (where to resume from)");
    if (!offline_options.out_dir.empty() && !node_options.lockstep) {
      throw CLI::ValidationError("--out belongs to --offline and --lockstep");
    }
    node_options.out_dir = offline_options.out_dir;
    node_options.output_hz = offline_options.output_hz;
    if (node_options.control_frame_hz > 0) offline_options.control_frame_hz = node_options.control_frame_hz;
    node_options.duration_s = offline_options.duration_s.value_or(0.0);
    if (input_delay_s && node_options.lockstep) {
      throw CLI::ValidationError("--input-delay belongs to real time (lockstep interpolates "
                                 "between samples with no delay)");
    }
    node_options.input_delay_s = input_delay_s;
    if (!lockstep_hands.empty() && !node_options.lockstep)
      throw CLI::ValidationError("--lockstep-hands belongs to --lockstep");
    for (const std::string& side : lockstep_hands) node_options.lockstep_hands.push_back(side == "left" ? 1 : 0);
    if (stats_out) {
      check_stats_out(*stats_out);
      node_options.stats_out = *stats_out;
    }
    physics::Scene scene = load_scene(scene_path);
    report_model_parts(scene);
    DdsParticipant participant(resolve_dds_options(dds_flags, "physics_node"), node_options.node_name);
    return physics_node::run_node(participant, std::move(scene), node_options);
  } catch (const CLI::Error& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
