#include "physics_node/node/node_loop.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "common/signals.hpp"
#include "physics_node/io/hand_input.hpp"
#include "physics_node/node/hand_channels.hpp"
#include "physics_node/node/lockstep_input.hpp"
#include "physics_node/node/loop_stats.hpp"
#include "physics_node/node/node_status.hpp"
#include "physics_node/node/realtime_pacer.hpp"
#include "physics_node/node/sim_commands.hpp"
#include "physics_node/node/state_publisher.hpp"
#include "physics_node/node/world_stepper.hpp"

namespace vcockpit::physics_node {
namespace {

// Lockstep: samples a hand may have queued ahead of the world before the node stops taking more
// (256 ms of a 1 kHz glove; the world needs one past each step's end), and the wall time it
// steps between looks at its input, commands and stop.
constexpr std::size_t kLockstepFeedBound = 256;
constexpr int64_t kLockstepSliceNs = 10'000'000;

// The node: the world and its pieces (input, stepping, status; publishing and the instructor's
// commands), and the two modes' loops, which differ only in their pacing.
class Node {
 public:
  Node(DdsParticipant& participant, physics::Scene scene, const NodeOptions& options)
      : options_(options),
        world_(std::move(scene)),
        hands_(participant, world_, options_),
        publisher_(participant, world_),
        sim_(participant, world_, options.node_name),
        stepper_(participant, world_, publisher_, sim_, options_),
        status_(options_, world_, hands_, stepper_, publisher_),
        lockstep_(hands_, world_) {
    shown_.resize(hands_.size());
    publisher_.publish_object_info(world_);
    publisher_.publish_hand_info(world_);
    publisher_.publish_control_info(world_);
    if (world_.time_ns() > 0) publish_state();  // resumed: the world as it was, at once
  }

  int run_realtime();
  int run_lockstep();

 private:
  // The instructor's commands (sim_commands.hpp), before a step: a reset's releases and control
  // changes are published and the world shown at once; after a freeze in lockstep, the hands
  // take up their gloves from now.
  void take_sim_commands() {
    const bool was_frozen = sim_.frozen();
    const SimCommands::Taken taken = sim_.take(world_);
    if (taken.reset || sim_.frozen() != was_frozen) stepper_.maybe_checkpoint(true);
    if (taken.reset_to_start) stepper_.control_frames().after_reset_to_start(world_);
    if (taken.reset) {
      stepper_.publish_events();
      if (options_.lockstep) {
        publish_lockstep_state();
      } else {
        publish_state();
      }
    }
    if (taken.unfrozen && options_.lockstep) lockstep_.resume_after_freeze();
  }

  void publish_state() {
    const int64_t start = monotonic_now_ns();
    publisher_.publish_state(world_, shown_);
    status_.add_publish_ns(monotonic_now_ns() - start);
  }
  // lockstep: the hands the replay drivers gave the last step
  void publish_lockstep_state() {
    for (const HandChannel& ch : hands_) {
      const physics_io::ShownInput& shown = ch.replay.shown();
      shown_[static_cast<std::size_t>(ch.hand)] = {{shown.sample_time_ns, shown.source_stamp_ns},
                                                   shown.tracking};
    }
    publish_state();
  }

