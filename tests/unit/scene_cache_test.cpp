// The image generator's scene cache (image_generator/node/scene_cache): a hand is drawn only with
// the geometry of its own cockpit/hand_info, hand states of a hand without info are counted and
// not drawn, a new info replaces the geometry, malformed messages are refused, a warm frame
// allocates nothing, and a control's light follows its control_state.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "hand/config/hand_yaml.hpp"
#include "idl/topics/hand_info_convert.hpp"
#include "idl/topics/pose_convert.hpp"
#include "image_generator/node/scene_cache.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::image_generator {
namespace {

const hand::HandModel& shipped_hand() {
  static const hand::HandModel model = load_hand_model(test::source_dir() + "/config/hand.yaml");
  return model;
}

cockpit::HandState hand_state(uint32_t hand_id, int64_t sim_time_ns) {
  cockpit::HandState state;
  state.hand_id(hand_id);
  state.sim_time_ns(sim_time_ns);
  state.tracking(true);
  state.grasped_object_id(cockpit::kNoObject);
  const auto X = to_idl(Eigen::Isometry3d(Eigen::Translation3d(0.3, 0.1 * hand_id, 1.0)));
  state.X_GH(X);
  for (auto& link : state.X_GL()) link = X;
  return state;
}

// An object's state: at the origin, held by no hand.
void place_at_origin(SceneCache& cache, uint32_t id) {
  cockpit::ObjectState state;
  state.object_id(id);
  state.X_GO(to_idl(Eigen::Isometry3d::Identity()));
  state.held_by_hand_id(cockpit::kNoObject);
  cache.on_state(state);
}

void add_box(SceneCache& cache) {
  cockpit::ObjectInfo info;
  info.object_id(0);
  info.shape(cockpit::BOX);
  info.dimensions_m({0.1, 0.1, 0.1});
  cache.on_info(info);
  place_at_origin(cache, 0);
}

constexpr std::size_t kHandInstances = 16;  // palm box + 15 phalanx capsules

// A MESH object's info: a node of a +y-up model file at scale 1, the box round it `size_m`.
cockpit::ObjectInfo mesh_object_info(uint32_t id, cockpit::ObjectKind kind, const std::string& file,
                                     const std::string& node, const std::array<double, 3>& size_m) {
  cockpit::ObjectInfo info;
  info.object_id(id);
  info.kind(kind);
  info.shape(cockpit::MESH);
  info.dimensions_m(size_m);
  info.mesh_file(file);
  info.mesh_node(node);
  info.mesh_scale(1.0);
  info.mesh_z_up(false);
  return info;
}

// A MESH object: its model file is loaded once, in the frame the physics node gives it (the node
// origin at mesh_origin_m), and drawn as that mesh; two objects of the same part share it. A file
// that cannot be read here is counted and its object drawn as the box round its vertices.
TEST(SceneCache, AMeshObjectIsDrawnAsItsModelOrItsBoxWhenTheFileFails) {
  SceneCache cache;
  const auto mesh_info = [&](uint32_t id, const std::string& file) {
    cockpit::ObjectInfo info = mesh_object_info(id, cockpit::DYNAMIC_OBJECT, file, "button", {0.024, 0.024, 0.012});
    info.mesh_origin_m(to_idl(Eigen::Vector3d(0.0, 0.0, 0.001)));
    info.mesh_center_m(to_idl(Eigen::Vector3d(0.0, 0.0, 0.002)));
    cache.on_info(info);
    place_at_origin(cache, id);
  };
  const std::string button = test::source_dir() + "/tests/data/models/button.gltf";
  mesh_info(0, button);
  mesh_info(1, button);
  mesh_info(2, test::source_dir() + "/tests/data/models/no_such.glb");
  std::vector<render::Instance> out;
  cache.build(out);
  ASSERT_EQ(out.size(), 3u);
  ASSERT_EQ(out[0].primitive, render::Primitive::kMesh);
  ASSERT_TRUE(out[0].mesh);
  EXPECT_EQ(out[0].mesh, out[1].mesh) << "one model part, loaded once";
  EXPECT_EQ(cache.model_triangles(), 20u);
  // the cap's bottom (z = -6 mm in its node) moved by the origin: -5 mm
  float lowest = 1.0f;
  for (const render::Vertex& v : out[0].mesh->vertices) lowest = std::min(lowest, v.position[2]);
  EXPECT_NEAR(lowest, -0.005f, 1e-6f);
  EXPECT_EQ(out[2].primitive, render::Primitive::kBox);
  EXPECT_TRUE(out[2].size_m.isApprox(Eigen::Vector3d(0.024, 0.024, 0.012)));
  EXPECT_TRUE(out[2].X_GO.translation().isApprox(Eigen::Vector3d(0.0, 0.0, 0.002)))
      << "centred where the vertices are";
  EXPECT_EQ(cache.models_refused(), 1u);
  EXPECT_NE(cache.last_model_error().find("no_such.glb: no such file"), std::string::npos)
      << cache.last_model_error();
  EXPECT_EQ(cache.model_textures(), 0u);
}

// A textured model part brings its image to the draw; one whose image is not found is drawn
// without it, counted and named for the log.
TEST(SceneCache, AModelsTexturesAreLoadedAndAMissingOneCounted) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("vcockpit_scene_cache_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string models = test::source_dir() + "/tests/data/models/";
  for (const char* name : {"placard.obj", "placard.mtl"})
    std::filesystem::copy_file(models + name, dir / name, std::filesystem::copy_options::overwrite_existing);
  SceneCache cache;
  const auto mesh_info = [&](uint32_t id, const std::string& file) {
    cache.on_info(mesh_object_info(id, cockpit::STATIC_OBJECT, file, "placard", {0.01, 0.2, 0.1}));
    place_at_origin(cache, id);
  };
  mesh_info(0, models + "placard.gltf");
  mesh_info(1, (dir / "placard.obj").string());
  std::vector<render::Instance> out;
  cache.build(out);
  std::filesystem::remove_all(dir);
  ASSERT_EQ(out.size(), 2u);
  ASSERT_TRUE(out[0].mesh && out[1].mesh);
  ASSERT_EQ(out[0].mesh->textures.size(), 1u);
  EXPECT_EQ(out[0].mesh->textures[0].width, 64u);
  EXPECT_TRUE(out[1].mesh->textures.empty());
  EXPECT_EQ(cache.model_textures(), 1u);
  EXPECT_EQ(cache.textures_left_out(), 1u);
  EXPECT_NE(cache.last_texture_left_out().find("placard.obj node 'placard': texture 'placard.png' not found"),
            std::string::npos)
      << cache.last_texture_left_out();
}

// A control with a light: its cap (object 0) and its annunciator (object 1) are drawn dull while
// its control_state says off and glowing while on; a control without a light changes nothing.
TEST(SceneCache, ALitControlsCapAndAnnunciatorGlowAndAreDullWhenOff) {
  SceneCache cache;
  for (uint32_t id : {0u, 1u, 2u}) {
    cockpit::ObjectInfo info;
    info.object_id(id);
    info.shape(cockpit::BOX);
    info.dimensions_m({0.02, 0.02, 0.01});
    info.color_rgba({0.9f, 0.6f, 0.1f, 1.0f});
    cache.on_info(info);
    place_at_origin(cache, id);
  }
  // a state before the info: kept and applied when the info comes
  cockpit::ControlState state;
  state.control_id(4);
  state.lit(true);
  cache.on_control_state(state);
  cockpit::ControlInfo info;
  info.control_id(4);
  info.object_id(0);
  info.light_object_id(1);
  info.lit_position(1);
  cache.on_control_info(info);
  std::vector<render::Instance> out;
  cache.build(out);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_TRUE(out[0].highlight);
  EXPECT_TRUE(out[1].highlight);
  EXPECT_FALSE(out[2].highlight) << "not this control's";
  EXPECT_EQ(out[0].rgba[0], 0.9f);
  state.lit(false);
  cache.on_control_state(state);
  cache.build(out);
  EXPECT_FALSE(out[0].highlight);
  EXPECT_FALSE(out[1].highlight);
  EXPECT_LT(out[0].rgba[0], 0.5f) << "dull when off";
  EXPECT_LT(out[1].rgba[1], 0.3f);
  EXPECT_EQ(out[2].rgba[0], 0.9f) << "an object without a light keeps its colour";
}

TEST(SceneCache, NoHandIsDrawnBeforeItsHandInfo) {
  SceneCache cache;
  add_box(cache);
  cache.on_hand(hand_state(0, 5'000'000));
  std::vector<render::Instance> out;
  cache.build(out);
  EXPECT_EQ(out.size(), 1u) << "the box only: no geometry for hand 0 yet";
  EXPECT_FALSE(cache.has_hand());
  EXPECT_FALSE(cache.has_hand_info(0));
  EXPECT_EQ(cache.hand_states_without_info(), 1u);
  EXPECT_EQ(cache.hand_without_info(), 0);
  EXPECT_EQ(cache.newest_sim_time_ns(), 0) << "an undrawn hand is not part of the drawn world";

  // the info arrives: the hand kept from before is drawn with the info's sizes
  ASSERT_TRUE(cache.on_hand_info(to_hand_info(shipped_hand(), 0)));
  EXPECT_TRUE(cache.has_hand_info(0));
  EXPECT_TRUE(cache.has_hand());
  EXPECT_EQ(cache.hand_without_info(), -1);
  EXPECT_EQ(cache.hand().hand_id(), 0u);
  EXPECT_EQ(cache.newest_sim_time_ns(), 5'000'000);
  cache.build(out);
  ASSERT_EQ(out.size(), 1u + kHandInstances);
  EXPECT_EQ(out[1].primitive, render::Primitive::kRoundedBox);
  EXPECT_EQ(out[1].size_m, shipped_hand().palm_size_m);
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const render::Instance& in = out[1 + static_cast<std::size_t>(l)];
    EXPECT_EQ(in.primitive, render::Primitive::kTaperedCapsule);
    EXPECT_EQ(in.size_m.x(), shipped_hand().capsules[l].radius_m) << l;
    EXPECT_EQ(in.size_m.y(), shipped_hand().capsules[l].length_m) << l;
  }
  cache.on_hand(hand_state(0, 6'000'000));
  EXPECT_EQ(cache.hand_states_without_info(), 1u);
  EXPECT_EQ(cache.newest_sim_time_ns(), 6'000'000);
}

