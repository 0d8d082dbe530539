#include "physics_node/node/node_loop.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "common/clock.hpp"
#include "common/signals.hpp"
#include "physics_node/io/grasp_event_text.hpp"
#include "physics_node/io/hand_input.hpp"
#include "physics_node/io/hand_motion_peak.hpp"
#include "physics_node/io/input_follower.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "physics_node/io/run_recorder.hpp"
#include "physics_node/node/loop_stats.hpp"
#include "physics_node/node/sample_gate.hpp"
#include "physics_node/node/state_publisher.hpp"

namespace vcockpit::physics_node {
namespace {

physics_io::FollowerOptions follower_options(const NodeOptions& options) {
  physics_io::FollowerOptions f;
  f.max_gap_ns = options.timing.max_gap_ns;
  if (options.input_delay_s) f.fixed_delay_ns = seconds_to_ns(*options.input_delay_s);
  return f;
}

// Everything the loop keeps between steps, in one place.
class Node {
 public:
  Node(DdsParticipant& participant, physics::Scene scene, const NodeOptions& options)
      : options_(options),
        world_(std::move(scene)),
        hand_(world_.scene().hands[0]),
        gate_(hand_),
        replay_(world_, hand_, options.timing),
        follower_(follower_options(options)),
        reader_(participant.make_reader<cockpit::HandSample>(options.lockstep ? "reliable"
                                                                              : "stream")),
        command_reader_(participant.make_reader<cockpit::ControlCommand>("event")),
        publisher_(participant, world_) {
    publisher_.publish_object_info(world_);
    publisher_.publish_hand_info(world_);
    publisher_.publish_control_info(world_);
    if (!options.out_dir.empty()) {
      recorder_ = std::make_unique<physics_io::RunRecorder>(
          options.out_dir, physics_io::output_interval_ns(options.output_hz, world_.scene()));
    }
    last_status_ns_ = monotonic_now_ns();
    last_sample_wall_ns_ = last_status_ns_;
  }

  int run_realtime();
  int run_lockstep();

 private:
  // Takes every pending sample; the accepted ones go to `on_sample(sample, new_source,
  // take_ns)`, their latencies to stats_. A different writer (a restarted glove driver) starts
  // its own timeline: time order is checked per source. No allocation.
  template <class OnSample>
  void drain(OnSample on_sample) {
    dds::SampleInfo info;
    while (reader_.take(message_, &info)) {
      const int64_t take_ns = monotonic_now_ns();
      const bool new_source = !have_source_ || info.publication_handle != source_;
      if (new_source) gate_.reset_time();
      hand::GloveSample sample;
      if (!gate_.accept(message_, sample)) continue;
      if (new_source) {
        if (have_source_) spdlog::info("hand samples from a new source: following its timeline");
        source_ = info.publication_handle;
        have_source_ = true;
      }
      ++received_;
      stats_.record_sample(info, message_.source_stamp_ns(), take_ns);
      last_sample_wall_ns_ = take_ns;
      on_sample(sample, new_source, take_ns);
    }
  }

  bool glove_alive(int64_t now_ns) const {
    if (received_ == 0) return false;
    const bool recent = now_ns - last_sample_wall_ns_ <= options_.timing.glove_timeout_ns;
    return recent && reader_.alive_writer_count() > 0;
  }

  // Commands from other nodes (cockpit/control_command) for the coming step: the world refuses a
  // control or position it does not have, and a control a hand holds.
  void take_commands() {
    while (command_reader_.take(command_)) {
      const auto& controls = world_.scene().controls;
      const int control = static_cast<int>(command_.control_id());
      const int position = static_cast<int>(command_.position());
      if (world_.command_control(control, position)) {
        spdlog::info("command from '{}': {} to {}", command_.source(), controls[control].name,
                     controls[control].positions[static_cast<std::size_t>(position)].name);
      } else {
        ++commands_refused_;
        spdlog::warn("command from '{}' refused: control {} position {} ({})", command_.source(),
                     command_.control_id(), command_.position(),
                     control >= 0 && control < static_cast<int>(controls.size())
                         ? "no such position, or a hand holds it"
                         : "no such control");
      }
    }
  }

