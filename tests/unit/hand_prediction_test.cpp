// The image generator's two layers and its hand prediction: static objects go to the background
// layer and everything that moves (a control's part whatever its kind, loose objects, hands) to
// the moving one; a hand is extrapolated from its last two states at their velocities over the
// horizon to the display time, capped, and not at all without a usable pair.

#include <gtest/gtest.h>

#include <cmath>

#include "hand/config/hand_yaml.hpp"
#include "idl/topics/hand_info_convert.hpp"
#include "idl/topics/pose_convert.hpp"
#include "image_generator/node/hand_prediction.hpp"
#include "image_generator/node/scene_cache.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::image_generator {
namespace {

constexpr int64_t kMs = 1'000'000;

TEST(ExtrapolatePose, MovesOnAtTheSameLinearAndAngularVelocity) {
  const Eigen::Isometry3d previous(Eigen::Translation3d(1.0, 0.0, 0.0));
  Eigen::Isometry3d now = Eigen::Translation3d(1.01, 0.0, 0.0) *
                          Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ());
  // 1 cm and 0.1 rad in 10 ms; 5 ms on: another 5 mm and 0.05 rad
  const Eigen::Isometry3d ahead = extrapolate_pose(previous, now, 0.010, 0.005);
  EXPECT_NEAR((ahead.translation() - Eigen::Vector3d(1.015, 0, 0)).norm(), 0.0, 1e-12);
  const Eigen::AngleAxisd turned(ahead.rotation());
  EXPECT_NEAR(turned.angle(), 0.15, 1e-9);
  EXPECT_NEAR(turned.axis().z(), 1.0, 1e-9);
  EXPECT_TRUE(extrapolate_pose(previous, now, 0.010, 0.0).isApprox(now)) << "no horizon";
  EXPECT_TRUE(extrapolate_pose(previous, now, 0.0, 0.005).isApprox(now)) << "no interval";
}

cockpit::HandState state_at(int64_t sample_time_ns, int64_t source_stamp_ns, double x_m) {
  cockpit::HandState s;
  s.hand_id(0);
  s.sample_time_ns(sample_time_ns);
  s.source_stamp_ns(source_stamp_ns);
  s.tracking(true);
  const auto X = to_idl(Eigen::Isometry3d(Eigen::Translation3d(x_m, 0.0, 1.0)));
  for (auto& link : s.X_GL()) link = X;
  for (auto& link : s.tracked_X_GL()) link = X;
  return s;
}

TEST(HandPredictor, ExtrapolatesFromTheLastTwoStatesToTheDisplayTime) {
  HandPredictor predictor;
  LinkPoses links;
  EXPECT_FALSE(predictor.predict(100 * kMs, false, links)) << "nothing yet";
  predictor.on_state(state_at(10 * kMs, 1000 * kMs, 0.30));
  EXPECT_FALSE(predictor.predict(1010 * kMs, false, links)) << "one state: no velocity";
  EXPECT_NEAR(links[0].translation().x(), 0.30, 1e-12) << "the state as it is";
  // 1 m/s along x (4 mm in 4 ms of source time)
  predictor.on_state(state_at(14 * kMs, 1004 * kMs, 0.304));
  predictor.on_state(state_at(14 * kMs, 1004 * kMs, 0.304));  // a repeat: ignored
  // shown 12 ms after the glove's moment of the newest state: 12 mm further
  ASSERT_TRUE(predictor.predict(1016 * kMs, false, links));
  EXPECT_EQ(predictor.horizon_ns(1016 * kMs), 12 * kMs);
  EXPECT_NEAR(links[7].translation().x(), 0.316, 1e-9);
  ASSERT_TRUE(predictor.predict(1016 * kMs, true, links));
  EXPECT_NEAR(links[15].translation().x(), 0.316, 1e-9) << "the tracked hand alike";
  // capped: a frame a second late is not drawn a metre away
  ASSERT_TRUE(predictor.predict(2004 * kMs, false, links));
  EXPECT_EQ(predictor.horizon_ns(2004 * kMs), HandPredictor::kMaxHorizon_ns);
  EXPECT_NEAR(links[0].translation().x(), 0.304 + 0.05, 1e-9);
}

TEST(HandPredictor, NoPredictionAcrossAGapOrWhileTheGloveIsLost) {
  HandPredictor predictor;
  LinkPoses links;
  predictor.on_state(state_at(10 * kMs, 1000 * kMs, 0.30));
  predictor.on_state(state_at(310 * kMs, 1300 * kMs, 0.40));  // 300 ms later: no velocity
  EXPECT_FALSE(predictor.predict(1310 * kMs, false, links));
  EXPECT_NEAR(links[0].translation().x(), 0.40, 1e-12);
  cockpit::HandState lost = state_at(314 * kMs, 1304 * kMs, 0.404);
  lost.tracking(false);
  predictor.on_state(lost);
  EXPECT_FALSE(predictor.predict(1310 * kMs, false, links)) << "the hand stays where it is";
}

void add_object(SceneCache& cache, uint32_t id, cockpit::ObjectKind kind) {
  cockpit::ObjectInfo info;
  info.object_id(id);
  info.kind(kind);
  info.shape(cockpit::BOX);
  info.dimensions_m({0.1, 0.1, 0.1});
  cache.on_info(info);
  cockpit::ObjectState state;
  state.object_id(id);
  state.X_GO(to_idl(Eigen::Isometry3d::Identity()));
  state.held_by_hand_id(cockpit::kNoObject);
  cache.on_state(state);
}

TEST(SceneCacheLayers, StaticObjectsAreTheBackgroundAndWhatMovesIsNot) {
  SceneCache cache;
  add_object(cache, 0, cockpit::STATIC_OBJECT);   // the panel
  add_object(cache, 1, cockpit::DYNAMIC_OBJECT);  // the cup
  add_object(cache, 2, cockpit::STATIC_OBJECT);   // a switch's bat: a control's moving part
  cockpit::ControlInfo control;
  control.control_id(0);
  control.object_id(2);
  control.lit_position(-1);
  cache.on_control_info(control);
  add_object(cache, 3, cockpit::STATIC_OBJECT);  // info after its control's: still moving
  control.control_id(1);
  control.object_id(3);
  cache.on_control_info(control);
  add_object(cache, 3, cockpit::STATIC_OBJECT);
  const hand::HandModel model = load_hand_model(test::source_dir() + "/config/hand.yaml");
  cockpit::HandInfo hand_info = to_hand_info(model, 0);
  cache.on_hand_info(hand_info);
  cache.on_hand(state_at(10 * kMs, 1000 * kMs, 0.3));

  std::vector<render::Instance> fixed, moving, all;
  cache.build_fixed(fixed);
  cache.build_moving(moving);
  cache.build(all);
  ASSERT_EQ(fixed.size(), 1u);
  EXPECT_TRUE(fixed[0].fixed);
  EXPECT_EQ(moving.size(), 3u + 16u) << "the cup, two control parts and the hand";
  for (const render::Instance& in : moving) EXPECT_FALSE(in.fixed);
  EXPECT_EQ(all.size(), fixed.size() + moving.size());
}

}  // namespace
}  // namespace vcockpit::image_generator