  // Real time: each hand's input for the step ending at slot_end_ns, a small delay behind its
  // source (the follower), with its glove's tracking.
  void set_realtime_inputs(int64_t slot_end_ns) {
    physics_io::FollowedInput followed;
    for (HandChannel& ch : hands_) {
      HandInputState& shown = shown_[static_cast<std::size_t>(ch.hand)];
      if (ch.follower.at(slot_end_ns, followed)) {
        ch.input = physics_io::hand_input_from_glove(ch.model, followed.sample);
        shown.stamps = {followed.sample.t_ns, followed.source_stamp_ns};
        ch.have_input = true;
      }
      if (ch.have_input) {
        ch.input.tracking = ch.tracking;
        world_.set_hand_input(ch.input, ch.hand);
      }
      shown.tracking = ch.tracking;
    }
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
  uint64_t steps_this_run() const { return world_.step_count() - steps_at_start_; }

  NodeOptions options_;
  physics::World world_;
  HandChannels hands_;                 // input
  StatePublisher publisher_;
  SimCommands sim_;
  WorldStepper stepper_;               // stepping
  NodeStatusReporter status_;          // status
  LockstepInput lockstep_;             // lockstep's stepping rule
  std::vector<HandInputState> shown_;  // per world hand: what hand_state says of its input
  LoopStats stats_;
  int64_t run_start_ns_ = 0;
  uint64_t steps_at_start_ = 0;  // a resumed world's steps before this run
  int64_t stop_at_ns_ = 0;
};

int Node::run_realtime() {
  start_clock();
  RealtimePacer pacer(std::llround(1e9 / options_.rate_hz), std::llround(1e9 / options_.publish_hz),
                      run_start_ns_);
  spdlog::info("real time: {} Hz steps, world published at {} Hz; the hand {} "
               "behind its glove, gaps over {:.3f} s not bridged",
               options_.rate_hz, options_.publish_hz,
               options_.input_delay_s ? fmt::format("{:.1f} ms", *options_.input_delay_s * 1e3)
                                      : std::string("one usual sample interval + 2 ms"),
               static_cast<double>(options_.timing.max_gap_ns) * 1e-9);
  char detail[64] = "no glove yet";
  while (!should_stop(monotonic_now_ns())) {
    pacer.wait_for_slot();
    hands_.drain(stats_, [&](HandChannel& ch, const hand::GloveSample& s, bool new_source,
                             int64_t take_ns) {
      if (new_source) ch.follower.reset();
      ch.follower.push(s, take_ns, hands_.source_stamp_ns());
    });
    take_sim_commands();
    const bool frozen = sim_.frozen();
    const bool any_alive = hands_.track_gloves(monotonic_now_ns());
    set_realtime_inputs(pacer.slot_end_ns());
    // frozen: time stands still (no step), everything else goes on
    if (!frozen) stepper_.step(stats_);
    const int64_t end_ns = monotonic_now_ns();
    if (!frozen) {
      for (const HandChannel& ch : hands_)
        if (ch.have_input && ch.tracking)
          stats_.hand_lag.record_ns(end_ns - shown_[static_cast<std::size_t>(ch.hand)].stamps.source_stamp_ns);
      pacer.step_ended(end_ns);
    }
    if (pacer.publish_due(end_ns)) publish_state();
    realtime_status_detail(hands_, frozen, detail, sizeof detail);
    status_.maybe_publish(end_ns, any_alive, detail, pacer.late_steps());
    if (const int64_t dropped = pacer.next_slot(monotonic_now_ns()); dropped > 0)
      spdlog::warn("{} steps behind the clock: resynchronised (counted as late)", dropped);
  }
  // the loop's own figures end here: the flush below is shutdown, not stepping
  const int64_t loop_end_ns = monotonic_now_ns();
  stepper_.control_frames().flush(500'000'000);  // the systems score the run's end on them
  publisher_.flush(500'000'000);
  stepper_.finish_checkpoints();
  const double loop_s = ns_to_seconds(loop_end_ns - run_start_ns_);
  const uint64_t steps = steps_this_run();  // (not a resumed world's)
  const double rate_hz = loop_s > 0 ? static_cast<double>(steps) / loop_s : 0.0;
  spdlog::info("stopped after {} steps in {:.3f} s ({:.1f} Hz); {} samples accepted, {} rejected, "
               "{} late steps",
               steps, loop_s, rate_hz, hands_.received(), hands_.rejected(), pacer.late_steps());
  StatsReport report;
  report.mode = "realtime";
  report.rate_hz = rate_hz;
  report.late_steps = pacer.late_steps();
  report.duration_s = loop_s;
  report.input_delay_ns = hands_.front().follower.delay_ns();
  status_.report_stop(report, steps, stats_);
  return 0;
}

int Node::run_lockstep() {
  const int64_t publish_every_ns = std::llround(1e9 / options_.publish_hz);
  int64_t next_publish_sim_ns = world_.time_ns();  // a resumed world goes on from its time
  bool dirty = false;
  spdlog::info("lockstep: stepping to each sample's stamp");
  if (options_.wait_frame_readers > 0) {
    if (stepper_.control_frames().wait_for_readers(options_.wait_frame_readers, 30'000'000'000)) {
      spdlog::info("{} control_frame reader(s) matched", options_.wait_frame_readers);
    } else {
      spdlog::warn("--wait-frame-readers: fewer than {} control_frame readers after 30 s; stepping "
                   "anyway", options_.wait_frame_readers);
    }
  }
  start_clock();
  int64_t last_publish_ns = 0;
  const int64_t step_ns = std::llround(world_.scene().step_s * 1e9);
  bool waiting = true;  // the world waits for input (or time is frozen)
  while (!should_stop(monotonic_now_ns())) {
    const bool idle = waiting && !hands_.wait_for_data(20'000'000);
    // a world with samples to step takes no more while a hand has kLockstepFeedBound queued: the
    // rest waits in DDS and holds the glove driver's writes back, so a world slower than its
    // glove is never seconds of samples behind (nor is a restarted driver's first sample)
    hands_.drain_while(
        stats_,
        [&](HandChannel& ch, const hand::GloveSample& s, bool new_source, int64_t) {
          lockstep_.queue(ch, s, new_source, hands_.source_stamp_ns());
        },
        [&] { return waiting || !hands_.any_feed_holds(kLockstepFeedBound); });
    take_sim_commands();
    if (sim_.frozen()) lockstep_.hold_frozen();
    // every step the input allows, as the offline runner steps, for one slice of wall time: new
    // samples (a new source), commands and a stop are seen between slices
    waiting = sim_.frozen();
    const int64_t slice_end_ns = monotonic_now_ns() + kLockstepSliceNs;
    while (!sim_.frozen() && monotonic_now_ns() < slice_end_ns) {
      const int64_t step_end_ns = world_.time_ns() + step_ns;
      bool any = false;
      const bool ready = lockstep_.take_for_step(step_end_ns, any);
      // the offline runner's first row: the hands set by their first samples, before any step
      if (any) stepper_.start_recording_once();
      if (!ready) {
        waiting = true;
        break;
      }
      lockstep_.set_inputs(step_end_ns);
      stepper_.step(stats_);
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
    const bool alive = hands_.any_alive(now_ns);
    status_.maybe_publish(now_ns, alive,
                          sim_.frozen()         ? "lockstep, frozen"
                          : alive               ? "lockstep"
                          : lockstep_.started() ? "lockstep, input ended"
                                                : "lockstep, waiting",
                          0);
  }
  const int64_t loop_end_ns = monotonic_now_ns();
  stepper_.control_frames().flush(500'000'000);  // the systems score the run's end on them
  publisher_.flush(500'000'000);
  stepper_.finish_checkpoints();
  stepper_.commit_recording();
  spdlog::info("stopped at {:.3f} s simulated after {} steps; {} samples accepted, {} rejected",
               ns_to_seconds(world_.time_ns()), world_.step_count(), hands_.received(),
               hands_.rejected());
  StatsReport report;
  report.mode = "lockstep";
  report.duration_s = ns_to_seconds(loop_end_ns - run_start_ns_);
  report.simulated_s = ns_to_seconds(world_.time_ns());
  status_.report_stop(report, steps_this_run(), stats_);
  return 0;
}

}  // namespace

int run_node(DdsParticipant& participant, physics::Scene scene, const NodeOptions& options) {
  if (!scene.has_hands()) throw std::invalid_argument("the scene has no hand for the glove to drive");
  Node node(participant, std::move(scene), options);
  return options.lockstep ? node.run_lockstep() : node.run_realtime();
}

}  // namespace vcockpit::physics_node
