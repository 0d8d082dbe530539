// glove_driver: publishes hand samples (wrist pose + 22 joint angles) on cockpit/hand_sample
// from a synthetic gesture script or a recorded glove log, or records that topic to a log.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <cmath>
#include <memory>
#include <optional>

#include "common/clock.hpp"
#include "common/logging.hpp"
#include "common/signals.hpp"
#include "common/yaml_config.hpp"
#include "hand/glove_log.hpp"
#include "glove_driver/glove/joints_input.hpp"
#include "glove_driver/glove/sample_source.hpp"
#include "glove_driver/node/recorder.hpp"
#include "glove_driver/node/replay_commands.hpp"
#include "glove_driver/node/sample_publisher.hpp"
#include "glove_driver/node/tracked_joints_publisher.hpp"
#include "common/terminal_progress.hpp"
#include "common/cli_finite.hpp"
#include "hand/config/hand_yaml.hpp"

namespace vcockpit::glove {
namespace {

struct Flags {
  DdsFlags dds;
  std::string source;
  std::string script_path;
  std::string log_path;
  std::string record_path;
  std::string hand_config = std::string(VCOCKPIT_CONFIG_DIR) + "/hand.yaml";
  std::string side;  // empty: the hand file's
  std::string node_name = "glove_driver";
  std::optional<uint32_t> hand_id;
  double rate = 1.0;
  std::optional<double> rate_hz;
  bool loop = false;
  bool hold_at_end = false;
  int64_t start_at_ns = 0;
  bool join_timeline = false;
  double start_offset_s = 0.0;
  bool lockstep = false;
  int wait_readers = 1;
  double match_timeout_s = 30.0;
  uint64_t count = 0;
  double duration_s = 0.0;
  double idle_timeout_s = 0.0;
  double max_gap_s = 0.25;
  std::string log_level = "info";
  bool calibrate = false;
  std::vector<double> palm_at = {0.36, -0.35, 0.84};
};

void add_flags(CLI::App& app, Flags& f) {
  add_dds_flags(app, f.dds);
  app.add_option("--source", f.source,
                 "where samples come from: synthetic, replay (a glove log) or joints (a hand-joints "
                 "log, retargeted to the hand)")
      ->check(CLI::IsMember({"synthetic", "replay", "joints"}));
  app.add_option("--script", f.script_path, "gesture script YAML (--source synthetic)")
      ->check(CLI::ExistingFile);
  app.add_option("--log", f.log_path,
                 "glove log CSV to replay (--source replay), or hand-joints log (--source joints)")
      ->check(CLI::ExistingFile);
  app.add_flag("--calibrate", f.calibrate,
               "--source joints: measure the hand on the recording and retarget on that hand");
  app.add_option("--palm-at", f.palm_at,
                 "--source joints: where the recording's mean palm goes in the cockpit (m)")
      ->expected(3)
      ->check(kFinite)
      ->capture_default_str();
  app.add_option("--record", f.record_path,
                 "record cockpit/hand_sample to this glove log (instead of publishing)");
  app.add_option("--side", f.side,
                 "right or left: this side's hand (the hand file's model, mirrored if it is of the "
                 "other side); default: the hand file's side")
      ->check(CLI::IsMember({"right", "left"}));
  app.add_option("--node-name", f.node_name,
                 "name on cockpit/node_status (a second glove driver, for the other hand, needs "
                 "its own)")
      ->capture_default_str();
  app.add_option("--hand-config,--hand-file", f.hand_config,
                 "hand model YAML (joint limits, rest pose, tracker)")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  app.add_option("--hand-id", f.hand_id, "hand id on the topic: 0 right, 1 left (default: the "
                                          "log's hand, else 0)");
  app.add_option("--rate", f.rate, "time scale: 2 plays twice as fast; 0 = as fast as possible")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--rate-hz", f.rate_hz, "synthetic samples per second (default: the script's)")
      ->check(CLI::Range(1.0, 100000.0));
  app.add_flag("--loop", f.loop, "replay: start over at the end (time keeps increasing)");
  app.add_option("--start-at-ns", f.start_at_ns,
                 "publish the first sample at this CLOCK_MONOTONIC time (ns), not before: glove "
                 "drivers started together begin together however long each takes to match its "
                 "reader (rig_launcher's {start_at_ns})")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--join-timeline", f.join_timeline,
               "with --start-at-ns in the past (a driver restarted after a crash): join the "
               "timeline where it stands now, as a live glove would, skipping the samples due "
               "before now instead of sending them in a burst (rig_launcher's restart_args)");
  app.add_flag("--hold-at-end", f.hold_at_end,
               "at the end of the samples, wait (until Ctrl-C) for an instructor's restart on "
               "cockpit/sim_command instead of exiting");
  app.add_option("--start-offset", f.start_offset_s, "replay: skip this many seconds of the log")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--lockstep", f.lockstep,
               "reliable keep-all delivery: wait for subscribers and their acknowledgements");
  app.add_option("--wait-readers", f.wait_readers,
                 "readers of cockpit/hand_sample to wait for before the first sample (0: start at "
                 "once; lockstep needs at least 1)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--match-timeout", f.match_timeout_s,
                 "seconds to wait for them: then lockstep fails, a stream starts anyway")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--count", f.count, "record: stop after this many samples");
  app.add_option("--duration", f.duration_s, "record: stop after this many seconds")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--idle-timeout", f.idle_timeout_s,
                 "record: stop this many seconds after the last sample")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-gap", f.max_gap_s,
                 "count intervals between published samples longer than this as gaps a physics "
                 "node with the same --max-gap does not bridge")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--log-level", f.log_level, "trace, debug, info, warn, error")
      ->capture_default_str();
}

