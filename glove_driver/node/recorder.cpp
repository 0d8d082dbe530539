#include "glove_driver/node/recorder.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "common/signals.hpp"
#include "glove_driver/node/sequence_gaps.hpp"
#include "hand/glove_log.hpp"
#include "hand/sample_validator.hpp"
#include "idl/topics/hand_sample_convert.hpp"

namespace vcockpit::glove {
namespace {

constexpr int64_t kPollNs = 5'000'000;  // well inside the readers' 4,096-sample histories at 1 kHz
constexpr int64_t kRematchNs = 100'000'000;

bool should_stop(const RecorderOptions& o, uint64_t written, int64_t start_ns, int64_t last_ns,
                 int64_t now_ns) {
  if (shutdown_requested()) return true;
  if (o.count > 0 && written >= o.count) return true;
  if (o.duration_s > 0 && now_ns - start_ns >= seconds_to_ns(o.duration_s)) return true;
  return o.idle_timeout_s > 0 && written > 0 && now_ns - last_ns >= seconds_to_ns(o.idle_timeout_s);
}

WriterId writer_of(const dds::SampleInfo& info) {
  WriterId id{};
  std::memcpy(id.data(), info.publication_handle.value, id.size());
  return id;
}

// Which writers the reliable reader has matched: their samples come through it (with repairs),
// and the best-effort reader's copies of them are not used.
class ReliableWriters {
 public:
  explicit ReliableWriters(dds::DataReader* reliable_reader) : reader_(reliable_reader) {}

  void saw(const WriterId& writer) { reliable_.insert(writer); }

  bool contains(const WriterId& writer, int64_t now_ns) {
    if (reliable_.count(writer) > 0) return true;
    if (reader_ == nullptr || now_ns - last_query_ns_ < kRematchNs) return false;
    last_query_ns_ = now_ns;  // a best-effort writer is asked about again only now and then
    std::vector<dds::InstanceHandle_t> handles;
    reader_->get_matched_publications(handles);
    for (const auto& h : handles) {
      WriterId id{};
      std::memcpy(id.data(), h.value, id.size());
      reliable_.insert(id);
    }
    return reliable_.count(writer) > 0;
  }

 private:
  dds::DataReader* reader_;
  std::set<WriterId> reliable_;
  int64_t last_query_ns_ = -kRematchNs;
};

struct Recording {
  Recording(hand::GloveLogWriter& log_in, hand::SampleValidator& validator_in,
            SequenceGaps& gaps_in, uint32_t hand_id_in)
      : log(log_in), validator(validator_in), gaps(gaps_in), hand_id(hand_id_in) {}

  hand::GloveLogWriter& log;
  hand::SampleValidator& validator;
  SequenceGaps& gaps;
  uint32_t hand_id;
  uint64_t other_hands = 0;
  std::set<WriterId> hand_writers;  // writers that sent this hand (whose gaps are reported)
  int64_t last_sample_ns = 0;

  void take(const cockpit::HandSample& message, const dds::SampleInfo& info) {
    const WriterId writer = writer_of(info);
    if (!gaps.add(writer, static_cast<uint64_t>(info.sample_identity.sequence_number().to64long()))) {
      return;  // the other reader's copy was written already
    }
    if (message.hand_id() != hand_id) {
      ++other_hands;
      return;
    }
    if (hand_writers.insert(writer).second) {
      writers_in_order.push_back(writer);
      // when the recording really began: a writer found late has sent samples meanwhile
      spdlog::info("receiving from writer {}: its first sample here is its sample {}",
                   writers_in_order.size(), info.sample_identity.sequence_number().to64long());
    }
    hand::GloveSample sample = from_hand_sample(message);
    const hand::GloveSample as_received = sample;
    if (!validator.accept(sample)) return;
    log.append(as_received);  // the log keeps what was sent; limits apply on replay
    last_sample_ns = monotonic_now_ns();
  }

