#include "physics_node/node/node_loop.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <array>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>

#include "common/clock.hpp"
#include "common/signals.hpp"
#include "physics_node/io/grasp_event_text.hpp"
#include "physics_node/io/hand_input.hpp"
#include "physics_node/io/hand_motion_peak.hpp"
#include "physics_node/io/hand_feed.hpp"
#include "physics_node/io/input_follower.hpp"
#include "physics_node/io/world_checkpoint.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "physics_node/io/run_recorder.hpp"
#include "physics_node/node/checkpoint_writer.hpp"
#include "physics_node/node/loop_stats.hpp"
#include "physics_node/node/sample_gate.hpp"
#include "physics_node/node/sim_commands.hpp"
#include "physics_node/node/state_publisher.hpp"

namespace vcockpit::physics_node {
namespace {

physics_io::FollowerOptions follower_options(const NodeOptions& options) {
  physics_io::FollowerOptions f;
  f.max_gap_ns = options.timing.max_gap_ns;
  if (options.input_delay_s) f.fixed_delay_ns = seconds_to_ns(*options.input_delay_s);
  return f;
}

// One hand's input: its own gate, timeline (lockstep: replay driver; real time: follower), source
// and glove liveliness. Samples go to the channel of their hand_id.
struct HandChannel {
  HandChannel(physics::World& world, int hand_index, const NodeOptions& options)
      : hand(hand_index),
        model(world.scene().hands[static_cast<std::size_t>(hand_index)]),
        gate(model),
        replay(world, model, options.timing, hand_index),
        follower(follower_options(options)) {}
  int hand;
  const hand::HandModel& model;
  SampleGate gate;
  physics_io::ReplayDriver replay;      // lockstep: the world advanced to each sample's stamp
  physics_io::InputFollower follower;  // real time: the hand a small delay behind the samples
  bool expected = false;               // lockstep: the world waits for this hand's samples
  dds::InstanceHandle_t source;
  bool have_source = false;
  uint64_t received = 0;
  int64_t last_sample_wall_ns = 0;
  uint64_t glove_lost = 0;             // real time (lockstep: the replay driver counts)
  bool tracking = false;
  bool have_input = false;
  physics::HandInput input;
  // lockstep: samples received and not yet given to the replay driver (it takes each as the
  // world reaches it, by the offline runner's rule)
  physics_io::HandFeed feed;
  bool arrived_frozen = false;  // lockstep: samples came while time was frozen
};

// Everything the loop keeps between steps, in one place.
class Node {
 public:
  Node(DdsParticipant& participant, physics::Scene scene, const NodeOptions& options)
      : options_(options),
        world_(std::move(scene)),
        reader_(participant.make_reader<cockpit::HandSample>(options.lockstep ? "reliable"
                                                                              : "stream")),
        // volatile: a node (re)started later does not carry out old commands
        command_reader_(participant.make_reader<cockpit::ControlCommand>("command")),
        publisher_(participant, world_),
        sim_(participant, world_, options.node_name) {
    hands_.reserve(static_cast<std::size_t>(world_.hand_count()));
    for (int h = 0; h < world_.hand_count(); ++h)
      hands_.emplace_back(world_, h, options);
    shown_.resize(hands_.size());
    for (const int id : options.lockstep_hands) {
      const int h = world_.hand_index(id);
      if (h < 0) throw std::invalid_argument("--lockstep-hands: the scene has no such hand");
      hands_[static_cast<std::size_t>(h)].expected = true;
    }
    if (!options.checkpoint_path.empty()) start_checkpoints();
    publisher_.publish_object_info(world_);
    publisher_.publish_hand_info(world_);
    publisher_.publish_control_info(world_);
    if (world_.time_ns() > 0) publish_state();  // resumed: the world as it was, at once
    if (!options.out_dir.empty()) {
      recorder_ = std::make_unique<physics_io::RunRecorder>(
          options.out_dir, physics_io::output_interval_ns(options.output_hz, world_.scene()));
    }
    last_status_ns_ = monotonic_now_ns();
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
      const int h = world_.hand_index(static_cast<int>(message_.hand_id()));
      if (h < 0) {  // a hand this scene does not have: refused and counted
        if (unknown_hand_++ == 0)
          spdlog::warn("hand samples for hand_id {}, which the scene has not: ignored (counted)",
                       message_.hand_id());
        continue;
      }
      HandChannel& ch = hands_[static_cast<std::size_t>(h)];
      const bool new_source = !ch.have_source || info.publication_handle != ch.source;
      if (new_source) ch.gate.reset_time();
      hand::GloveSample sample;
      if (!ch.gate.accept(message_, sample)) continue;
      if (new_source) {
        if (ch.have_source)
          spdlog::info("{} hand samples from a new source: following its timeline", side_name(h));
        ch.source = info.publication_handle;
        ch.have_source = true;
      }
      ++received_;
      ++ch.received;
      stats_.record_sample(info, message_.source_stamp_ns(), take_ns);
      ch.last_sample_wall_ns = take_ns;
      on_sample(ch, sample, new_source, take_ns);
    }
  }

