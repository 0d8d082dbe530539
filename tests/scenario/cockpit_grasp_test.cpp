// The bundled grasping glove log on the default cockpit: the cup is grasped, lifted with the hand
// (following it within 1 mm while held), released, and falls back to rest on the console, with
// no chatter. The same run twice gives byte-identical outputs; bad inputs leave no outputs.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/grasp_event_text.hpp"
#include "physics_node/io/replay_driver.hpp"
#include "physics_node/io/offline_runner.hpp"
#include "tests/support/process.hpp"

namespace vcockpit::test {
namespace {

std::string source_dir() { return std::getenv("VCOCKPIT_SOURCE_DIR"); }
std::string scene_path() { return source_dir() + "/config/cockpit.yaml"; }
std::string grasp_log_path() {
  return source_dir() + "/config/glove_logs/reach_grasp_lift_release.csv";
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(CockpitGrasp, CupIsGraspedLiftedReleasedAndComesToRest) {
  physics::Scene scene = load_scene(scene_path());
  const int cup = scene.find_object("cup");
  ASSERT_GE(cup, 0);
  const auto log = hand::read_glove_log(grasp_log_path(), scene.hands[0]);
  const hand::HandModel hand = scene.hands[0];
  physics::World world(scene);
  const double rest_z = world.bodies()[cup].X_GO.translation().z();

  int grasps = 0, releases = 0;
  int64_t grasp_ns = -1, release_ns = -1;
  Eigen::Isometry3d X_HO = Eigen::Isometry3d::Identity();
  double max_follow_error_m = 0.0, max_lift_m = 0.0;
  const int64_t end_ns =
      log.samples.back().t_ns - log.samples.front().t_ns + 1'500'000'000;  // 1.5 s to settle
  auto step = [&] {
    world.step();
    for (const auto& e : world.step_events()) {
      EXPECT_EQ(e.object, cup) << "unexpected " << (e.grasp ? "grasp" : "release") << " of "
                               << world.scene().objects[e.object].name << ": "
                               << physics_io::grasp_event_text(e);
      if (e.grasp) {
        ++grasps;
        grasp_ns = e.t_ns;
        X_HO = world.X_GH().inverse() * world.bodies()[cup].X_GO;
      } else {
        ++releases;
        release_ns = e.t_ns;
      }
      std::printf("%.3f s %s %s: %s\n", e.t_ns * 1e-9, e.grasp ? "GRASP" : "RELEASE",
                  world.scene().objects[e.object].name.c_str(),
                  physics_io::grasp_event_text(e).c_str());
    }
    const auto& body = world.bodies()[cup];
    if (body.held_by != physics::kNotHeld) {
      const Eigen::Isometry3d expected = world.X_GH() * X_HO;
      max_follow_error_m =
          std::max(max_follow_error_m, (body.X_GO.translation() - expected.translation()).norm());
      max_lift_m = std::max(max_lift_m, body.X_GO.translation().z() - rest_z);
    }
  };
  physics_io::ReplayDriver driver(world, hand);
  for (const auto& sample : log.samples) driver.feed(sample, step);
  driver.step_until(end_ns, step);
  ASSERT_EQ(grasps, 1) << "exactly one grasp (no chatter)";
  ASSERT_EQ(releases, 1) << "exactly one release (no chatter)";
  EXPECT_LT(grasp_ns, release_ns);
  EXPECT_LT(max_follow_error_m, 1e-3) << "the held cup must follow the hand";
  EXPECT_GT(max_lift_m, 0.08) << "the cup was lifted about 10 cm";
  const auto& cup_state = world.bodies()[cup];
  EXPECT_EQ(cup_state.held_by, physics::kNotHeld);
  EXPECT_NEAR(cup_state.X_GO.translation().z(), rest_z, 3e-3) << "back on the console";
  EXPECT_GT(cup_state.X_GO.linear()(2, 2), 0.99) << "standing upright";
  EXPECT_LT(cup_state.v_G.norm(), 5e-3) << "at rest";
}

TEST(CockpitGrasp, SameRunTwiceGivesByteIdenticalOutputs) {
  std::string outputs[2];
  for (int run = 0; run < 2; ++run) {
    physics_io::OfflineOptions options;
    options.scene_path = scene_path();
    options.log_paths = {grasp_log_path()};
    options.out_dir = make_temp_dir("cockpit_grasp_run" + std::to_string(run));
    const auto summary = physics_io::run_offline(load_scene(options.scene_path), options);
    EXPECT_EQ(summary.grasps, 1);
    EXPECT_EQ(summary.releases, 1);
    outputs[run] = read_text(options.out_dir + "/trajectories.csv") + "\n--\n" +
                   read_text(options.out_dir + "/events.jsonl");
    EXPECT_TRUE(std::filesystem::exists(options.out_dir + "/summary.json"));
  }
  EXPECT_GT(outputs[0].size(), 10000u);
  EXPECT_TRUE(outputs[0] == outputs[1]) << "two runs of the same inputs differ";
}

TEST(CockpitGrasp, BadInputsAreClearErrorsAndLeaveNoOutput) {
  const std::string dir = make_temp_dir("cockpit_grasp_bad");
  const std::string bad_log = dir + "/bad.csv";
  std::ofstream(bad_log) << "t_s,x_m,y_m,z_m,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n0.001,0,0,0,1,0,0\n";
  physics_io::OfflineOptions options;
  options.scene_path = scene_path();
  options.log_paths = {bad_log};
  options.out_dir = dir + "/out";
  try {
    physics_io::run_offline(load_scene(options.scene_path), options);
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:3"), std::string::npos) << e.what();
  }
  options.log_paths = {grasp_log_path()};
  options.scene_path = dir + "/missing.yaml";
  try {
    physics_io::run_offline(load_scene(options.scene_path), options);
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("missing.yaml"), std::string::npos) << e.what();
  }
  // nothing half-written: either no directory or an empty one
  if (std::filesystem::exists(options.out_dir)) {
    EXPECT_TRUE(std::filesystem::is_empty(options.out_dir));
  }
}

}  // namespace
}  // namespace vcockpit::test
