#include "glove_driver/node/sample_publisher.hpp"

#include <spdlog/spdlog.h>

#include "common/clock.hpp"
#include "common/signals.hpp"
#include "idl/topics/hand_sample_convert.hpp"
#include "idl/topics/node_status_convert.hpp"

namespace vcockpit::glove {

SamplePublisher::SamplePublisher(DdsParticipant& participant, const hand::HandModel& hand,
                                 const PublisherOptions& options)
    : options_(options),
      validator_(hand),
      writer_(participant.make_writer<cockpit::HandSample>(options.lockstep ? "reliable"
                                                                            : "hand_stream")),
      status_writer_(participant.make_writer<cockpit::NodeStatus>("state")) {
  last_status_ns_ = monotonic_now_ns();
}

bool SamplePublisher::wait_for_readers() {
  if (options_.readers <= 0) return true;
  spdlog::info("waiting up to {} s for {} reader(s) on {}{}", options_.match_timeout_s,
               options_.readers, TopicTraits<cockpit::HandSample>::kName,
               options_.lockstep ? "" : " (--wait-readers 0 starts at once)");
  const int64_t deadline = monotonic_now_ns() + seconds_to_ns(options_.match_timeout_s);
  while (!shutdown_requested() && monotonic_now_ns() < deadline) {
    if (writer_.wait_for_matched(options_.readers, 100'000'000)) return true;
  }
  if (shutdown_requested()) return false;
  if (options_.lockstep) {
    spdlog::error("lockstep: {} reader(s) did not match within {} s", options_.readers,
                  options_.match_timeout_s);
    return false;
  }
  spdlog::warn("{} reader(s) did not match within {} s ({} did): starting anyway", options_.readers,
               options_.match_timeout_s, writer_.matched_count());
  return true;
}

hand::InputCounts SamplePublisher::counts() const {
  hand::InputCounts c = load_counts_;
  c += validator_.counts();
  c += interval_counts_;
  return c;
}

bool SamplePublisher::publish(hand::GloveSample sample) {
  if (!validator_.accept(sample)) return false;
  if (validator_.counts().accepted > 1) {
    const int64_t interval_ns = sample.t_ns - last_t_ns_;
    hand::count_interval(interval_counts_, intervals_.add(interval_ns, options_.max_gap_ns),
                         interval_ns, false);
  }
  last_t_ns_ = sample.t_ns;
  message_ = to_hand_sample(sample, options_.hand_id, published_, monotonic_now_ns());
  // a reliable history stays full while a reader lags; keep trying while it is still there
  while (!writer_.write(message_)) {
    if (!options_.lockstep || shutdown_requested() || writer_.matched_count() == 0) {
      ++write_failures_;
      return false;
    }
  }
  ++published_;
  return true;
}

void SamplePublisher::tick(int64_t now_ns) {
  if (now_ns - last_status_ns_ >= 1'000'000'000) publish_status(cockpit::RUNNING, now_ns);
}

bool SamplePublisher::finish() {
  bool ok = true;
  // a lockstep replay that ran to its end waits for every acknowledgement; one stopped (Ctrl-C,
  // the rig stopping) does not: the node holds back what it has not stepped to (its reader is
  // full), and waiting for that would outlast the launcher's stop
  if (options_.lockstep && published_ > 0 && !shutdown_requested()) {
    ok = writer_.wait_for_acknowledgments(seconds_to_ns(options_.match_timeout_s));
    if (!ok) spdlog::error("lockstep: subscribers did not acknowledge every sample");
  } else if (published_ > 0) {
    // a reliable reader (a recorder, a lockstep node) may still be having the last samples
    // repaired: a moment for that, never long enough to hold up a stop (best-effort readers
    // acknowledge nothing)
    writer_.wait_for_acknowledgments(500'000'000);
  }
  publish_status(cockpit::STOPPING, monotonic_now_ns());
  status_writer_.wait_for_acknowledgments(1'000'000'000);  // the last report must not be lost
  return ok && write_failures_ == 0;
}

void SamplePublisher::publish_status(cockpit::NodeState state, int64_t now_ns) {
  const hand::InputCounts c = counts();
  cockpit::NodeStatus status;
  status.node_name(options_.node_name);
  status.state(state);
  status.stamp_ns(now_ns);
  const double period_s = ns_to_seconds(now_ns - last_status_ns_);
  status.loop_rate_hz(period_s > 0 ? static_cast<double>(published_ - published_at_last_status_) / period_s
                                   : 0.0);
  status.published(published_);
  status.received(c.accepted);
  set_input_counts(c, status);
  status.input_delay_ms(0.0);
  status.input_alive(true);
  status.detail(std::string(options_.lockstep ? "lockstep" : "stream") + ", " +
                std::to_string(writer_.matched_count()) + " subscriber(s)");
  status_writer_.write(status);
  last_status_ns_ = now_ns;
  published_at_last_status_ = published_;
}

}  // namespace vcockpit::glove