  // What this hand's writers sent and the log lacks, in total and at the start (before the
  // recorder matched them), and per writer in the order they were first seen.
  struct Lost {
    uint64_t total = 0;
    uint64_t at_start = 0;
    std::string per_writer;  // "writer 1: first received sample 455, newest 5001, 454 sent ..."
  };
  Lost lost() const {
    Lost l;
    int n = 0;
    for (const WriterId& w : writers_in_order) {
      if (hand_writers.count(w) == 0) continue;
      const SequenceGaps::Track t = gaps.of(w);
      l.total += t.missing();
      l.at_start += t.at_start();
      ++n;
      l.per_writer += (n > 1 ? "; " : "") + std::string("writer ") + std::to_string(n) +
                      ": first received sample " + std::to_string(t.first) + ", newest " +
                      std::to_string(t.newest) + ", " + std::to_string(t.at_start()) +
                      " sent before, " + std::to_string(t.in_gaps) + " in gaps";
    }
    return l;
  }
  std::vector<WriterId> writers_in_order;
};

}  // namespace

int run_recorder(DdsParticipant& participant, const hand::HandModel& hand,
                 const RecorderOptions& options) {
  // lockstep: one reliable keep-all reader; else a reliable and a best-effort one (see the header)
  auto reliable_reader =
      participant.make_reader<cockpit::HandSample>(options.lockstep ? "reliable" : "record");
  std::optional<Reader<cockpit::HandSample>> any_reader;
  if (!options.lockstep) any_reader = participant.make_reader<cockpit::HandSample>("record_any");
  ReliableWriters reliable_writers(reliable_reader.raw());

  hand::GloveLogWriter log(
      options.path, hand.left,
      {"source: recorded from " + std::string(TopicTraits<cockpit::HandSample>::kName)});
  hand::SampleValidator validator(hand);
  SequenceGaps gaps;
  spdlog::info("recording {} to {}", TopicTraits<cockpit::HandSample>::kName, options.path);

  const int64_t start_ns = monotonic_now_ns();
  Recording rec(log, validator, gaps, options.hand_id);
  rec.last_sample_ns = start_ns;
  const auto room = [&] { return options.count == 0 || log.count() < options.count; };
  cockpit::HandSample message;
  dds::SampleInfo info;
  while (!should_stop(options, log.count(), start_ns, rec.last_sample_ns, monotonic_now_ns())) {
    reliable_reader.wait_for_data(kPollNs);
    while (room() && reliable_reader.take(message, &info)) {
      reliable_writers.saw(writer_of(info));
      rec.take(message, info);
    }
    if (!any_reader) continue;
    const int64_t now_ns = monotonic_now_ns();
    while (room() && any_reader->take(message, &info)) {
      if (!reliable_writers.contains(writer_of(info), now_ns)) rec.take(message, info);
    }
  }
  const auto& c = validator.counts();
  const Recording::Lost lost = rec.lost();
  if (log.count() == 0) {
    spdlog::error("no samples received; {} not written (rejected {})", options.path, c.rejected());
    return 1;  // the partial file goes with `log`
  }
  // writers number their samples from 1: what came before a writer's first received sample was
  // sent before this recorder matched it, and is missing from the log as much as a gap is
  const std::string lost_text =
      std::to_string(lost.total) + " samples (" + std::to_string(lost.at_start) +
      " sent before the recorder matched their writer, " +
      std::to_string(lost.total - lost.at_start) + " in gaps of the sequence numbers; " +
      std::to_string(rec.hand_writers.size()) + " writer(s)" +
      (lost.per_writer.empty() ? "" : ": " + lost.per_writer) + ")";
  log.append_comment("lost: " + lost_text);
  log.commit();
  spdlog::info("wrote {} samples to {}; lost {}; rejected {}: {} non-finite, {} bad quaternion, "
               "{} stale; {} of other hands",
               log.count(), options.path, lost_text, c.rejected(), c.rejected_nonfinite,
               c.rejected_out_of_range, c.rejected_stale, rec.other_hands);
  if (lost.total > 0) {
    spdlog::warn("{}: {} samples sent were never received ({} of them before the recorder "
                 "matched their writer)",
                 options.path, lost.total, lost.at_start);
  }
  return 0;
}

}  // namespace vcockpit::glove