// Later than this past --start-at-ns, a first start is reported: two hands begun apart by
// more than a few samples no longer move together.
constexpr int64_t kLateStartWarning_ns = 20'000'000;

int run_publisher(DdsParticipant& participant, const hand::HandModel& hand, Source& source,
                  const PublisherOptions& options, bool hold_at_end, int64_t start_at_ns,
                  bool join_timeline) {
  SamplePublisher publisher(participant, hand, options);
  std::optional<TrackedJointsPublisher> joints_publisher;
  if (source.has_tracked_joints()) joints_publisher.emplace(participant, options.hand_id, options.lockstep);
  publisher.add_load_counts(source.load_counts());
  ReplayCommands commands(participant, options.node_name);
  if (!publisher.wait_for_readers()) return shutdown_requested() ? 0 : 1;
  if (start_at_ns > monotonic_now_ns()) sleep_until_ns(start_at_ns);
  spdlog::info("publishing on {} ({} reader(s) matched)", TopicTraits<cockpit::HandSample>::kName,
               publisher.matched_readers());
  TerminalProgress progress;
  const int64_t run_start_ns = monotonic_now_ns();
  int64_t start_ns = run_start_ns;  // wall time of the timeline's 0 (moved by a restart)
  // joining a timeline that began before this process: its 0 is the rig's start, and what was
  // due before now is skipped
  bool joining = join_timeline && start_at_ns > 0 && start_at_ns < run_start_ns;
  if (joining) start_ns = start_at_ns;
  // a first start past the rig's start (a scene slow to load, a sanitized build): the log
  // still plays whole, but behind the other hands' and behind where a restart would join it
  if (!joining && start_at_ns > 0 && run_start_ns - start_at_ns > kLateStartWarning_ns) {
    spdlog::warn("began {:.3f} s after the rig's start (--start-at-ns): the reader matched late; "
                 "this hand's samples run that far behind the rig's timeline",
                 ns_to_seconds(run_start_ns - start_at_ns));
  }
  uint64_t skipped = 0;
  bool restarted = false;
  bool ended = false;
  // Restarted while the physics is frozen (an instructor's freeze, reset, restart, unfreeze):
  // the replay stands at its first sample, given again every sample interval with its time going
  // on, until time goes on. Started at once, its first seconds would play to a frozen world and
  // be lost by the unfreeze.
  bool holding_start = false;
  hand::GloveSample sample;
  int64_t due_ns = 0;
  while (!shutdown_requested()) {
    if (commands.take_restart(source.can_restart())) {
      source.restart();
      restarted = true;
      ended = false;
      holding_start = commands.physics_frozen();
      if (holding_start) spdlog::info("the physics is frozen: the replay waits at its start until time goes on");
    } else if (holding_start) {
      if (commands.physics_frozen()) {
        source.restart();  // the first sample again, one sample interval on
      } else {
        holding_start = false;
        spdlog::info("time goes on: the replay plays from its start");
      }
    }
    if (!source.next(sample, due_ns)) {
      if (!hold_at_end) break;
      if (!ended) spdlog::info("the samples ended: waiting for a restart (Ctrl-C ends)");
      ended = true;
      sleep_until_ns(monotonic_now_ns() + 20'000'000);
      publisher.tick(monotonic_now_ns());
      continue;
    }
    // after a restart the timeline goes on from the last sample: its next sample is due now,
    // however long the replay stood at its end
    if (restarted) start_ns = monotonic_now_ns() - due_ns;
    restarted = false;
    if (joining) {
      if (start_ns + due_ns < monotonic_now_ns()) {
        ++skipped;
        continue;
      }
      spdlog::info("joined the timeline {:.3f} s after its start ({} samples due before now "
                   "skipped)",
                   ns_to_seconds(monotonic_now_ns() - start_ns), skipped);
      joining = false;
    }
    if (due_ns > 0) sleep_until_ns(start_ns + due_ns);
    if (holding_start && due_ns == 0) sleep_until_ns(monotonic_now_ns() + 10'000'000);  // (--rate 0)
    publisher.publish(sample);
    if (joints_publisher && source.tracked_joints() != nullptr)
      joints_publisher->publish(*source.tracked_joints(), sample.t_ns);
    const int64_t now_ns = monotonic_now_ns();
    publisher.tick(now_ns);
    const double wall_s = ns_to_seconds(now_ns - run_start_ns);
    progress.update(now_ns, source.position_s(), source.total_s(),
                    wall_s > 0 ? source.position_s() / wall_s : 0.0, publisher.published());
  }
  progress.finish();
  const bool ok = publisher.finish();
  spdlog::info("published {} samples in {:.3f} s ({} write failures); {}", publisher.published(),
               ns_to_seconds(monotonic_now_ns() - run_start_ns), publisher.write_failures(),
               hand::input_counts_text(publisher.counts()));
  return ok ? 0 : 1;
}

