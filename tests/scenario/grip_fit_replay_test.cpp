// grip_fit's scenes replayed: the Leap Motion "grab" (tests/data/real/README.md) with the
// project's hand, a 3 cm bar, a 4 cm cylinder and a 5 cm ball. grip_fit's library path chooses
// each scene (fit/grip_choice.hpp: moments across the closing and the first closed stretch, each
// candidate replayed in memory until one holds), writes it as the tool does, and the written file
// is replayed the way the real-recording tests replay theirs (real_grip::replay_real_grip). What
// a user expects of it:
//   - the object is grasped (GRASP), and its first RELEASE, for the hand letting go (hand opened,
//     thumb left, fingers left), comes after the hand has started to open (the first closed
//     stretch's opening, steady_moment.hpp rule 5) and before the log ends;
//   - until 0.3 s after that release the object never more than 1 cm below its pedestal's top;
//   - a free object (before the grasp, after the release) never faster than 0.5 m/s horizontally;
//   - no link more than 1 mm inside the object or any static object, at any step.
// The file's replay must also be the one grip_fit judged (the same events and figures): what is
// written is what was verified. The figures are printed for the record.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "hand/glove_log.hpp"
#include "hand/config/calibrated_hand_yaml.hpp"
#include "hand/config/hand_yaml.hpp"
#include "hand/tracking/joints_replay.hpp"
#include "hand/tracking/leapjs_import.hpp"
#include "physics_node/config/grip_scene_yaml.hpp"
#include "physics_node/fit/grip_choice.hpp"
#include "tests/scenario/real_grip/real_grip_run.hpp"
#include "tests/support/process.hpp"

namespace vcockpit {
namespace {

std::string source_dir() {
  return std::getenv("VCOCKPIT_SOURCE_DIR");
}

class GripFitReplay : public ::testing::Test {
 protected:
  // the log and its hand: the converted Leap log on the project's hand, unless a test sets them
  std::string log_path_ = source_dir() + "/tests/data/real/leap_grab.csv";
  std::string hand_path_ = source_dir() + "/config/hand.yaml";
  hand::HandModel model_;
  hand::GloveLog log_;

