#include "physics_node/node/node_status.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>

#include "common/clock.hpp"
#include "idl/topics/node_status_convert.hpp"

namespace vcockpit::physics_node {

NodeStatusReporter::NodeStatusReporter(const NodeOptions& options, const physics::World& world,
                                       const HandChannels& hands, WorldStepper& stepper,
                                       StatePublisher& publisher)
    : options_(options),
      world_(world),
      hands_(hands),
      stepper_(stepper),
      publisher_(publisher),
      last_status_ns_(monotonic_now_ns()) {}

void NodeStatusReporter::maybe_publish(int64_t now_ns, bool alive, const char* detail,
                                       uint64_t late_steps) {
  if (now_ns - last_status_ns_ < 1'000'000'000) return;
  const double period_s = ns_to_seconds(now_ns - last_status_ns_);
  cockpit::NodeStatus status;
  status.node_name(options_.node_name);
  status.state(alive ? cockpit::RUNNING : cockpit::DEGRADED);
  status.detail(detail);
  status.stamp_ns(now_ns);
  status.loop_rate_hz(static_cast<double>(stepper_.steps_in_period()) / period_s);
  status.input_rate_hz(static_cast<double>(hands_.received() - received_at_last_status_) / period_s);
  status.received(hands_.received());
  status.published(world_.step_count());
  set_input_counts(hands_.counts(), status);
  status.input_delay_ms(options_.lockstep ? 0.0
                                          : static_cast<double>(hands_.front().follower.delay_ns()) * 1e-6);
  // each hand: its samples, glove losses, tracking and grasps
  status.hands().clear();
  for (const HandChannel& ch : hands_) {
    cockpit::HandInputStatus h;
    h.hand_id(static_cast<uint32_t>(world_.hand_id(ch.hand)));
    h.received(ch.received);
    h.glove_lost(hands_.counts(ch).glove_lost);
    h.tracking(options_.lockstep ? ch.replay.shown().tracking : ch.tracking);
    h.grasps(stepper_.grasps(ch.hand));
    status.hands().push_back(h);
  }
  status.late_steps(late_steps);
  status.input_alive(alive);
  const uint64_t steps_in_period = stepper_.steps_in_period();
  const double steps = steps_in_period > 0 ? static_cast<double>(steps_in_period) : 1.0;
  static_assert(physics::kStageCount == static_cast<int>(cockpit::STAGE_PUBLISH),
                "the topic's stages are the world's, in its order, then publish and total");
  for (int s = 0; s < physics::kStageCount; ++s)
    status.stage_time_us()[s] = static_cast<double>(stepper_.stage_ns()[s]) * 1e-3 / steps;
  status.stage_time_us()[cockpit::STAGE_PUBLISH] = static_cast<double>(publish_ns_) * 1e-3 / steps;
  double total = 0;
  for (int s = 0; s < static_cast<int>(cockpit::STAGE_TOTAL); ++s) total += status.stage_time_us()[s];
  status.stage_time_us()[cockpit::STAGE_TOTAL] = total;
  publisher_.publish_status(status);
  stepper_.clear_period();
  publish_ns_ = 0;
  received_at_last_status_ = hands_.received();
  last_status_ns_ = now_ns;
}

void NodeStatusReporter::report_stop(StatsReport report, uint64_t steps_this_run,
                                     const LoopStats& stats) const {
  report.steps = steps_this_run;
  report.samples = hands_.received();
  report.rejected = hands_.rejected();
  report.input = hands_.counts();
  report.hand_peak_wrist_mps = stepper_.hand_peak().wrist_mps();
  report.hand_peak_joint_radps = stepper_.hand_peak().joint_radps();
  spdlog::info("DDS transit {}; sample age at step {}; step compute {}",
               latency_text_us(stats.dds_transit), latency_text_us(stats.age_at_step),
               latency_text_us(stats.step_compute));
  spdlog::info("input: {}", hand::input_counts_text(report.input));
  if (hands_.size() > 1) {
    for (const HandChannel& ch : hands_)
      spdlog::info("{} hand: {} samples; {}", hands_.side_name(ch.hand), ch.received,
                   hand::input_counts_text(hands_.counts(ch)));
  }
  if (!options_.lockstep) {
    spdlog::info("hand lag behind its source {} (interpolation delay now {:.2f} ms); peak wrist "
                 "speed {:.2f} m/s, joint {:.1f} rad/s",
                 latency_text_us(stats.hand_lag),
                 static_cast<double>(report.input_delay_ns.value_or(0)) * 1e-6,
                 report.hand_peak_wrist_mps, report.hand_peak_joint_radps);
  }
  if (options_.stats_out.empty()) return;
  write_stats_json(options_.stats_out, report, stats);
  spdlog::info("statistics written to {}", options_.stats_out);
}

void realtime_status_detail(const HandChannels& hands, bool frozen, char* out, std::size_t size) {
  bool any_input = false;
  bool any_alive = false;
  for (const HandChannel& ch : hands) {
    any_input = any_input || ch.have_input;
    any_alive = any_alive || ch.tracking;
  }
  if (frozen) {
    std::snprintf(out, size, "frozen");
  } else if (!any_input) {
    std::snprintf(out, size, "no glove yet");
  } else if (!any_alive) {
    std::snprintf(out, size, "glove lost");
  } else {
    std::snprintf(out, size, "tracking");
    for (const HandChannel& ch : hands)
      if (ch.have_input && !ch.tracking)
        std::snprintf(out, size, "tracking; %s glove lost", hands.side_name(ch.hand));
  }
}

}  // namespace vcockpit::physics_node
