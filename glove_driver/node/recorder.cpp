#include "glove_driver/node/recorder.hpp"

#include <spdlog/spdlog.h>

#include "common/clock.hpp"
#include "common/signals.hpp"
#include "hand/glove_log.hpp"
#include "idl/topics/hand_sample_convert.hpp"
#include "hand/sample_validator.hpp"

namespace vcockpit::glove {
namespace {

bool should_stop(const RecorderOptions& o, uint64_t written, int64_t start_ns, int64_t last_ns,
                 int64_t now_ns) {
  if (shutdown_requested()) return true;
  if (o.count > 0 && written >= o.count) return true;
  if (o.duration_s > 0 && now_ns - start_ns >= seconds_to_ns(o.duration_s)) return true;
  return o.idle_timeout_s > 0 && written > 0 && now_ns - last_ns >= seconds_to_ns(o.idle_timeout_s);
}

}  // namespace

int run_recorder(DdsParticipant& participant, const hand::HandModel& hand,
                 const RecorderOptions& options) {
  auto reader = participant.make_reader<cockpit::HandSample>(options.lockstep ? "reliable"
                                                                             : "stream");
  hand::GloveLogWriter log(options.path, hand.left,
                     {"source: recorded from " + std::string(TopicTraits<cockpit::HandSample>::kName)});
  hand::SampleValidator validator(hand);
  spdlog::info("recording {} to {}", TopicTraits<cockpit::HandSample>::kName, options.path);

  const int64_t start_ns = monotonic_now_ns();
  int64_t last_sample_ns = start_ns;
  uint64_t other_hands = 0;
  cockpit::HandSample message;
  while (!should_stop(options, log.count(), start_ns, last_sample_ns, monotonic_now_ns())) {
    reader.wait_for_data(50'000'000);
    while (log.count() < options.count || options.count == 0) {
      if (!reader.take(message)) break;
      if (message.hand_id() != options.hand_id) {
        ++other_hands;
        continue;
      }
      hand::GloveSample sample = from_hand_sample(message);
      const hand::GloveSample as_received = sample;
      if (!validator.accept(sample)) continue;
      log.append(as_received);  // the log keeps what was sent; limits apply on replay
      last_sample_ns = monotonic_now_ns();
    }
  }
  const auto& c = validator.counts();
  if (log.count() == 0) {
    spdlog::error("no samples received; {} not written (rejected {})", options.path, c.rejected());
    return 1;  // the partial file goes with `log`
  }
  log.commit();
  spdlog::info("wrote {} samples to {} (rejected {}: {} non-finite, {} bad quaternion, {} stale; "
               "{} of other hands)",
               log.count(), options.path, c.rejected(), c.rejected_nonfinite,
               c.rejected_out_of_range, c.rejected_stale, other_hands);
  return 0;
}

}  // namespace vcockpit::glove