  void step_world() {
    take_commands();
    const int64_t start_ns = monotonic_now_ns();
    world_.step();
    stats_.step_compute.record_ns(monotonic_now_ns() - start_ns);
    hand_peak_.record(world_);
    if (recorder_) recorder_->after_step(world_);
    publisher_.publish_events(world_);
    for (const auto& f : world_.step_faults()) {
      spdlog::warn("object '{}' (#{}): {} at {:.3f} s, put back where it was at the step's start, "
                   "at rest (further faults of it are counted, not logged)",
                   world_.scene().objects[f.object].name, f.object,
                   physics::body_fault_name(f.what), ns_to_seconds(f.first_t_ns));
    }
    for (const auto& e : world_.step_events()) {
      spdlog::info("{} {} at {:.3f} s: {}", e.grasp ? "GRASP" : "RELEASE",
                   world_.scene().objects[e.object].name, ns_to_seconds(e.t_ns),
                   physics_io::grasp_event_text(e));
    }
    for (const auto& e : world_.control_events()) {
      const physics::ControlSpec& c = world_.scene().controls[static_cast<std::size_t>(e.control)];
      spdlog::info("CONTROL {} {} -> {} at {:.3f} s: {}{}{}", c.name,
                   c.positions[static_cast<std::size_t>(e.from)].name,
                   c.positions[static_cast<std::size_t>(e.to)].name, ns_to_seconds(e.t_ns),
                   physics::control_cause_name(e.cause), e.link >= 0 ? " by " : "",
                   e.link >= 0 ? std::string(physics::link_name(static_cast<physics::Link>(e.link)))
                               : std::string());
    }
    ++steps_in_period_;
    for (int s = 0; s < physics::kStageCount; ++s) stage_ns_[s] += world_.stage_times().ns[s];
  }

  void publish_state(bool tracking) {
    const int64_t start = monotonic_now_ns();
    publisher_.publish_state(world_, stamps_, tracking);
    publish_ns_ += monotonic_now_ns() - start;
  }
  // lockstep: the hand the replay driver gave the last step
  void publish_lockstep_state() {
    const physics_io::ShownInput& shown = replay_.shown();
    stamps_ = {shown.sample_time_ns, shown.source_stamp_ns};
    publish_state(shown.tracking);
  }

  void maybe_publish_status(int64_t now_ns, bool alive, const char* detail);
  // Everything counted about the input so far: the gate's, the timing's (follower in real time,
  // replay driver in lockstep), glove lost.
  hand::InputCounts input_counts() const {
    hand::InputCounts c = gate_.counts();
    c.rejected_out_of_range += gate_.rejected_flagged_or_far();  // as node_status always had it
    c += options_.lockstep ? replay_.counts() : follower_.counts();
    c.glove_lost += glove_lost_;
    return c;
  }

  // --duration: the loops stop by themselves at this monotonic time (0: never).
  void start_clock() {
    run_start_ns_ = monotonic_now_ns();
    stop_at_ns_ = options_.duration_s > 0 ? run_start_ns_ + seconds_to_ns(options_.duration_s) : 0;
  }
  bool should_stop(int64_t now_ns) const {
    return shutdown_requested() || (stop_at_ns_ > 0 && now_ns >= stop_at_ns_);
  }
  // The latency log line and the --stats-out file (the caller fills mode, duration and what is
  // particular to its mode).
  void report_stop(StatsReport report);

