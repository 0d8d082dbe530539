// Test publisher: waits for its subscriber, writes `--count` pattern HandSamples at `--rate-hz`
// with the given QoS profile, waits for acknowledgement, exits 0 (or 1 on any failure).

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <cmath>

#include "common/clock.hpp"
#include "dds/dds_participant.hpp"
#include "common/logging.hpp"
#include "common/signals.hpp"
#include "tests/support/hand_sample_pattern.hpp"

int main(int argc, char** argv) {
  using namespace vcockpit;
  CLI::App app("hand_sample_pub: test publisher of pattern HandSamples");
  DdsFlags dds_flags;
  add_dds_flags(app, dds_flags);
  int count = 1000;
  double rate_hz = 1000.0;
  std::string profile = "reliable";
  int nan_at = -1, stale_at = -1;
  bool all_valid = false;
  app.add_flag("--all-valid", all_valid, "clear the pattern's source-invalid flags");
  app.add_option("--nan-at", nan_at, "make sample N's wrist x NaN");
  app.add_option("--stale-at", stale_at, "give sample N the stamp of sample N - 5");
  app.add_option("--count", count)->check(CLI::PositiveNumber);
  app.add_option("--rate-hz", rate_hz)->check(CLI::PositiveNumber);
  app.add_option("--profile", profile);
  CLI11_PARSE(app, argc, argv);
  setup_logging("hand_sample_pub");
  install_shutdown_handlers();
  try {
    DdsParticipant participant(resolve_dds_options(dds_flags), "hand_sample_pub");
    auto writer = participant.make_writer<cockpit::HandSample>(profile);
    if (!writer.wait_for_matched(1, 10'000'000'000)) {
      spdlog::error("no subscriber matched within 10 s");
      return 1;
    }
    const auto period_ns = static_cast<int64_t>(1e9 / rate_hz);
    int64_t next_ns = monotonic_now_ns();
    for (int i = 0; i < count && !shutdown_requested(); ++i) {
      sleep_until_ns(next_ns);
      next_ns += period_ns;
      auto sample = test::hand_sample_pattern(static_cast<uint64_t>(i));
      if (all_valid) sample.valid(true);
      if (i == nan_at) sample.X_MT().position_m().x(std::nan(""));
      if (i == stale_at) sample.sample_time_ns(sample.sample_time_ns() - 5'000'000);
      sample.source_stamp_ns(monotonic_now_ns());
      if (!writer.write(sample)) {
        spdlog::error("write {} failed", i);
        return 1;
      }
    }
    if (!writer.wait_for_acknowledgments(10'000'000'000)) {
      spdlog::error("subscriber did not acknowledge within 10 s");
      return 1;
    }
    spdlog::info("published {} samples", count);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
