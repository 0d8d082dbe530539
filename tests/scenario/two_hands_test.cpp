// Two hands in the default cockpit (config/cockpit.yaml: a right hand and its mirror image on the
// left), through the offline runner with one glove log per hand:
// - the bundled handover (config/glove_logs/handover_right.csv + handover_left.csv, recordings of
//   config/gestures/handover_*.yaml): the right hand takes the cup and lifts it, the left hand
//   closes its grip round it and takes it (RELEASE "handed over" by the right and GRASP by the left
//   in the same step, each naming the other), then sets it down; the cup does not move when it
//   changes hands, and ends where it started, upright;
// - the bundled two-handed lift (two_hand_lift_right.csv + two_hand_lift_left.csv): both hands'
//   power grips on the 2.5 kg bar across the glareshield take it together (a GRASP per hand, in
//   one step), it rises 10 cm with them and comes back down; the right hand's log alone does not
//   lift it: its grip meets the gesture rule and eq. 30 fails ("force residual too large");
// - the logs are refused when the scene has no hand of their side, or two logs name one hand.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/offline_runner.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "physics_node/physics/grasp.hpp"
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

TEST(TwoHands, BothHandsLiftTheHeavyBarTogether) {
  physics_io::OfflineOptions options;
  options.scene_path = source_dir() + "/config/cockpit.yaml";
  options.log_paths = {log_path("two_hand_lift_right"), log_path("two_hand_lift_left")};
  options.out_dir = make_temp_dir("two_hands_lift");
  physics_io::run_offline(load_scene(options.scene_path), options);
  const std::vector<nlohmann::json> events = events_of(options.out_dir);
  ASSERT_GE(events.size(), 2u);
  EXPECT_EQ(text_of(events[0]), "grasp right heavy_bar with left");
  EXPECT_EQ(text_of(events[1]), "grasp left heavy_bar with right");
  EXPECT_EQ(events[0].at("t_s"), events[1].at("t_s"));
  int grasps = 0;
  for (const auto& e : events) {
    EXPECT_EQ(e.at("object"), "heavy_bar");
    grasps += e.at("event") == "grasp" ? 1 : 0;
  }
  EXPECT_EQ(grasps, 2) << "one GRASP per hand";
  // it rises with the hands, held by both, and ends back on the glareshield
  const std::vector<Row> bar = trajectory_of(options.out_dir, "heavy_bar");
  ASSERT_FALSE(bar.empty());
  const double rest_z = bar.front().p.z();
  double top_z = rest_z;
  std::string held_at_top;
  for (const Row& r : bar) {
    if (r.p.z() > top_z) {
      top_z = r.p.z();
      held_at_top = r.held_by;
    }
  }
  std::printf("the bar rose %.1f mm with both hands\n", (top_z - rest_z) * 1e3);
  EXPECT_GT(top_z - rest_z, 0.08);
  EXPECT_EQ(held_at_top, "both");
  EXPECT_LT(std::abs(bar.back().p.z() - rest_z), 3e-3);
  EXPECT_TRUE(bar.back().held_by.empty());
}

// The right hand's half of the lift alone: its grip closes round the bar exactly as with both,
// meets the gesture rule, and cannot carry the bar's weight: no GRASP, the bar stays down, and
// the test's verdict during the lift is eq. 30's.
TEST(TwoHands, OneHandAloneDoesNotLiftTheHeavyBar) {
  const physics::Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  const int bar = scene.find_object("heavy_bar");
  ASSERT_GE(bar, 0);
  physics::World world(scene);
  const hand::GloveLog log = hand::read_glove_log(log_path("two_hand_lift_right"), scene.hands[0]);
  physics_io::ReplayDriver driver(world, world.scene().hands[0], {}, 0);
  const int objects = static_cast<int>(scene.objects.size());
  int gesture_steps = 0, force_residual_steps = 0, grasps = 0;
  double top_z = world.bodies()[static_cast<std::size_t>(bar)].X_GO.translation().z();
  const double rest_z = top_z;
  std::vector<physics::HandContact> on_bar;
  for (const hand::GloveSample& sample : log.samples) {
    driver.feed(sample, [&] {
      world.step();
      for (const auto& e : world.step_events()) grasps += e.grasp ? 1 : 0;
      top_z = std::max(top_z, world.bodies()[static_cast<std::size_t>(bar)].X_GO.translation().z());
      // the right hand's grasp test on the bar, as the world makes it
      on_bar.clear();
      for (const physics::AppliedContact& a : world.contacts()) {
        if (a.contact.body_a != bar || a.contact.body_b < objects || a.contact.body_b >= objects + physics::kLinkCount)
          continue;
        on_bar.push_back({static_cast<physics::Link>(a.contact.body_b - objects), a.contact.p_G,
                          -a.contact.n_G, -a.F_on_b_G});
      }
      if (on_bar.empty()) return;
      const physics::ObjectSpec& o = scene.objects[static_cast<std::size_t>(bar)];
      const physics::GraspCheck check = physics::evaluate_grasp(
          on_bar.data(), on_bar.size(), world.bodies()[static_cast<std::size_t>(bar)].X_GO.translation(),
          o.mass_kg, scene.gravity_mps2, scene.grasp, false);
      if (check.gesture_holds()) ++gesture_steps;
      if (check.verdict == physics::GraspReason::kForceResidual) ++force_residual_steps;
    });
  }
  std::printf("one hand: grip meets the gesture rule for %d steps, eq. 30 fails in %d; the bar rose "
              "%.2f mm\n", gesture_steps, force_residual_steps, (top_z - rest_z) * 1e3);
  EXPECT_EQ(grasps, 0);
  EXPECT_GT(gesture_steps, 500) << "the grip closed round the bar (for a second or more)";
  EXPECT_EQ(force_residual_steps, gesture_steps) << "and every time, eq. 30 is what fails";
  EXPECT_LT(top_z - rest_z, 2e-3);
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