  const char* side_name(int hand) const { return world_.hand_id(hand) == 1 ? "left" : "right"; }

  bool glove_alive(const HandChannel& ch, int64_t now_ns) const {
    if (ch.received == 0) return false;
    const bool recent = now_ns - ch.last_sample_wall_ns <= options_.timing.glove_timeout_ns;
    return recent && reader_.alive_writer_count() > 0;
  }
  bool any_glove_alive(int64_t now_ns) const {
    for (const HandChannel& ch : hands_)
      if (glove_alive(ch, now_ns)) return true;
    return false;
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
    log_events();
    ++steps_in_period_;
    for (int s = 0; s < physics::kStageCount; ++s) stage_ns_[s] += world_.stage_times().ns[s];
    maybe_checkpoint();
  }

  // --checkpoint: the fingerprint of the scene as it starts, then (--resume) the newest save.
  void start_checkpoints() {
    const std::filesystem::path dir = std::filesystem::path(options_.checkpoint_path).parent_path();
    std::error_code error;
    if (!dir.empty()) std::filesystem::create_directories(dir, error);
    if (error)
      throw std::runtime_error("--checkpoint: cannot create " + dir.string() + ": " + error.message());
    fingerprint_ = physics_io::scene_fingerprint(world_);
    if (options_.resume) resume_from_checkpoint();
    checkpointer_ = std::make_unique<CheckpointWriter>(options_.checkpoint_path, fingerprint_);
    next_checkpoint_ns_ = world_.time_ns() + seconds_to_ns(options_.checkpoint_every_s);
  }
  void resume_from_checkpoint() {
    const std::string& path = options_.checkpoint_path;
    std::optional<physics_io::Checkpoint> saved;
    try {
      saved = physics_io::read_checkpoint_file(path, world_);
    } catch (const physics_io::CheckpointError& e) {
      std::error_code ignored;
      std::filesystem::rename(path, path + ".bad", ignored);
      spdlog::error("not resumed: {} (kept as {}.bad); starting from the scene", e.what(), path);
      return;
    }
    if (!saved) {
      spdlog::warn("not resumed: no checkpoint {} yet; starting from the scene", path);
      return;
    }
    world_.restore(saved->world);
    sim_.restore_frozen(saved->frozen);
    int held = 0;
    for (const physics::BodyState& b : world_.state().bodies) held += b.held() ? 1 : 0;
    spdlog::info("resumed from {}: {:.3f} s simulated, {} steps, {} object(s) held{}; the hands "
                 "take up their gloves from their next samples",
                 path, ns_to_seconds(world_.time_ns()), world_.step_count(), held,
                 saved->frozen ? ", frozen" : "");
  }
  // Every checkpoint_every_s of simulated time (or now, `force`): the world to the writer thread.
  void maybe_checkpoint(bool force = false) {
    if (!checkpointer_ || (!force && world_.time_ns() < next_checkpoint_ns_)) return;
    checkpoint_.world = world_.state();  // into the buffers of an older one: no allocation
    checkpoint_.frozen = sim_.frozen();
    checkpointer_->offer(checkpoint_);
    next_checkpoint_ns_ = world_.time_ns() + seconds_to_ns(options_.checkpoint_every_s);
  }
  // At stop: the last world saved, and how saving went.
  void finish_checkpoints() {
    if (!checkpointer_) return;
    maybe_checkpoint(true);
    checkpointer_->flush();
    spdlog::info("checkpoints: {} written to {}, {} replaced by a newer one before written, {} "
                 "failed",
                 checkpointer_->written(), checkpointer_->path(), checkpointer_->superseded(),
                 checkpointer_->failed());
  }

