// grip_fit on a real recording: the Leap Motion "grab" (tests/data/real/README.md) with the
// project's hand. Its steadiest closed moment lies in the first fist (the log closes it twice),
// and a 3 cm bar, a 4 cm cylinder and a 5 cm ball each have a placement there; each written scene
// loads. The figures are printed for the record.

#include <gtest/gtest.h>

#include <cstdio>

#include "hand/glove_log.hpp"
#include "physics_node/config/grip_scene_yaml.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/fit/grip_fit.hpp"
#include "physics_node/fit/steady_moment.hpp"
#include "tests/support/process.hpp"
#include "tests/unit/grip_fit_samples.hpp"

namespace vcockpit::fit {
namespace {

using physics::Shape;

class GripFitLeap : public ::testing::Test {
 protected:
  hand::HandModel model_ = test::grip_fit_hand();
  hand::GloveLog log_ =
      hand::read_glove_log(test::source_dir() + "/tests/data/real/leap_grab.csv", model_);

  void place(const char* name, const Shape& shape) {
    const auto moment = steadiest_closed_moment(model_, log_.samples);
    ASSERT_TRUE(moment);
    const double t_s = hand::ns_to_log_seconds(moment->t_ns);
    // the first fist closes 0.2-0.8 s (the second, 2.2-2.7 s, is steadier but comes later)
    EXPECT_GT(t_s, 0.2);
    EXPECT_LT(t_s, 0.85);
    const GripHand grip = grip_hand_at(model_, log_.samples[moment->index]);
    const auto before = hands_before(model_, log_.samples, moment->index);
    const FitResult r = fit_object_in_grip(grip, shape, {}, before);
    const Placement& p = r.best;
    const Eigen::Vector3d p_GO = p.X_GO.translation();
    const Eigen::Vector3d rpy = object_rpy_deg(shape, p.X_GO.linear());
    std::printf(
        "leap grab, %s: t_s %.4f (sample %zu, motion %.3f rad); %s at (%.5f, %.5f, %.5f) m, "
        "rpy_deg (%.2f, %.2f, %.2f)\n",
        name, t_s, moment->index, moment->motion, p.accepted ? "placed" : "NOT PLACED", p_GO.x(),
        p_GO.y(), p_GO.z(), rpy.x(), rpy.y(), rpy.z());
    for (int f = 0; f < hand::kFingerCount; ++f) {
      const auto k = static_cast<std::size_t>(f);
      std::printf("  %-7s %7.2f mm  %-15s %4.0f deg\n",
                  std::string(hand::finger_name(static_cast<hand::Finger>(f))).c_str(),
                  p.finger_distance_m[k] * 1e3,
                  std::string(hand::link_name(p.finger_link[k])).c_str(),
                  p.finger_opposition_deg[k]);
    }
    std::printf("  palm %.2f mm; deepest link %s %.2f mm; the hand before the moment %.2f mm\n",
                p.link_distance_m[0] * 1e3, std::string(hand::link_name(p.deepest_link)).c_str(),
                p.deepest_m * 1e3, p.approach_m * 1e3);
    ASSERT_TRUE(p.accepted);
    EXPECT_LE(p.finger_distance_m[0], 1e-3);
    EXPECT_GE(p.touching_fingers, 3);
    EXPECT_GE(p.gripping_fingers, 1);
    EXPECT_LE(p.deepest_m, 2e-3);

    GripSceneSpec spec;
    spec.shape = shape;
    spec.X_GO = p.X_GO;
    spec.layout = lay_out_supports(grip, shape, p.X_GO);
    spec.hand_path = test::source_dir() + "/config/hand.yaml";
    spec.cockpit_path = test::source_dir() + "/config/cockpit.yaml";
    const std::string path = test::make_temp_dir("grip_fit_leap") + "/scene.yaml";
    write_grip_scene(spec, path);
    const physics::Scene scene = load_scene(path);
    const int object = scene.find_object("object");
    ASSERT_GE(object, 0);
    EXPECT_LT((scene.objects[static_cast<std::size_t>(object)].X_GO.translation() - p_GO).norm(),
              1e-6);
  }
};

TEST_F(GripFitLeap, A3cmBar) {
  place("3 cm bar", Shape::cylinder(0.015, 0.12));
}
TEST_F(GripFitLeap, A4cmCylinder) {
  place("4 cm cylinder", Shape::cylinder(0.02, 0.12));
}
TEST_F(GripFitLeap, A5cmBall) {
  place("5 cm ball", Shape::sphere(0.025));
}

}  // namespace
}  // namespace vcockpit::fit