TEST(SceneCache, EachHandUsesTheInfoOfItsOwnHandId) {
  SceneCache cache;
  hand::HandModel wide = shipped_hand();
  for (auto& c : wide.capsules) c.radius_m *= 2.0;
  ASSERT_TRUE(cache.on_hand_info(to_hand_info(wide, 0)));
  cache.on_hand(hand_state(1, 1'000'000));  // the left hand: no info for it
  cache.on_hand(hand_state(0, 2'000'000));
  std::vector<render::Instance> out;
  cache.build(out);
  ASSERT_EQ(out.size(), kHandInstances) << "only the right hand";
  EXPECT_EQ(out[4].size_m.x(), 2.0 * shipped_hand().capsules[4].radius_m);
  EXPECT_EQ(cache.hand_states_without_info(), 1u);
  EXPECT_EQ(cache.hand_without_info(), 1);
  EXPECT_EQ(cache.hand().hand_id(), 0u);

  // the left hand's info: both hands drawn, each with its own sizes
  ASSERT_TRUE(cache.on_hand_info(to_hand_info(hand::mirrored(shipped_hand()), 1)));
  cache.build(out);
  ASSERT_EQ(out.size(), 2 * kHandInstances);
  EXPECT_EQ(out[4].size_m.x(), 2.0 * shipped_hand().capsules[4].radius_m);
  EXPECT_EQ(out[kHandInstances + 4].size_m.x(), shipped_hand().capsules[4].radius_m);

  // a restarted physics node with another hand file: its info replaces the geometry
  ASSERT_TRUE(cache.on_hand_info(to_hand_info(shipped_hand(), 0)));
  cache.build(out);
  EXPECT_EQ(out[4].size_m.x(), shipped_hand().capsules[4].radius_m);
}