  void fit_and_replay(const char* name, const char* stem, const physics::Shape& shape) {
    model_ = load_hand_model(hand_path_);
    log_ = hand::read_glove_log(log_path_, model_);
    ASSERT_FALSE(model_.left);  // the Leap log is a right hand, as config/hand.yaml
    GripSceneSpec base;
    base.object_name = "object";
    base.shape = shape;
    base.mass_kg = 0.06;
    base.hand_path = hand_path_;
    base.cockpit_path = source_dir() + "/config/cockpit.yaml";
    const std::string path = test::make_temp_dir("grip_fit_replay") + "/" + stem + ".yaml";

    const fit::GripChoiceOptions options;
    const auto started = std::chrono::steady_clock::now();
    const fit::GripChoice choice = fit::choose_grip(
        model_, log_.samples, shape, options,
        [&](const fit::GripTrial& t) { return grip_scene(with_candidate(base, t), path); },
        [&](const fit::GripTrial& t) {
          std::printf("%s: tried %s\n", name, fit::trial_line(t).c_str());
        });
    const double took_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    ASSERT_TRUE(choice.stretch);
    ASSERT_GE(choice.chosen, 0) << name << ": no placement holds when replayed";
    const fit::GripTrial& chosen = choice.trials[static_cast<std::size_t>(choice.chosen)];
    ASSERT_TRUE(chosen.replayed);
    write_grip_scene(with_candidate(base, chosen), path);

    const real_grip::RealGripRun run =
        real_grip::replay_real_grip(path, log_path_, "object", "pedestal");
    // world time 0 is the log's first sample
    const double opening_s = choice.opening_s - hand::ns_to_log_seconds(log_.samples.front().t_ns);
    std::printf(
        "%s: chosen in %.1f s after %zu trial(s): t_s %.4f (closure %.0f%%), %s, result %d of "
        "%d; the hand opens after %.3f s, the log ends at %.3f s\n%s"
        "deepest below the pedestal top %.1f mm, fastest free %.3f m/s (at %.3f s), deepest "
        "link in the object %.2f mm, in a static object %.2f mm\n",
        name, took_s, choice.trials.size(), hand::ns_to_log_seconds(chosen.moment.t_ns),
        chosen.moment.closure_share * 100.0, chosen.placement.rest_name, chosen.rank, chosen.of,
        opening_s, run.last_sample_s, run.events.c_str(), run.deepest_below_support_m * 1e3,
        run.fastest_free_horizontal_mps, run.fastest_free_at_s, run.deepest_link_in_object_m * 1e3,
        run.deepest_link_in_static_m * 1e3);

    ASSERT_GE(run.grasp_s, 0.0) << name << ": never grasped\n" << run.events;
    EXPECT_LT(run.grasp_s, opening_s) << run.events;
    ASSERT_GE(run.release_s, 0.0) << name << ": never let go\n" << run.events;
    EXPECT_GT(run.release_s, opening_s) << run.events;
    EXPECT_LE(run.release_s, run.last_sample_s) << run.events;
    EXPECT_TRUE(run.release_reason == physics::GraspReason::kHandOpened ||
                run.release_reason == physics::GraspReason::kThumbLeft ||
                run.release_reason == physics::GraspReason::kFingersLeft)
        << physics::grasp_reason_name(run.release_reason);
    EXPECT_LE(run.deepest_below_support_m, 0.01);
    EXPECT_LE(run.fastest_free_horizontal_mps, 0.5);
    EXPECT_LE(run.deepest_link_in_object_m, 1e-3);
    EXPECT_LE(run.deepest_link_in_static_m, 1e-3);

    // the file is the scene grip_fit replayed (its numbers rounded as written): the same run
    EXPECT_EQ(run.events, chosen.run.events);
    EXPECT_EQ(run.deepest_below_support_m, chosen.run.deepest_below_support_m);
    EXPECT_EQ(run.fastest_free_horizontal_mps, chosen.run.fastest_free_horizontal_mps);
    EXPECT_EQ(run.end_s, chosen.run.end_s);
  }
};

// The same recording taken from Leap's own JSON (tests/data/real/leap/grab.json) the way a user
// takes it: imported (hand_import), its hand calibrated on it and retargeted (hand_retarget).
// Nothing is trimmed: the opening hand sweeps through the object's place before it closes.
class RetargetedGripFitReplay : public GripFitReplay {
 protected:
  void SetUp() override {
    const std::string dir = test::make_temp_dir("retargeted_grip_fit");
    const hand::tracking::LeapImport in =
        hand::tracking::import_leapjs(source_dir() + "/tests/data/real/leap/grab.json");
    const hand::tracking::JointsReplay replay = hand::tracking::replay_joints(
        in.frames, hand::tracking::JointsSpace::kXr, load_hand_model(source_dir() + "/config/hand.yaml"),
        true, Eigen::Vector3d(0.36, -0.35, 0.84));
    const hand::tracking::ReplayedHand& right = replay.hands[0];
    ASSERT_TRUE(right.present);
    ASSERT_EQ(right.samples.size(), in.frames.size()) << "every palm placed";
    hand_path_ = dir + "/hand_grab.yaml";
    log_path_ = dir + "/grab.csv";
    write_calibrated_hand_yaml(source_dir() + "/config/hand.yaml", right.model, hand_path_, {"test"});
    hand::write_glove_log(log_path_, right.samples, false, {"retargeted from grab.json"});
  }
};

TEST_F(RetargetedGripFitReplay, A3cmBarIsHeldUntilTheHandOpens) {
  fit_and_replay("retargeted, 3 cm bar", "bar", physics::Shape::cylinder(0.015, 0.12));
}
TEST_F(RetargetedGripFitReplay, A4cmCylinderIsHeldUntilTheHandOpens) {
  fit_and_replay("retargeted, 4 cm cylinder", "cylinder", physics::Shape::cylinder(0.02, 0.12));
}
TEST_F(RetargetedGripFitReplay, A5cmBallIsHeldUntilTheHandOpens) {
  fit_and_replay("retargeted, 5 cm ball", "ball", physics::Shape::sphere(0.025));
}

TEST_F(GripFitReplay, A3cmBarIsHeldUntilTheHandOpens) {
  fit_and_replay("3 cm bar", "bar", physics::Shape::cylinder(0.015, 0.12));
}
TEST_F(GripFitReplay, A4cmCylinderIsHeldUntilTheHandOpens) {
  fit_and_replay("4 cm cylinder", "cylinder", physics::Shape::cylinder(0.02, 0.12));
}
TEST_F(GripFitReplay, A5cmBallIsHeldUntilTheHandOpens) {
  fit_and_replay("5 cm ball", "ball", physics::Shape::sphere(0.025));
}

}  // namespace
}  // namespace vcockpit