int run(const Flags& f) {
  const bool recording = !f.record_path.empty();
  if (recording == !f.source.empty()) {
    throw CLI::ValidationError("give either --source synthetic|replay|joints or --record FILE");
  }
  if (f.source == "synthetic" && f.script_path.empty()) {
    throw CLI::ValidationError("--source synthetic needs --script FILE");
  }
  if ((f.source == "replay" || f.source == "joints") && f.log_path.empty()) {
    throw CLI::ValidationError("--source " + f.source + " needs --log FILE");
  }
  hand::HandModel hand = load_hand_model(f.hand_config);
  if (!f.side.empty() && (f.side == "left") != hand.left) hand = hand::mirrored(hand);
  DdsParticipant participant(resolve_dds_options(f.dds, "glove_driver"), "glove_driver");

  if (recording) {
    RecorderOptions options;
    options.path = f.record_path;
    options.lockstep = f.lockstep;
    options.hand_id = f.hand_id.value_or(hand.left ? 1 : 0);
    options.count = f.count;
    options.duration_s = f.duration_s;
    options.idle_timeout_s = f.idle_timeout_s;
    return run_recorder(participant, hand, options);
  }

  std::unique_ptr<Source> source;
  bool left = hand.left;
  if (f.source == "replay") {
    hand::GloveLog log = hand::read_glove_log(f.log_path, hand);
    left = log.left_hand;
    for (const std::string& warning : hand::glove_log_warnings(log)) spdlog::warn("{}", warning);
    spdlog::info("{}: {} samples, {:.3f} s", f.log_path, log.samples.size(),
                 ns_to_seconds(log.samples.back().t_ns - log.samples.front().t_ns));
    source = std::make_unique<ReplaySource>(
        std::move(log), ReplayOptions{f.rate, f.loop, f.start_offset_s});
  } else if (f.source == "joints") {
    JointsInputOptions joints;
    if (!f.side.empty()) joints.left_hand = f.side == "left";
    joints.calibrate = f.calibrate;
    joints.palm_G = Eigen::Vector3d(f.palm_at[0], f.palm_at[1], f.palm_at[2]);
    JointsInput input = joints_input(f.log_path, hand.left ? hand::mirrored(hand) : hand, joints);
    left = input.log.left_hand;
    hand = input.hand;
    spdlog::info("{}: {} samples of the {} hand retargeted{}, {:.3f} s; fingertip error p50 {:.1f} "
                 "mm, p99 {:.1f} mm; {} frames without a placeable palm",
                 f.log_path, input.log.samples.size(), left ? "left" : "right",
                 f.calibrate ? " on the hand calibrated on it" : "",
                 ns_to_seconds(input.log.samples.back().t_ns - input.log.samples.front().t_ns),
                 input.tip_error_p50_m * 1e3, input.tip_error_p99_m * 1e3, input.unplaced_frames);
    source = std::make_unique<JointsSource>(std::move(input),
                                            ReplayOptions{f.rate, f.loop, f.start_offset_s});
  } else {
    GestureScript script = GestureScript::load(f.script_path, hand);
    const double rate_hz = f.rate_hz.value_or(script.rate_hz());
    source = std::make_unique<SyntheticSource>(std::move(script), rate_hz, f.rate);
  }
  PublisherOptions options;
  options.hand_id = f.hand_id.value_or(left ? 1 : 0);
  options.node_name = f.node_name;
  options.lockstep = f.lockstep;
  options.readers = f.wait_readers;
  if (f.lockstep && f.wait_readers < 1)
    throw CLI::ValidationError("--lockstep needs --wait-readers 1 or more: it waits for their "
                               "acknowledgements");
  options.match_timeout_s = f.match_timeout_s;
  options.max_gap_ns = std::llround(f.max_gap_s * 1e9);
  if (f.join_timeline && f.rate <= 0)
    throw CLI::ValidationError("--join-timeline needs a timeline: --rate above 0");
  return run_publisher(participant, hand, *source, options, f.hold_at_end, f.start_at_ns,
                       f.join_timeline);
}

}  // namespace
}  // namespace vcockpit::glove

int main(int argc, char** argv) {
  using namespace vcockpit;
  CLI::App app("glove_driver: publishes glove + wrist tracker samples on cockpit/hand_sample "
               "(synthetic gestures or a replayed glove log), or records them to a glove log");
  glove::Flags flags;
  glove::add_flags(app, flags);
  CLI11_PARSE(app, argc, argv);
  try {
    setup_logging("glove_driver", flags.log_level);
    install_shutdown_handlers();
    return glove::run(flags);
  } catch (const CLI::Error& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