  // The last step's (or reset's) faults, grasp and control events, in the log.
  void log_events() {
    for (const auto& f : world_.step_faults()) {
      spdlog::warn("object '{}' (#{}): {} at {:.3f} s, put back where it was at the step's start, "
                   "at rest (further faults of it are counted, not logged)",
                   world_.scene().objects[f.object].name, f.object,
                   physics::body_fault_name(f.what), ns_to_seconds(f.first_t_ns));
    }
    for (const auto& e : world_.step_events()) {
      const int h = world_.hand_index(e.hand_id);
      if (e.grasp && h >= 0) ++grasps_[static_cast<std::size_t>(h)];
      spdlog::info("{} {} at {:.3f} s{}: {}", e.grasp ? "GRASP" : "RELEASE",
                   world_.scene().objects[e.object].name, ns_to_seconds(e.t_ns),
                   hands_.size() > 1 ? std::string(" by the ") + (e.hand_id == 1 ? "left" : "right") + " hand"
                                     : std::string(),
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
  }

  // The instructor's commands (sim_commands.hpp), before a step: a reset's releases and control
  // changes are published and the world shown at once; after a freeze in lockstep, the hands
  // take up their gloves from now.
  void take_sim_commands() {
    const bool was_frozen = sim_.frozen();
    const SimCommands::Taken taken = sim_.take(world_);
    if (taken.reset || sim_.frozen() != was_frozen) maybe_checkpoint(true);
    if (taken.reset) {
      publisher_.publish_events(world_);
      log_events();
      if (options_.lockstep) {
        publish_lockstep_state();
      } else {
        publish_state();
      }
    }
    if (taken.unfrozen && options_.lockstep) resume_lockstep();
  }
  // Lockstep, frozen: the samples that keep arriving are not stepped through; each hand keeps
  // only its newest (the glove's present) for when time goes on.
  void hold_frozen_lockstep() {
    for (HandChannel& ch : hands_) {
      if (!ch.feed.has_queued()) continue;
      ch.feed.keep_newest_only();
      ch.arrived_frozen = true;
    }
  }
  // Lockstep, unfrozen: the world's time stood still while the gloves' went on; each hand that
  // sent samples meanwhile starts a new timeline at its newest sample, all at one origin (the
  // latest of them is the world's present, so none begins in the future: a hand every step
  // waits for must have its sample now), and the world goes on from where it stopped.
  void resume_lockstep() {
    bool any = false;
    int64_t origin_ns = 0;
    for (HandChannel& ch : hands_) {
      if (!ch.arrived_frozen || !ch.feed.has_queued()) continue;
      const int64_t t_ns = ch.feed.front().t_ns;
      origin_ns = any ? std::max(origin_ns, t_ns) : t_ns;
      any = true;
    }
    for (HandChannel& ch : hands_) {
      if (!ch.arrived_frozen || !ch.feed.has_queued()) continue;
      ch.replay.restart();
      ch.replay.set_origin(origin_ns);
      ch.arrived_frozen = false;
    }
  }

  void publish_state() {
    const int64_t start = monotonic_now_ns();
    publisher_.publish_state(world_, shown_);
    publish_ns_ += monotonic_now_ns() - start;
  }
  // lockstep: the hands the replay drivers gave the last step
  void publish_lockstep_state() {
    for (std::size_t h = 0; h < hands_.size(); ++h) {
      const physics_io::ShownInput& shown = hands_[h].replay.shown();
      shown_[h] = {{shown.sample_time_ns, shown.source_stamp_ns}, shown.tracking};
    }
    publish_state();
  }

  void maybe_publish_status(int64_t now_ns, bool alive, const char* detail);
  // Everything counted about the input so far: the gate's, the timing's (follower in real time,
  // replay driver in lockstep), glove lost.
  hand::InputCounts input_counts(const HandChannel& ch) const {
    hand::InputCounts c = ch.gate.counts();
    c.rejected_out_of_range += ch.gate.rejected_flagged_or_far();  // as node_status always had it
    c += options_.lockstep ? ch.replay.counts() : ch.follower.counts();
    c.glove_lost += ch.glove_lost;
    return c;
  }
  hand::InputCounts input_counts() const {
    hand::InputCounts c;
    for (const HandChannel& ch : hands_) c += input_counts(ch);
    return c;
  }
  uint64_t rejected() const {
    uint64_t n = unknown_hand_;
    for (const HandChannel& ch : hands_) n += ch.gate.rejected();
    return n;
  }

  // --duration: the loops stop by themselves at this monotonic time (0: never).
  void start_clock() {
    run_start_ns_ = monotonic_now_ns();
    steps_at_start_ = world_.step_count();
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
  std::vector<HandChannel> hands_;      // per world hand: its input
  std::vector<HandInputState> shown_;   // per world hand: what hand_state says of its input
  uint64_t unknown_hand_ = 0;           // samples for a hand the scene has not
  std::array<uint32_t, physics::kMaxHands> grasps_{};  // per world hand
  physics_io::HandMotionPeak hand_peak_;
  Reader<cockpit::HandSample> reader_;
  Reader<cockpit::ControlCommand> command_reader_;
  cockpit::ControlCommand command_;
  uint64_t commands_refused_ = 0;
  StatePublisher publisher_;
  SimCommands sim_;
  cockpit::HandSample message_;
  uint64_t received_ = 0;
  uint64_t received_at_last_status_ = 0;
  uint64_t late_steps_ = 0;
  uint64_t steps_in_period_ = 0;
  int64_t stage_ns_[physics::kStageCount] = {};
  int64_t publish_ns_ = 0;
  int64_t last_status_ns_ = 0;
  int64_t run_start_ns_ = 0;
  uint64_t steps_at_start_ = 0;  // a resumed world's steps before this run
  int64_t stop_at_ns_ = 0;
  LoopStats stats_;
  std::unique_ptr<physics_io::RunRecorder> recorder_;  // lockstep --out
  bool recording_started_ = false;
  std::unique_ptr<CheckpointWriter> checkpointer_;  // --checkpoint
  uint64_t fingerprint_ = 0;
  int64_t next_checkpoint_ns_ = 0;
  physics_io::Checkpoint checkpoint_;  // reused: a copy of the world's state
};

void Node::report_stop(StatsReport report) {
  report.steps = world_.step_count() - steps_at_start_;
  report.samples = received_;
  report.rejected = rejected();
  report.input = input_counts();
  report.hand_peak_wrist_mps = hand_peak_.wrist_mps();
  report.hand_peak_joint_radps = hand_peak_.joint_radps();
  spdlog::info("DDS transit {}; sample age at step {}; step compute {}",
               latency_text_us(stats_.dds_transit), latency_text_us(stats_.age_at_step),
               latency_text_us(stats_.step_compute));
  spdlog::info("input: {}", hand::input_counts_text(report.input));
  if (hands_.size() > 1) {
    for (const HandChannel& ch : hands_)
      spdlog::info("{} hand: {} samples; {}", side_name(ch.hand), ch.received,
                   hand::input_counts_text(input_counts(ch)));
  }
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
  status.input_delay_ms(options_.lockstep ? 0.0 : static_cast<double>(hands_.front().follower.delay_ns()) * 1e-6);
  // each hand: its samples, glove losses, tracking and grasps
  status.hands().clear();
  for (const HandChannel& ch : hands_) {
    cockpit::HandInputStatus h;
    h.hand_id(static_cast<uint32_t>(world_.hand_id(ch.hand)));
    h.received(ch.received);
    h.glove_lost(input_counts(ch).glove_lost);
    h.tracking(options_.lockstep ? ch.replay.shown().tracking : ch.tracking);
    h.grasps(grasps_[static_cast<std::size_t>(ch.hand)]);
    status.hands().push_back(h);
  }
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
  spdlog::info("real time: {} Hz steps ({} substeps), world published at {} Hz; the hand {} "
               "behind its glove, gaps over {:.3f} s not bridged",
               options_.rate_hz, world_.substeps(), options_.publish_hz,
               options_.input_delay_s ? fmt::format("{:.1f} ms", *options_.input_delay_s * 1e3)
                                      : std::string("one usual sample interval + 2 ms"),
               static_cast<double>(options_.timing.max_gap_ns) * 1e-9);
  physics_io::FollowedInput followed;
  char detail[64] = "no glove yet";
  while (!should_stop(monotonic_now_ns())) {
    sleep_until_ns(next_ns);
    drain([&](HandChannel& ch, const hand::GloveSample& s, bool new_source, int64_t take_ns) {
      if (new_source) ch.follower.reset();
      ch.follower.push(s, take_ns, message_.source_stamp_ns());
    });
    take_sim_commands();
    const bool frozen = sim_.frozen();
    const int64_t now_ns = monotonic_now_ns();
    bool any_alive = false;
    bool any_input = false;
    for (HandChannel& ch : hands_) {
      const bool alive = glove_alive(ch, now_ns);
      if (alive != ch.tracking && ch.have_input) {
        if (alive) {
          spdlog::warn("{} glove samples resumed: tracking", side_name(ch.hand));
        } else {
          spdlog::warn("{} glove lost: holding the hand, releasing what it holds", side_name(ch.hand));
        }
        if (!alive) ++ch.glove_lost;
      }
      ch.tracking = alive;
      any_alive = any_alive || alive;
      // the hand at the end of this step's slot, a small delay behind the source
      HandInputState& shown = shown_[static_cast<std::size_t>(ch.hand)];
      if (ch.follower.at(next_ns + period_ns, followed)) {
        ch.input = physics_io::hand_input_from_glove(ch.model, followed.sample);
        shown.stamps = {followed.sample.t_ns, followed.source_stamp_ns};
        ch.have_input = true;
      }
      if (ch.have_input) {
        ch.input.tracking = ch.tracking;
        world_.set_hand_input(ch.input, ch.hand);
      }
      shown.tracking = ch.tracking;
      any_input = any_input || ch.have_input;
    }
    // frozen: time stands still (no step), everything else goes on
    if (!frozen) step_world();
    const int64_t end_ns = monotonic_now_ns();
    if (!frozen) {
      for (const HandChannel& ch : hands_)
        if (ch.have_input && ch.tracking)
          stats_.hand_lag.record_ns(end_ns - shown_[static_cast<std::size_t>(ch.hand)].stamps.source_stamp_ns);
      if (end_ns > next_ns + period_ns) ++late_steps_;
    }
    if (end_ns >= next_publish_ns) {
      publish_state();
      next_publish_ns += publish_period_ns;
      if (next_publish_ns < end_ns) next_publish_ns = end_ns + publish_period_ns;
    }
    // "tracking", "glove lost" (every hand with input lost), or which hand's glove is lost
    if (frozen) {
      std::snprintf(detail, sizeof detail, "frozen");
    } else if (!any_input) {
      std::snprintf(detail, sizeof detail, "no glove yet");
    } else if (!any_alive) {
      std::snprintf(detail, sizeof detail, "glove lost");
    } else {
      std::snprintf(detail, sizeof detail, "tracking");
      for (const HandChannel& ch : hands_)
        if (ch.have_input && !ch.tracking)
          std::snprintf(detail, sizeof detail, "tracking; %s glove lost", side_name(ch.hand));
    }
    maybe_publish_status(end_ns, any_alive, detail);
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
  finish_checkpoints();
  const double loop_s = ns_to_seconds(loop_end_ns - run_start_ns_);
  const uint64_t steps = world_.step_count() - steps_at_start_;  // this run's (not a resumed world's)
  const double rate_hz = loop_s > 0 ? static_cast<double>(steps) / loop_s : 0.0;
  spdlog::info("stopped after {} steps in {:.3f} s ({:.1f} Hz); {} samples accepted, {} rejected, "
               "{} late steps",
               steps, loop_s, rate_hz, received_, rejected(), late_steps_);
  StatsReport report;
  report.mode = "realtime";
  report.rate_hz = rate_hz;
  report.late_steps = late_steps_;
  report.duration_s = loop_s;
  report.input_delay_ns = hands_.front().follower.delay_ns();
  report_stop(report);
  return 0;
}

int Node::run_lockstep() {
  const int64_t publish_every_ns = std::llround(1e9 / options_.publish_hz);
  int64_t next_publish_sim_ns = world_.time_ns();  // a resumed world goes on from its time
  bool dirty = false;
  spdlog::info("lockstep: stepping to each sample's stamp ({} substeps per step)",
               world_.substeps());
  start_clock();
  int64_t last_publish_ns = 0;
  const int64_t step_ns = std::llround(world_.scene().step_s * 1e9);
  while (!should_stop(monotonic_now_ns())) {
    const bool idle = !reader_.wait_for_data(20'000'000);
    drain([&](HandChannel& ch, const hand::GloveSample& s, bool new_source, int64_t) {
      if (new_source) {
        // world time 0 is the first sample; a later source continues from where the world is;
        // a second hand's first source shares the first hand's timeline (one clock)
        ch.replay.restart();
        const HandChannel* begun = nullptr;
        for (const HandChannel& other : hands_)
          if (&other != &ch && other.replay.has_sample()) begun = &other;
        if (begun != nullptr && !ch.replay.has_sample() && ch.received == 1)
          ch.replay.set_origin(begun->replay.source_time_at_world_zero() + world_.time_ns());
        ch.feed.drop_queued();
      }
      ch.feed.queue(s, message_.source_stamp_ns());
    });
    take_sim_commands();
    if (sim_.frozen()) hold_frozen_lockstep();
    // Step as the offline runner does (HandFeed's rule): before each step, each hand takes its
    // samples up to the first at or past the step's end; the step waits until every hand that
    // has begun (and every --lockstep-hands hand) has one, as more samples may still come.
    while (!sim_.frozen()) {
      const int64_t step_end_ns = world_.time_ns() + step_ns;
      bool ready = true;
      bool any = false;
      for (HandChannel& ch : hands_) {
        ch.feed.take_until(ch.replay, step_end_ns, world_.time_ns());
        if (!ch.replay.has_sample()) {
          ready = ready && !ch.expected;
          continue;
        }
        any = true;
        ready = ready && ch.replay.newest_world_ns() >= step_end_ns;
      }
      // the offline runner's first row: the hands set by their first samples, before any step
      if (any && recorder_ && !recording_started_) {
        recorder_->start(world_);
        recording_started_ = true;
      }
      if (!ready || !any) break;
      for (HandChannel& ch : hands_)
        if (ch.replay.has_sample()) ch.replay.input_for_step_ending(step_end_ns);
      step_world();
      dirty = true;
      if (world_.time_ns() >= next_publish_sim_ns) {
        publish_lockstep_state();
        last_publish_ns = monotonic_now_ns();
        next_publish_sim_ns += publish_every_ns;
      }
    }
    // caught up with the input: show where the world is, at most at --publish-hz of wall time
    // (a replay at its own pace would otherwise publish every sample), and at once when the
    // input pauses or ends
    const int64_t now_ns = monotonic_now_ns();
    if (dirty && (idle || now_ns - last_publish_ns >= publish_every_ns)) {
      publish_lockstep_state();
      last_publish_ns = now_ns;
      dirty = false;
    }
    const bool alive = any_glove_alive(now_ns);
    bool started = false;
    for (const HandChannel& ch : hands_) started = started || ch.replay.started();
    maybe_publish_status(now_ns, alive,
                         sim_.frozen() ? "lockstep, frozen"
                         : alive       ? "lockstep"
                         : started     ? "lockstep, input ended"
                                       : "lockstep, waiting");
  }
  const int64_t loop_end_ns = monotonic_now_ns();
  publisher_.flush(500'000'000);
  finish_checkpoints();
  if (recorder_) {
    if (!recording_started_) recorder_->start(world_);
    recorder_->commit();
    spdlog::info("wrote {}/trajectories.csv and events.jsonl", options_.out_dir);
  }
  spdlog::info("stopped at {:.3f} s simulated after {} steps; {} samples accepted, {} rejected",
               ns_to_seconds(world_.time_ns()), world_.step_count(), received_, rejected());
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
