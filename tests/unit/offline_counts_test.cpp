// physics_node --offline counts a crafted log's faults honestly (physics_io/offline_runner.hpp):
// k clamped values, a missing column, a gap bridged, gaps not bridged, the glove lost once; they
// land in summary.json's "input" exactly, and the hand's peak speed stays the recorded one.

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <nlohmann/json.hpp>

#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/offline_runner.hpp"
#include "tests/support/crafted_glove_log.hpp"
#include "tests/support/process.hpp"

namespace vcockpit::physics_io {
namespace {

std::string source_dir() {
  return std::getenv("VCOCKPIT_SOURCE_DIR");
}

// Writes the crafted log into a fresh directory, runs the offline runner on the default cockpit
// and returns its summary.json.
nlohmann::json run_crafted(const test::CraftedGloveLog& craft, const std::string& name,
                           RunSummary* summary = nullptr) {
  const std::string dir = test::make_temp_dir(name);
  const std::string log = dir + "/crafted.csv";
  std::ofstream(log) << craft.text();
  OfflineOptions options;
  options.scene_path = source_dir() + "/config/cockpit.yaml";
  options.log_paths = {log};
  options.out_dir = dir + "/out";
  const RunSummary run = run_offline(load_scene(options.scene_path), options);
  if (summary) *summary = run;
  std::ifstream in(options.out_dir + "/summary.json");
  return nlohmann::json::parse(in);
}

TEST(OfflineCounts, ACraftedLogsClampsMissingColumnGapsAndGloveLostLandInTheSummary) {
  test::CraftedGloveLog craft;
  craft.run(0, 100, 3);   // 3 values clamped
  craft.run(200, 300);    // after a 0.1 s gap: bridged
  craft.run(600, 700);    // after 0.3 s: not bridged (max gap 0.25 s)
  craft.run(1900, 2000);  // after 1.2 s: not bridged, the glove lost from 1.7 s
  RunSummary summary;
  const auto j = run_crafted(craft, "offline_counts", &summary);
  EXPECT_EQ(summary.steps, 2000u);

  const auto& input = j.at("input");
  EXPECT_EQ(input.at("accepted"), craft.rows());
  EXPECT_EQ(input.at("rejected"), 0);
  EXPECT_EQ(input.at("clamped"), 3);
  EXPECT_EQ(craft.clamped(), 3);
  EXPECT_EQ(input.at("missing_columns"), 1);
  EXPECT_EQ(input.at("intervals"), craft.rows() - 1);
  EXPECT_EQ(input.at("intervals_interpolated"), 40);
  EXPECT_EQ(input.at("gaps_bridged"), 1);
  EXPECT_EQ(input.at("gaps_not_bridged"), 2);
  EXPECT_EQ(input.at("intervals_late"), 0);
  EXPECT_NEAR(input.at("longest_interval_s").get<double>(), 1.2, 1e-12);
  EXPECT_EQ(input.at("glove_lost"), 1);
  EXPECT_EQ(input.at("max_gap_s"), 0.25);
  EXPECT_EQ(input.at("glove_timeout_s"), 1.0);
  // the jumps after the two gaps not bridged are the only fast steps: 0.3 s and 1.2 s of
  // motion (6 and 24 cm) arrive in one step, and the drawn (proxy) hand catches up with them at
  // its maximum speed, not at 240 m/s
  EXPECT_NEAR(j.at("hand_peak_wrist_speed_mps").get<double>(), physics::ProxyParams{}.max_speed_mps,
              1e-6);
}

TEST(OfflineCounts, BridgingEveryGapLeavesTheRecordedSpeed) {
  test::CraftedGloveLog craft;
  craft.run(0, 100);
  craft.run(200, 300);
  const auto j = run_crafted(craft, "offline_counts_bridged");
  EXPECT_NEAR(j.at("hand_peak_wrist_speed_mps").get<double>(), 0.2, 1e-9);
  EXPECT_EQ(j.at("input").at("gaps_bridged"), 1);
  EXPECT_EQ(j.at("input").at("glove_lost"), 0);
}

TEST(OfflineCounts, ADurationPastTheLogHoldsTheLastSampleAndLosesTheGloveAfterTheTimeout) {
  test::CraftedGloveLog craft;
  craft.run(0, 100);
  const std::string dir = test::make_temp_dir("offline_counts_duration");
  const std::string log = dir + "/crafted.csv";
  std::ofstream(log) << craft.text();
  OfflineOptions options;
  options.scene_path = source_dir() + "/config/cockpit.yaml";
  options.log_paths = {log};
  options.out_dir = dir + "/out";
  options.duration_s = 1.1;  // the glove is lost at 1.1 s, 1 s after the last sample
  run_offline(load_scene(options.scene_path), options);
  std::ifstream in(options.out_dir + "/summary.json");
  EXPECT_EQ(nlohmann::json::parse(in).at("input").at("glove_lost"), 0) << "1 s: not yet";
  options.duration_s = 1.101;
  run_offline(load_scene(options.scene_path), options);
  std::ifstream again(options.out_dir + "/summary.json");
  EXPECT_EQ(nlohmann::json::parse(again).at("input").at("glove_lost"), 1);
}

TEST(OfflineCounts, WithoutADurationTheRunEndsWhereALockstepReplayStops) {
  // stamps off the 1 ms grid: the last step that ends by the last sample (61.2 ms) is the 61st
  const std::string dir = test::make_temp_dir("offline_counts_end");
  const std::string log = dir + "/off_grid.csv";
  std::ofstream(log) << "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0,0,3,1,0,0,0\n"
                        "0.0305,0.01,0,3,1,0,0,0\n0.0612,0.02,0,3,1,0,0,0\n";
  OfflineOptions options;
  options.scene_path = source_dir() + "/config/cockpit.yaml";
  options.log_paths = {log};
  options.out_dir = dir + "/out";
  EXPECT_EQ(run_offline(load_scene(options.scene_path), options).steps, 61u);
}

}  // namespace
}  // namespace vcockpit::physics_io