TEST(SceneCache, TheTrackedHandIsAGhostOnlyWhenItIsAwayFromTheDrawnOne) {
  SceneCache cache;
  ASSERT_TRUE(cache.on_hand_info(to_hand_info(shipped_hand(), 0)));
  cockpit::HandState state = hand_state(0, 1'000'000);
  const auto X_tracked = to_idl(Eigen::Isometry3d(Eigen::Translation3d(0.3, 0.0, 0.95)));
  for (auto& link : state.tracked_X_GL()) link = X_tracked;
  state.tracked_offset_m(0.5 * SceneCache::kDefaultGhostThreshold_m);
  cache.on_hand(state);
  std::vector<render::Instance> out;
  cache.build(out);
  EXPECT_EQ(out.size(), kHandInstances) << "close enough: no ghost";

  state.tracked_offset_m(0.05);  // the tracked hand 5 cm into a panel
  cache.on_hand(state);
  cache.build(out);
  ASSERT_EQ(out.size(), kHandInstances + 15) << "the hand, then the ghost's 15 bones";
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const render::Instance& bone = out[kHandInstances + static_cast<std::size_t>(l) - 1];
    EXPECT_EQ(bone.primitive, render::Primitive::kCapsule);
    EXPECT_LT(bone.size_m.x(), shipped_hand().capsules[l].radius_m) << "thinner than the hand";
    EXPECT_EQ(bone.size_m.y(), shipped_hand().capsules[l].length_m);
    // at the tracked link pose: the capsule's centre half its length along the link's x
    EXPECT_NEAR(bone.X_GO.translation().z(), 0.95, 1e-12);
  }

  cache.set_ghost_threshold_m(0.1);
  cache.build(out);
  EXPECT_EQ(out.size(), kHandInstances) << "a larger threshold: no ghost at 5 cm";
}

