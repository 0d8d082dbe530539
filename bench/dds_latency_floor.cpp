// dds_latency_floor: the bare Fast DDS floor under the glove -> physics latency. One binary, two
// roles, and nothing between them but Fast DDS with the rig's own settings: the project's
// DdsParticipant (same QoS file, same participant profile, default "loopback"), the same topic and
// type (cockpit/hand_sample, cockpit::HandSample) and the same "stream" endpoint profile that
// glove_driver -> physics_node use.
//
//   --role writer  waits for a reader, then publishes at --rate-hz for --duration S or --count N,
//                  stamping source_stamp_ns with the monotonic clock just before each write.
//   --role reader  blocks in wait_for_data, takes every sample at once and records
//                    dds_transit    SampleInfo reception - source timestamp (Fast DDS's stamps)
//                    take_latency   monotonic now at take - source_stamp_ns
//                  the figures physics_node --stats-out reports as dds_transit_us and
//                  age_at_step_us; it stops when the writer is gone, after --count/--duration,
//                  after --idle-timeout without data, or on SIGINT, prints them and writes --out.
//
// Run it on a domain of its own (--domain or VCOCKPIT_DOMAIN) so no rig node joins in.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "common/atomic_file.hpp"
#include "common/cli_finite.hpp"
#include "common/clock.hpp"
#include "dds/dds_participant.hpp"
#include "common/json_file.hpp"
#include "common/latency_histogram.hpp"
#include "common/logging.hpp"
#include "common/signals.hpp"