  NodeOptions options_;
  physics::World world_;
  const hand::HandModel& hand_;
  SampleGate gate_;
  physics_io::ReplayDriver replay_;      // lockstep: the world advanced to each sample's stamp
  physics_io::InputFollower follower_;  // real time: the hand a small delay behind the samples
  physics_io::HandMotionPeak hand_peak_;
  uint64_t glove_lost_ = 0;             // real time (lockstep: the replay driver counts)
  Reader<cockpit::HandSample> reader_;
  Reader<cockpit::ControlCommand> command_reader_;
  cockpit::ControlCommand command_;
  uint64_t commands_refused_ = 0;
  StatePublisher publisher_;
  cockpit::HandSample message_;
  dds::InstanceHandle_t source_;
  bool have_source_ = false;
  InputStamps stamps_;
  physics::HandInput input_;
  uint64_t received_ = 0;
  uint64_t received_at_last_status_ = 0;
  uint64_t late_steps_ = 0;
  uint64_t steps_in_period_ = 0;
  int64_t stage_ns_[physics::kStageCount] = {};
  int64_t publish_ns_ = 0;
  int64_t last_status_ns_ = 0;
  int64_t last_sample_wall_ns_ = 0;
  int64_t run_start_ns_ = 0;
  int64_t stop_at_ns_ = 0;
  LoopStats stats_;
  std::unique_ptr<physics_io::RunRecorder> recorder_;  // lockstep --out
  bool recording_started_ = false;
};

void Node::report_stop(StatsReport report) {
  report.steps = world_.step_count();
  report.samples = received_;
  report.rejected = gate_.rejected();
  report.input = input_counts();
  report.hand_peak_wrist_mps = hand_peak_.wrist_mps();
  report.hand_peak_joint_radps = hand_peak_.joint_radps();
  spdlog::info("DDS transit {}; sample age at step {}; step compute {}",
               latency_text_us(stats_.dds_transit), latency_text_us(stats_.age_at_step),
               latency_text_us(stats_.step_compute));
  spdlog::info("input: {}", hand::input_counts_text(report.input));
  if (!options_.lockstep) {
    spdlog::info("hand lag behind its source {} (interpolation delay now {:.2f} ms); peak wrist "
                 "speed {:.2f} m/s, joint {:.1f} rad/s",
                 latency_text_us(stats_.hand_lag),
                 static_cast<double>(report.input_delay_ns.value_or(0)) * 1e-6,
                 report.hand_peak_wrist_mps, report.hand_peak_joint_radps);
  }
  if (options_.stats_out.empty()) return;
  write_stats_json(options_.stats_out, report, stats_);
  spdlog::info("statistics written to {}", options_.stats_out);
}

void Node::maybe_publish_status(int64_t now_ns, bool alive, const char* detail) {
  if (now_ns - last_status_ns_ < 1'000'000'000) return;
  const double period_s = ns_to_seconds(now_ns - last_status_ns_);
  cockpit::NodeStatus status;
  status.node_name(options_.node_name);
  status.state(alive ? cockpit::RUNNING : cockpit::DEGRADED);
  status.detail(detail);
  status.stamp_ns(now_ns);
  status.loop_rate_hz(static_cast<double>(steps_in_period_) / period_s);
  status.input_rate_hz(static_cast<double>(received_ - received_at_last_status_) / period_s);
  status.received(received_);
  status.published(world_.step_count());
  const hand::InputCounts input = input_counts();
  status.rejected(input.rejected());
  status.rejected_nonfinite(input.rejected_nonfinite);
  status.rejected_out_of_range(input.rejected_out_of_range);
  status.rejected_stale(input.rejected_stale);
  status.clamped(input.clamped);
  status.missing_columns(input.missing_columns);
  status.intervals(input.intervals);
  status.intervals_interpolated(input.intervals_interpolated);
  status.gaps_bridged(input.gaps_bridged);
  status.gaps_not_bridged(input.gaps_not_bridged);
  status.intervals_late(input.intervals_late);
  status.longest_interval_s(static_cast<double>(input.longest_interval_ns) * 1e-9);
  status.glove_lost(input.glove_lost);
  status.input_delay_ms(options_.lockstep ? 0.0 : static_cast<double>(follower_.delay_ns()) * 1e-6);
  status.late_steps(late_steps_);
  status.input_alive(alive);
  const double steps = steps_in_period_ > 0 ? static_cast<double>(steps_in_period_) : 1.0;
  for (int s = 0; s < physics::kStageCount; ++s) {
    status.stage_time_us()[s] = static_cast<double>(stage_ns_[s]) * 1e-3 / steps;
    stage_ns_[s] = 0;
  }
  status.stage_time_us()[cockpit::STAGE_PUBLISH] = static_cast<double>(publish_ns_) * 1e-3 / steps;
  double total = 0;
  for (int s = 0; s < static_cast<int>(cockpit::STAGE_TOTAL); ++s) total += status.stage_time_us()[s];
  status.stage_time_us()[cockpit::STAGE_TOTAL] = total;
  publisher_.publish_status(status);
  publish_ns_ = 0;
  steps_in_period_ = 0;
  received_at_last_status_ = received_;
  last_status_ns_ = now_ns;
}

int Node::run_realtime() {
  const int64_t period_ns = std::llround(1e9 / options_.rate_hz);
  const int64_t publish_period_ns = std::llround(1e9 / options_.publish_hz);
  start_clock();
  int64_t next_ns = run_start_ns_;
  int64_t next_publish_ns = next_ns;
  bool tracking = false;
  bool have_input = false;
  spdlog::info("real time: {} Hz steps ({} substeps), world published at {} Hz; the hand {} "
               "behind its glove, gaps over {:.3f} s not bridged",
               options_.rate_hz, world_.substeps(), options_.publish_hz,
               options_.input_delay_s ? fmt::format("{:.1f} ms", *options_.input_delay_s * 1e3)
                                      : std::string("one usual sample interval + 2 ms"),
               static_cast<double>(options_.timing.max_gap_ns) * 1e-9);
  physics_io::FollowedInput followed;
  while (!should_stop(monotonic_now_ns())) {
    sleep_until_ns(next_ns);
    drain([&](const hand::GloveSample& s, bool new_source, int64_t take_ns) {
      if (new_source) follower_.reset();
      follower_.push(s, take_ns, message_.source_stamp_ns());
    });
    const int64_t now_ns = monotonic_now_ns();
    const bool alive = glove_alive(now_ns);
    if (alive != tracking && have_input) {
      spdlog::warn(alive ? "glove samples resumed: tracking" : "glove lost: holding the hand, "
                                                               "releasing what it holds");
      if (!alive) ++glove_lost_;
    }
    tracking = alive;
    // the hand at the end of this step's slot, a small delay behind the source
    if (follower_.at(next_ns + period_ns, followed)) {
      input_ = physics_io::hand_input_from_glove(hand_, followed.sample);
      stamps_ = {followed.sample.t_ns, followed.source_stamp_ns};
      have_input = true;
    }
    if (have_input) {
      input_.tracking = tracking;
      world_.set_hand_input(input_);
    }
    step_world();
    const int64_t end_ns = monotonic_now_ns();
    if (have_input && tracking) stats_.hand_lag.record_ns(end_ns - stamps_.source_stamp_ns);
    if (end_ns > next_ns + period_ns) ++late_steps_;
    if (end_ns >= next_publish_ns) {
      publish_state(tracking);
      next_publish_ns += publish_period_ns;
      if (next_publish_ns < end_ns) next_publish_ns = end_ns + publish_period_ns;
    }
    maybe_publish_status(end_ns, alive, alive ? "tracking" : have_input ? "glove lost" : "no glove yet");
    next_ns += period_ns;
    // far behind (a stall): resynchronise, counting every dropped slot as late
    const int64_t behind = (monotonic_now_ns() - next_ns) / period_ns;
    if (behind > kMaxCatchUpSteps) {
      late_steps_ += static_cast<uint64_t>(behind);
      spdlog::warn("{} steps behind the clock: resynchronised (counted as late)", behind);
      next_ns += behind * period_ns;
    }
  }
  // the loop's own figures end here: the flush below is shutdown, not stepping
  const int64_t loop_end_ns = monotonic_now_ns();
  publisher_.flush(500'000'000);
  const double loop_s = ns_to_seconds(loop_end_ns - run_start_ns_);
  const double rate_hz = loop_s > 0 ? static_cast<double>(world_.step_count()) / loop_s : 0.0;
  spdlog::info("stopped after {} steps in {:.3f} s ({:.1f} Hz); {} samples accepted, {} rejected, "
               "{} late steps",
               world_.step_count(), loop_s, rate_hz, received_, gate_.rejected(), late_steps_);
  StatsReport report;
  report.mode = "realtime";
  report.rate_hz = rate_hz;
  report.late_steps = late_steps_;
  report.duration_s = loop_s;
  report.input_delay_ns = follower_.delay_ns();
  report_stop(report);
  return 0;
}

int Node::run_lockstep() {
  const int64_t publish_every_ns = std::llround(1e9 / options_.publish_hz);
  int64_t next_publish_sim_ns = 0;
  bool dirty = false;
  spdlog::info("lockstep: stepping to each sample's stamp ({} substeps per step)",
               world_.substeps());
  start_clock();
  int64_t last_publish_ns = 0;
  while (!should_stop(monotonic_now_ns())) {
    const bool idle = !reader_.wait_for_data(20'000'000);
    drain([&](const hand::GloveSample& s, bool new_source, int64_t) {
      // world time 0 is the first sample; a later source continues from where the world is
      if (new_source) replay_.restart();
      replay_.feed(
          s,
          [&] {
            step_world();
            dirty = true;
            if (world_.time_ns() >= next_publish_sim_ns) {
              publish_lockstep_state();
              last_publish_ns = monotonic_now_ns();
              next_publish_sim_ns += publish_every_ns;
            }
          },
          message_.source_stamp_ns());
      // the offline runner's first row: the hand set by the first sample, before any step
      if (recorder_ && !recording_started_) {
        recorder_->start(world_);
        recording_started_ = true;
      }
    });
    // caught up with the input: show where the world is, at most at --publish-hz of wall time
    // (a replay at its own pace would otherwise publish every sample), and at once when the
    // input pauses or ends
    const int64_t now_ns = monotonic_now_ns();
    if (dirty && (idle || now_ns - last_publish_ns >= publish_every_ns)) {
      publish_lockstep_state();
      last_publish_ns = now_ns;
      dirty = false;
    }
    const bool alive = glove_alive(now_ns);
    maybe_publish_status(now_ns, alive, alive ? "lockstep" : replay_.started() ? "lockstep, input ended"
                                                                     : "lockstep, waiting");
  }
  const int64_t loop_end_ns = monotonic_now_ns();
  publisher_.flush(500'000'000);
  if (recorder_) {
    if (!recording_started_) recorder_->start(world_);
    recorder_->commit();
    spdlog::info("wrote {}/trajectories.csv and events.jsonl", options_.out_dir);
  }
  spdlog::info("stopped at {:.3f} s simulated after {} steps; {} samples accepted, {} rejected",
               ns_to_seconds(world_.time_ns()), world_.step_count(), received_, gate_.rejected());
  StatsReport report;
  report.mode = "lockstep";
  report.duration_s = ns_to_seconds(loop_end_ns - run_start_ns_);
  report.simulated_s = ns_to_seconds(world_.time_ns());
  report_stop(report);
  return 0;
}

}  // namespace

int run_node(DdsParticipant& participant, physics::Scene scene, const NodeOptions& options) {
  if (!scene.has_hands()) throw std::invalid_argument("the scene has no hand for the glove to drive");
  Node node(participant, std::move(scene), options);
  return options.lockstep ? node.run_lockstep() : node.run_realtime();
}

}  // namespace vcockpit::physics_node
