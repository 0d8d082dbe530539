// Two hands in the default cockpit (config/cockpit.yaml: a right hand and its mirror image on the
// left), through the offline runner with one glove log per hand:
// - the bundled handover (config/glove_logs/handover_right.csv + handover_left.csv, recordings of
//   config/gestures/handover_*.yaml): the right hand takes the cup and lifts it, the left hand
//   closes its grip round it and takes it (RELEASE "handed over" by the right and GRASP by the left
//   in the same step, each naming the other), then sets it down; the cup does not move when it
//   changes hands, and ends where it started, upright;
// - the logs are refused when the scene has no hand of their side, or two logs name one hand.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/offline_runner.hpp"
#include "tests/support/process.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::test {
namespace {

std::string log_path(const std::string& name) {
  return source_dir() + "/config/glove_logs/" + name + ".csv";
}

struct Row {
  double t_s;
  Eigen::Vector3d p;
  double qw;
  std::string held_by;
};

// The rows of one object in trajectories.csv.
std::vector<Row> trajectory_of(const std::string& dir, const std::string& object) {
  std::ifstream in(dir + "/trajectories.csv");
  std::vector<Row> rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::size_t start = 0;
    for (std::size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
      f.push_back(line.substr(start, comma - start));
    f.push_back(line.substr(start));
    if (f.size() < 16 || f[1] != object) continue;
    rows.push_back({std::stod(f[0]), {std::stod(f[2]), std::stod(f[3]), std::stod(f[4])},
                    std::stod(f[5]), f[15]});
  }
  return rows;
}

std::vector<nlohmann::json> events_of(const std::string& dir) {
  std::ifstream in(dir + "/events.jsonl");
  std::vector<nlohmann::json> events;
  for (std::string line; std::getline(in, line);) events.push_back(nlohmann::json::parse(line));
  return events;
}

std::string text_of(const nlohmann::json& e) {
  std::string t = e.at("event").get<std::string>() + " " + e.at("hand").get<std::string>() + " " +
                  e.at("object").get<std::string>();
  if (e.contains("with")) t += " with " + e.at("with").get<std::string>();
  const std::string reason = e.at("reason");
  if (reason.rfind("handed over", 0) == 0) t += " (handed over)";
  return t;
}

TEST(TwoHands, TheRightHandHandsTheCupToTheLeftWithoutAJump) {
  physics_io::OfflineOptions options;
  options.scene_path = source_dir() + "/config/cockpit.yaml";
  options.log_paths = {log_path("handover_right"), log_path("handover_left")};
  options.out_dir = make_temp_dir("two_hands_handover");
  const physics_io::RunSummary summary = physics_io::run_offline(load_scene(options.scene_path), options);

  const std::vector<nlohmann::json> events = events_of(options.out_dir);
  std::string got;
  for (const auto& e : events) got += text_of(e) + "\n";
  EXPECT_EQ(got,
            "grasp right cup\n"
            "release right cup with left (handed over)\n"
            "grasp left cup with right\n"
            "release left cup\n");
  ASSERT_EQ(events.size(), 4u);
  const double handover_s = events[1].at("t_s");
  EXPECT_EQ(events[2].at("t_s").get<double>(), handover_s) << "in the same step";

  // the cup through the handover: it stays in a hand (never free) and does not move by more
  // than 1 mm between rows in the 0.2 s around it (the hands hold it still there)
  const std::vector<Row> cup = trajectory_of(options.out_dir, "cup");
  ASSERT_GT(cup.size(), 1000u);
  double largest_m = 0.0;
  for (std::size_t i = 1; i < cup.size(); ++i) {
    if (std::abs(cup[i].t_s - handover_s) > 0.1) continue;
    largest_m = std::max(largest_m, (cup[i].p - cup[i - 1].p).norm());
    EXPECT_FALSE(cup[i].held_by.empty()) << "free at " << cup[i].t_s << " s";
  }
  EXPECT_LT(largest_m, 1e-3);
  std::printf("handover at %.3f s; largest row-to-row move of the cup within 0.1 s of it: %.3f mm\n",
              handover_s, largest_m * 1e3);
  // held by the right just before, by the left just after
  std::string before, after;
  for (const Row& r : cup) {
    if (r.t_s < handover_s) before = r.held_by;
    if (after.empty() && r.t_s > handover_s) after = r.held_by;
  }
  EXPECT_EQ(before, "right");
  EXPECT_EQ(after, "left");
  // set down where it stood, upright, free
  const Row& last = cup.back();
  EXPECT_LT((last.p - Eigen::Vector3d(0.45, -0.35, 0.75)).norm(), 5e-3);
  EXPECT_GT(last.qw, 0.999);
  EXPECT_TRUE(last.held_by.empty());

  // each hand's part in the summary
  ASSERT_EQ(summary.hands.size(), 2u);
  EXPECT_EQ(summary.hands[0].hand_id, 0);
  EXPECT_EQ(summary.hands[0].grasps, 1);
  EXPECT_EQ(summary.hands[1].hand_id, 1);
  EXPECT_EQ(summary.hands[1].grasps, 1);
  EXPECT_EQ(summary.hands[1].input.accepted, summary.hands[0].input.accepted);
}

TEST(TwoHands, ALogOfAHandTheSceneLacksOrTwoLogsOfOneHandAreRefused) {
  physics_io::OfflineOptions options;
  options.scene_path = source_dir() + "/config/cockpit.yaml";
  options.out_dir = make_temp_dir("two_hands_refused");
  physics::Scene one_hand = load_scene(options.scene_path);
  one_hand.hands.resize(1);  // the right hand only
  options.log_paths = {log_path("handover_left")};
  try {
    physics_io::run_offline(one_hand, options);
    FAIL() << "a left hand's log drove a scene without a left hand";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no such hand"), std::string::npos) << e.what();
  }
  options.log_paths = {log_path("handover_right"), log_path("reach_grasp_lift_release")};
  try {
    physics_io::run_offline(load_scene(options.scene_path), options);
    FAIL() << "two right hands' logs were taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("one log per hand"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vcockpit::test