// A hand tracker's joints are drawn as dots beside the hand when asked, only the tracked ones,
// only while they are of the hand's time; a bad message is refused.
TEST(SceneCache, TrackedJointsAreDotsBesideTheirHandWhenShown) {
  SceneCache cache;
  ASSERT_TRUE(cache.on_hand_info(to_hand_info(shipped_hand(), 1)));
  cockpit::HandState state = hand_state(1, 1'000'000);
  state.sample_time_ns(5'000'000'000);
  cache.on_hand(state);
  cockpit::TrackedJoints joints;
  joints.hand_id(1);
  joints.sample_time_ns(5'000'000'000);
  for (std::size_t j = 0; j < 26; ++j) {
    joints.valid()[j] = j != 1;  // the wrist not tracked
    joints.p_G_m()[j] = to_idl(Eigen::Vector3d(0.3, 0.1, 1.0 + 0.01 * static_cast<double>(j)));
  }
  ASSERT_TRUE(cache.on_tracked_joints(joints));
  std::vector<render::Instance> out;
  cache.build(out);
  EXPECT_EQ(out.size(), kHandInstances) << "not shown unless asked";

  cache.set_show_tracked_joints(true);
  cache.build(out);
  ASSERT_EQ(out.size(), kHandInstances + 25) << "a dot per tracked joint";
  const render::Instance& tip = out.back();  // the little fingertip, the last joint
  EXPECT_EQ(tip.primitive, render::Primitive::kSphere);
  EXPECT_EQ(tip.size_m.x(), SceneCache::kJointDotRadius_m);
  EXPECT_NEAR(tip.X_GO.translation().z(), 1.25, 1e-12);

  state.sample_time_ns(5'000'000'000 + 2 * SceneCache::kTrackedJointsAge_ns);
  cache.on_hand(state);
  cache.build(out);
  EXPECT_EQ(out.size(), kHandInstances) << "joints of another moment are not drawn";

  joints.p_G_m()[3] = to_idl(Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  EXPECT_FALSE(cache.on_tracked_joints(joints));
  joints.hand_id(2);
  EXPECT_FALSE(cache.on_tracked_joints(joints));
  EXPECT_EQ(cache.hand_messages_refused(), 2u);
}

TEST(SceneCache, MalformedHandMessagesAreRefused) {
  SceneCache cache;
  cockpit::HandInfo bad_id = to_hand_info(shipped_hand(), 2);
  EXPECT_FALSE(cache.on_hand_info(bad_id));
  cockpit::HandInfo nan_radius = to_hand_info(shipped_hand(), 0);
  nan_radius.capsules()[cockpit::MIDDLE_DISTAL].radius_m(std::numeric_limits<double>::quiet_NaN());
  EXPECT_FALSE(cache.on_hand_info(nan_radius));
  EXPECT_FALSE(cache.has_hand_info(0));
  cache.on_hand(hand_state(7, 1));
  EXPECT_EQ(cache.hand_messages_refused(), 3u);
  std::vector<render::Instance> out;
  cache.build(out);
  EXPECT_TRUE(out.empty());
}

TEST(SceneCache, WarmFramesAllocateNothing) {
  SceneCache cache;
  add_box(cache);
  ASSERT_TRUE(cache.on_hand_info(to_hand_info(shipped_hand(), 0)));
  ASSERT_TRUE(cache.on_hand_info(to_hand_info(hand::mirrored(shipped_hand()), 1)));
  const cockpit::HandState right = hand_state(0, 1), left = hand_state(1, 1);
  const cockpit::HandState stranger = hand_state(5, 1);
  std::vector<render::Instance> out;
  cache.on_hand(right);
  cache.on_hand(left);
  cache.build(out);  // grows the vector once
  test::g_allocations = 0;
  test::g_count_allocations = true;
  static void* volatile sink = nullptr;  // control: the counter sees an allocation
  sink = ::operator new(16);
  test::g_count_allocations = false;
  ::operator delete(sink);
  ASSERT_EQ(test::g_allocations.load(), 1);
  test::g_allocations = 0;
  test::g_count_allocations = true;
  for (int i = 0; i < 100; ++i) {
    cache.on_hand(right);
    cache.on_hand(left);
    cache.on_hand(stranger);
    cache.build(out);
  }
  test::g_count_allocations = false;
  EXPECT_EQ(test::g_allocations.load(), 0);
  EXPECT_EQ(out.size(), 1u + 2 * kHandInstances);
}

}  // namespace
}  // namespace vcockpit::image_generator
