// Test subscriber: takes HandSamples until `--count` arrived or `--timeout-s` passed, and writes
// each one's CDR bytes (source_stamp_ns zeroed) to `--out` as length-prefixed records.
// Exits 0 when the count arrived, 1 otherwise.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <cstdio>

#include "common/clock.hpp"
#include "dds/dds_participant.hpp"
#include "common/logging.hpp"
#include "common/signals.hpp"
#include "tests/support/hand_sample_pattern.hpp"

namespace {

// The publisher's final node_status (its STOPPING report) as key=value lines.
void write_last_status(vcockpit::Reader<cockpit::NodeStatus>& reader, const std::string& path) {
  cockpit::NodeStatus status, last;
  bool have = false;
  const int64_t deadline_ns = vcockpit::monotonic_now_ns() + 5'000'000'000;
  while (vcockpit::monotonic_now_ns() < deadline_ns && !(have && last.state() == cockpit::STOPPING)) {
    reader.wait_for_data(100'000'000);
    while (reader.take(status)) {
      last = status;
      have = true;
    }
  }
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) return;
  std::fprintf(f, "node=%s\nstate=%d\npublished=%llu\nrejected=%llu\nclamped=%llu\n",
               last.node_name().c_str(), static_cast<int>(last.state()),
               static_cast<unsigned long long>(last.published()),
               static_cast<unsigned long long>(last.rejected()),
               static_cast<unsigned long long>(last.clamped()));
  std::fclose(f);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace vcockpit;
  CLI::App app("hand_sample_sub: test subscriber that records HandSamples");
  DdsFlags dds_flags;
  add_dds_flags(app, dds_flags);
  int count = 1000;
  double timeout_s = 30.0;
  std::string profile = "reliable";
  std::string out_path;
  std::string status_out;
  app.add_option("--count", count)->check(CLI::PositiveNumber);
  app.add_option("--timeout-s", timeout_s)->check(CLI::PositiveNumber);
  app.add_option("--profile", profile);
  app.add_option("--out", out_path)->required();
  app.add_option("--status-out", status_out,
                 "also take cockpit/node_status and write the last one's counters here");
  CLI11_PARSE(app, argc, argv);
  setup_logging("hand_sample_sub");
  install_shutdown_handlers();
  try {
    DdsParticipant participant(resolve_dds_options(dds_flags), "hand_sample_sub");
    auto reader = participant.make_reader<cockpit::HandSample>(profile);
    auto status_reader = participant.make_reader<cockpit::NodeStatus>("state");
    std::FILE* out = std::fopen(out_path.c_str(), "wb");
    if (!out) {
      spdlog::error("{}: cannot open for writing", out_path);
      return 1;
    }
    const int64_t deadline_ns = monotonic_now_ns() + static_cast<int64_t>(timeout_s * 1e9);
    int received = 0;
    cockpit::HandSample sample;
    while (received < count && !shutdown_requested() && monotonic_now_ns() < deadline_ns) {
      reader.wait_for_data(100'000'000);
      // no more than --count: a burst read at once may hold more than the count still needs
      while (received < count && reader.take(sample)) {
        sample.source_stamp_ns(0);
        const auto bytes = test::serialize(sample);
        const auto size = static_cast<uint32_t>(bytes.size());
        std::fwrite(&size, sizeof size, 1, out);
        std::fwrite(bytes.data(), 1, bytes.size(), out);
        ++received;
      }
    }
    std::fclose(out);
    if (!status_out.empty()) write_last_status(status_reader, status_out);
    spdlog::info("received {} of {} samples", received, count);
    return received == count ? 0 : 1;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