namespace vcockpit::bench {
namespace {

// A writer's match means it saw the reader; the reader may see the writer a little later, and a
// best-effort reader drops data from writers it has not matched yet. Discovery on loopback takes
// 10-15 ms: this margin keeps the first samples from being lost to it.
constexpr int64_t kSettleAfterMatch_ns = 200'000'000;
// After the last write: let the last samples arrive before the writer's deletion unmatches it.
constexpr int64_t kLingerAfterLast_ns = 200'000'000;
// The reader's wait granularity, for its stop conditions (not a latency: data wakes it at once).
constexpr int64_t kWaitSlice_ns = 50'000'000;

struct Flags {
  std::string role;
  std::optional<double> rate_hz;
  std::optional<double> duration_s;
  std::optional<uint64_t> count;
  double match_timeout_s = 30.0;
  std::optional<double> idle_timeout_s;
  std::optional<std::string> out_path;
  DdsFlags dds;
  std::string log_level = "info";
};

// A plausible sample: an open right hand at rest, valid. Only seq and the stamps change.
cockpit::HandSample make_sample(uint64_t seq, int64_t period_ns) {
  cockpit::HandSample s;
  s.hand_id(0);
  s.seq(seq);
  s.sample_time_ns(static_cast<int64_t>(seq) * period_ns);
  s.X_MT().position_m().x(0.2);
  s.X_MT().position_m().y(-0.45);
  s.X_MT().position_m().z(0.95);
  s.X_MT().orientation().w(1.0);
  s.valid(true);
  return s;
}

int run_writer(const Flags& f) {
  const double rate_hz = f.rate_hz.value_or(1000.0);
  const auto period_ns = static_cast<int64_t>(1e9 / rate_hz + 0.5);
  DdsParticipant participant(resolve_dds_options(f.dds), "dds_latency_floor_writer");
  auto writer = participant.make_writer<cockpit::HandSample>("stream");
  spdlog::info("writer on domain {}: waiting up to {:.0f} s for a reader", participant.domain_id(),
               f.match_timeout_s);
  if (!writer.wait_for_matched(1, seconds_to_ns(f.match_timeout_s))) {
    spdlog::error("no reader matched within {:.1f} s", f.match_timeout_s);
    return 1;
  }
  sleep_until_ns(monotonic_now_ns() + kSettleAfterMatch_ns);

  // --count N, else --duration S (default 5 s) at the rate
  const uint64_t count =
      f.count ? *f.count
              : static_cast<uint64_t>(std::max(1.0, f.duration_s.value_or(5.0) * rate_hz + 0.5));
  cockpit::HandSample sample = make_sample(0, period_ns);
  uint64_t written = 0;
  uint64_t failures = 0;
  const int64_t start_ns = monotonic_now_ns();
  int64_t next_ns = start_ns;
  for (uint64_t seq = 0; seq < count && !shutdown_requested(); ++seq) {
    sleep_until_ns(next_ns);
    next_ns += period_ns;
    sample.seq(seq);
    sample.sample_time_ns(static_cast<int64_t>(seq) * period_ns);
    sample.source_stamp_ns(monotonic_now_ns());
    if (writer.write(sample)) {
      ++written;
    } else {
      ++failures;
    }
  }
  const double elapsed_s = ns_to_seconds(monotonic_now_ns() - start_ns);
  sleep_until_ns(monotonic_now_ns() + kLingerAfterLast_ns);
  spdlog::info("wrote {} samples in {:.3f} s ({:.1f} Hz), {} write failures", written, elapsed_s,
               elapsed_s > 0 ? static_cast<double>(written) / elapsed_s : 0.0, failures);
  return failures == 0 ? 0 : 1;
}

enum class StopReason { kSignal, kCount, kDuration, kWriterGone, kIdle };

const char* describe(StopReason why) {
  switch (why) {
    case StopReason::kSignal: return "interrupted";
    case StopReason::kCount: return "count reached";
    case StopReason::kDuration: return "duration reached";
    case StopReason::kWriterGone: return "the writer is gone";
    case StopReason::kIdle: return "idle timeout";
  }
  return "?";
}

struct ReaderResult {
  uint64_t samples = 0;
  uint64_t expected = 0;  // the writer numbers from 0: highest seq + 1, or --count if it is more
  double duration_s = 0;  // first to last sample
  LatencyHistogram dds_transit;
  LatencyHistogram take_latency;
  uint64_t lost() const { return expected > samples ? expected - samples : 0; }
};

void write_reader_json(AtomicFile& file, const ReaderResult& r) {
  nlohmann::ordered_json j;
  j["samples"] = r.samples;
  j["lost"] = r.lost();
  j["duration_s"] = r.duration_s;
  j["dds_transit_us"] = latency_json_us(r.dds_transit);
  j["take_latency_us"] = latency_json_us(r.take_latency);
  write_json(file, j);
  file.commit();  // throws FileError naming the path
}

int run_reader(const Flags& f) {
  // opened now so a path that cannot be written fails before the run, not after it
  std::optional<AtomicFile> out;
  if (f.out_path) out.emplace(*f.out_path);
  DdsParticipant participant(resolve_dds_options(f.dds), "dds_latency_floor_reader");
  auto reader = participant.make_reader<cockpit::HandSample>("stream");
  spdlog::info("reader on domain {}: waiting up to {:.0f} s for a writer", participant.domain_id(),
               f.match_timeout_s);
  if (!reader.wait_for_matched(1, seconds_to_ns(f.match_timeout_s))) {
    spdlog::error("no writer matched within {:.1f} s", f.match_timeout_s);
    return 1;
  }
  const int64_t idle_limit_ns = seconds_to_ns(f.idle_timeout_s.value_or(2.0));
  const int64_t duration_ns = f.duration_s ? seconds_to_ns(*f.duration_s) : 0;
  ReaderResult r;
  cockpit::HandSample message;
  dds::SampleInfo info;
  int64_t first_ns = 0;
  int64_t last_ns = monotonic_now_ns();  // idle time counts from the match until data comes
  uint64_t highest_seq = 0;
  StopReason why = StopReason::kSignal;
  while (!shutdown_requested()) {
    reader.wait_for_data(kWaitSlice_ns);
    while (reader.take(message, &info)) {
      const int64_t take_ns = monotonic_now_ns();
      r.take_latency.record_ns(take_ns - message.source_stamp_ns());
      r.dds_transit.record_ns(info.reception_timestamp.to_ns() - info.source_timestamp.to_ns());
      if (r.samples == 0) first_ns = take_ns;
      highest_seq = std::max(highest_seq, message.seq());
      ++r.samples;
      last_ns = take_ns;
    }
    const int64_t now_ns = monotonic_now_ns();
    if (f.count && r.samples >= *f.count) {
      why = StopReason::kCount;
      break;
    }
    if (duration_ns > 0 && r.samples > 0 && now_ns - first_ns >= duration_ns) {
      why = StopReason::kDuration;
      break;
    }
    if (reader.matched_count() == 0) {
      why = StopReason::kWriterGone;
      break;
    }
    if (now_ns - last_ns >= idle_limit_ns) {
      why = StopReason::kIdle;
      break;
    }
  }
  r.expected = r.samples > 0 ? highest_seq + 1 : 0;
  // the writer left or went quiet before the count: the rest of it was lost
  if (f.count && (why == StopReason::kWriterGone || why == StopReason::kIdle)) {
    r.expected = std::max(r.expected, *f.count);
  }
  r.duration_s = r.samples > 0 ? ns_to_seconds(last_ns - first_ns) : 0.0;
  spdlog::info("stopped ({}): {} samples, {} lost over {:.3f} s", describe(why), r.samples, r.lost(),
               r.duration_s);
  spdlog::info("DDS transit {}", latency_text_us(r.dds_transit));
  spdlog::info("take latency {}", latency_text_us(r.take_latency));
  if (out) {
    write_reader_json(*out, r);
    spdlog::info("written to {}", out->path());
  }
  if (r.samples == 0) {
    spdlog::error("no samples received");
    return 1;
  }
  return 0;
}

void add_flags(CLI::App& app, Flags& f) {
  app.add_option("--role", f.role, "writer (publishes) or reader (measures)")
      ->required()
      ->check(CLI::IsMember({"writer", "reader"}));
  app.add_option("--rate-hz", f.rate_hz, "writer: samples per second (default 1000)")
      ->check(CLI::Range(1.0, 100000.0) & kFinite);
  app.add_option("--duration", f.duration_s,
                 "writer: publish for this many seconds (default 5 unless --count); reader: stop "
                 "this many seconds after the first sample")
      ->check(CLI::Range(0.001, 1e6) & kFinite);
  app.add_option("--count", f.count, "writer: publish this many samples; reader: stop after them")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1'000'000'000}));
  app.add_option("--match-timeout", f.match_timeout_s,
                 "seconds to wait for the other role to match before failing")
      ->check(CLI::Range(0.001, 3600.0) & kFinite)
      ->capture_default_str();
  app.add_option("--idle-timeout", f.idle_timeout_s,
                 "reader: stop after this many seconds without a sample (default 2)")
      ->check(CLI::Range(0.001, 3600.0) & kFinite);
  app.add_option("--out", f.out_path, "reader: write the figures to this JSON file");
  add_dds_flags(app, f.dds);
  app.add_option("--log-level", f.log_level, "trace, debug, info, warn, error")
      ->capture_default_str();
}

// Options of the other role are errors, not silently ignored.
void check_flags(const Flags& f) {
  const bool writer = f.role == "writer";
  if (writer) {
    if (f.duration_s && f.count) throw CLI::ValidationError("writer: give --duration or --count, not both");
    if (f.out_path) throw CLI::ValidationError("--out belongs to --role reader");
    if (f.idle_timeout_s) throw CLI::ValidationError("--idle-timeout belongs to --role reader");
  } else {
    if (f.rate_hz) throw CLI::ValidationError("--rate-hz belongs to --role writer");
    if (f.out_path && f.out_path->empty()) throw CLI::ValidationError("--out: empty file name");
  }
}

}  // namespace
}  // namespace vcockpit::bench

int main(int argc, char** argv) {
  using namespace vcockpit;
  CLI::App app("dds_latency_floor: bare Fast DDS one-way latency of cockpit::HandSample with the "
               "rig's QoS (participant profile and the \"stream\" endpoint profile); run a "
               "--role reader and a --role writer on the same domain");
  bench::Flags flags;
  bench::add_flags(app, flags);
  CLI11_PARSE(app, argc, argv);
  try {
    bench::check_flags(flags);
    setup_logging("dds_latency_floor", flags.log_level);
    install_shutdown_handlers();
    return flags.role == "writer" ? bench::run_writer(flags) : bench::run_reader(flags);
  } catch (const CLI::Error& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
