// The OpenXR side of hand tracking: the replay runtime's timeline, OpenXR joint locations as
// tracked joints, and openxr_hand_bridge's session through the real Khronos loader against the
// replay runtime, with Debian's core validation layer on (and shown to catch a misuse).

#include <gtest/gtest.h>

#include <openxr/openxr.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "common/clock.hpp"
#include "glove_driver/openxr/replay_runtime/joints_timeline.hpp"
#include "glove_driver/openxr/xr_hand_session.hpp"
#include "glove_driver/openxr/xr_joint_locations.hpp"
#include "glove_driver/openxr/xr_struct.hpp"
#include "hand/tracking/joints_log.hpp"
#include "tests/support/process.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::glove {
namespace {

using hand::tracking::JointsFrame;
using hand::tracking::XrJoint;

// Joint j of a frame at (j cm, 10 cm + the frame's time in m, -30 cm): each joint and frame apart.
JointsFrame frame_at(double t_s, bool left) {
  JointsFrame f;
  f.t_ns = std::llround(t_s * 1e9);
  f.left_hand = left;
  for (std::size_t j = 0; j < f.joints.size(); ++j) {
    f.joints[j].valid = true;
    f.joints[j].p_m = Eigen::Vector3d(0.01 * static_cast<double>(j), 0.1 + t_s, -0.3);
  }
  return f;
}

TEST(JointsTimeline, ServesEachHandsNewestFrameAndLosesTheHandInGaps) {
  // right at 0, 0.05, 0.1 and then 0.5 s (a 0.4 s gap); left from 0.2 s
  std::vector<JointsFrame> frames = {frame_at(0.0, false), frame_at(0.05, false), frame_at(0.1, false),
                                     frame_at(0.2, true), frame_at(0.5, false)};
  const xr_replay::JointsTimeline timeline(frames, 1.0, false);
  const auto right_at = [&](double s) { return timeline.at(false, std::llround(s * 1e9)); };
  ASSERT_NE(right_at(0.0), nullptr);
  EXPECT_EQ(right_at(0.0)->t_ns, 0);
  EXPECT_EQ(right_at(0.07)->t_ns, 50'000'000);
  EXPECT_EQ(right_at(0.19)->t_ns, 100'000'000) << "90 ms after its newest frame: still tracked";
  EXPECT_EQ(right_at(0.25), nullptr) << "150 ms into a gap: lost";
  EXPECT_EQ(right_at(0.5)->t_ns, 500'000'000);
  EXPECT_EQ(timeline.at(true, 100'000'000), nullptr) << "before the left hand's first frame";
  EXPECT_EQ(timeline.at(true, 250'000'000)->t_ns, 200'000'000);
  EXPECT_FALSE(timeline.ended(500'000'000));
  EXPECT_TRUE(timeline.ended(500'000'001));
  EXPECT_EQ(right_at(0.6), nullptr) << "after the end";
}

TEST(JointsTimeline, LoopsOverTheLogWithOneIntervalToWrapAndRunsAtItsRate) {
  const std::vector<JointsFrame> frames = {frame_at(1.0, false), frame_at(1.1, false), frame_at(1.2, false)};
  const xr_replay::JointsTimeline looping(frames, 1.0, true);
  EXPECT_EQ(looping.period_ns(), 300'000'000);
  EXPECT_FALSE(looping.ended(10'000'000'000));
  EXPECT_EQ(looping.log_time_ns(350'000'000), 1'050'000'000);
  EXPECT_EQ(looping.at(false, 350'000'000)->t_ns, 1'000'000'000);
  const xr_replay::JointsTimeline fast(frames, 2.0, false);
  EXPECT_EQ(fast.at(false, 100'000'000)->t_ns, 1'200'000'000) << "0.1 s at twice the rate";
  EXPECT_THROW(xr_replay::JointsTimeline({}, 1.0, false), std::invalid_argument);
  EXPECT_THROW(xr_replay::JointsTimeline(frames, 0.0, false), std::invalid_argument);
}

TEST(JointsTimeline, ALostJointStaysWhereItWasLastSeenAndIsNotValid) {
  std::vector<JointsFrame> frames = {frame_at(0.0, false), frame_at(0.05, false)};
  frames[1][XrJoint::kIndexTip].valid = false;
  frames[1][XrJoint::kIndexTip].p_m = Eigen::Vector3d::Zero();
  frames[0][XrJoint::kThumbTip].valid = false;  // lost from the start: at the palm
  const xr_replay::JointsTimeline timeline(frames, 1.0, false);
  const JointsFrame& second = *timeline.at(false, 50'000'000);
  EXPECT_FALSE(second[XrJoint::kIndexTip].valid);
  EXPECT_TRUE(second[XrJoint::kIndexTip].p_m.isApprox(frames[0][XrJoint::kIndexTip].p_m));
  const JointsFrame& first = *timeline.at(false, 0);
  EXPECT_TRUE(first[XrJoint::kThumbTip].p_m.isApprox(frames[0][XrJoint::kPalm].p_m));
}

TEST(JointsTimeline, AJointNeverSeenWhileThePalmIsLostIsWhereThePalmWasLastSeen) {
  std::vector<JointsFrame> frames = {frame_at(0.0, false), frame_at(0.05, false)};
  frames[0][XrJoint::kLittleTip].valid = false;  // not seen until after the palm is lost
  frames[1][XrJoint::kLittleTip].valid = false;
  frames[1][XrJoint::kPalm].valid = false;
  const xr_replay::JointsTimeline timeline(frames, 1.0, false);
  const JointsFrame& second = *timeline.at(false, 50'000'000);
  EXPECT_TRUE(second[XrJoint::kLittleTip].p_m.isApprox(frames[0][XrJoint::kPalm].p_m))
      << "not at the tracking space's origin";
}

TEST(JointsTimeline, AnyElapsedTimeAtAnyRateStaysInRange) {
  const std::vector<JointsFrame> frames = {frame_at(1.0, false), frame_at(1.1, false)};
  const xr_replay::JointsTimeline fast(frames, 1000.0, false);
  EXPECT_TRUE(fast.ended(INT64_MAX));
  EXPECT_EQ(fast.at(false, INT64_MAX), nullptr);
  EXPECT_EQ(fast.log_time_ns(INT64_MAX), 1'100'000'001) << "one past the last frame";
  const xr_replay::JointsTimeline looping(frames, 1000.0, true);
  EXPECT_GE(looping.log_time_ns(INT64_MAX), 1'000'000'000);
  EXPECT_LT(looping.log_time_ns(INT64_MAX), 1'200'000'000);
}

TEST(XrJointLocations, APositionCountsOnlyWhenValidAndTrackedAndOrientationLikewise) {
  std::vector<XrHandJointLocationEXT> locations(XR_HAND_JOINT_COUNT_EXT);
  for (int j = 0; j < XR_HAND_JOINT_COUNT_EXT; ++j) {
    locations[j].locationFlags = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_POSITION_TRACKED_BIT |
                                 XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
    locations[j].pose = {{0, 0, 0, 1}, {0.01f * static_cast<float>(j), 0.2f, -0.3f}};
    locations[j].radius = 0.005f;
  }
  locations[XR_HAND_JOINT_INDEX_TIP_EXT].locationFlags = XR_SPACE_LOCATION_POSITION_VALID_BIT |
                                                         XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;  // a guess
  locations[XR_HAND_JOINT_WRIST_EXT].locationFlags |= XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;
  locations[XR_HAND_JOINT_WRIST_EXT].pose.orientation = {0, 0.70710678f, 0, 0.70710678f};
  const JointsFrame f = xr::joints_frame(locations.data(), true, 42);
  EXPECT_TRUE(f.left_hand);
  EXPECT_EQ(f.t_ns, 42);
  EXPECT_FALSE(f[XrJoint::kIndexTip].valid);
  ASSERT_TRUE(f[XrJoint::kLittleTip].valid);
  EXPECT_NEAR(f[XrJoint::kLittleTip].p_m.x(), 0.25, 1e-6);
  EXPECT_NEAR(f[XrJoint::kLittleTip].radius_m, 0.005, 1e-9);
  EXPECT_FALSE(f[XrJoint::kPalm].has_orientation) << "valid but not tracked";
  ASSERT_TRUE(f[XrJoint::kWrist].has_orientation);
  EXPECT_NEAR(f[XrJoint::kWrist].q.y(), 0.70710678, 1e-6);
}

// Through the loader: the replay runtime by its manifest, the validation layer on.
class ThroughTheLoader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::make_temp_dir("openxr_replay_test");
    log_ = dir_ + "/joints.csv";
    std::vector<JointsFrame> frames = {frame_at(0.0, false), frame_at(0.5, false), frame_at(1.0, false)};
    frames[1][XrJoint::kMiddleTip].valid = false;
    hand::tracking::write_joints_log(log_, hand::tracking::JointsSpace::kXr, frames, {});
    setenv("XR_RUNTIME_JSON", XR_REPLAY_RUNTIME_JSON, 1);
    setenv("VCOCKPIT_XR_REPLAY_LOG", log_.c_str(), 1);
    setenv("VCOCKPIT_XR_REPLAY_RATE", "1", 1);
    setenv("XR_ENABLE_API_LAYERS", "XR_APILAYER_LUNARG_core_validation", 1);
    setenv("XR_API_LAYER_PATH", "/usr/share/openxr/1/api_layers/explicit.d", 1);
    // the layer's own report (Debian's 1.0.20 layer sends its findings there, not to messengers)
    setenv("XR_CORE_VALIDATION_EXPORT_TYPE", "text", 1);
    setenv("XR_CORE_VALIDATION_FILE_NAME", (dir_ + "/validation.txt").c_str(), 1);
  }
  std::string validation_report() const { return test::read_text(dir_ + "/validation.txt"); }
  // Polls until focused (or false on timeout).
  static bool until_focused(xr::XrHandSession& session) {
    const int64_t deadline = monotonic_now_ns() + 5'000'000'000;
    while (monotonic_now_ns() < deadline) {
      if (!session.poll()) return false;
      if (session.focused()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return false;
  }
  std::string dir_, log_;
};

TEST_F(ThroughTheLoader, TheBridgesSessionLocatesTheLogsJointsAndSeesNoValidationMessage) {
  xr::XrHandSession session({});
  EXPECT_EQ(session.runtime_name(), "vcockpit joints-log replay");
  ASSERT_TRUE(until_focused(session));
  const int64_t now_ns = monotonic_now_ns();
  JointsFrame f;
  ASSERT_TRUE(session.locate(false, session.time_at(now_ns), 7, f)) << "the right hand, at the log's start";
  EXPECT_EQ(f.t_ns, 7);
  EXPECT_FALSE(f.left_hand);
  const JointsFrame expected = frame_at(0.0, false);
  for (std::size_t j = 0; j < f.joints.size(); ++j) {
    EXPECT_TRUE(f.joints[j].valid) << j;
    EXPECT_LT((f.joints[j].p_m - expected.joints[j].p_m).norm(), 1e-6) << "joint " << j;
  }
  EXPECT_FALSE(session.locate(true, session.time_at(now_ns), 7, f)) << "no left hand in the log";
  // 0.52 s on: the second frame, whose middle tip the tracker lost
  ASSERT_TRUE(session.locate(false, session.time_at(now_ns + 520'000'000), 8, f));
  EXPECT_NEAR(f[XrJoint::kPalm].p_m.y(), 0.6, 1e-6) << "the frame at 0.5 s";
  EXPECT_FALSE(f[XrJoint::kMiddleTip].valid);
  EXPECT_EQ(session.validation().errors, 0);
  EXPECT_EQ(session.validation().warnings, 0);
  EXPECT_EQ(validation_report().find("VALID_ERROR"), std::string::npos) << validation_report();
}

TEST_F(ThroughTheLoader, TheSessionEndsAtTheLogsEndAndIsNotLost) {
  setenv("VCOCKPIT_XR_REPLAY_RATE", "20", 1);  // the 1 s log in 50 ms
  xr::XrHandSession session({});
  ASSERT_TRUE(until_focused(session));
  const int64_t deadline = monotonic_now_ns() + 5'000'000'000;
  while (session.poll() && monotonic_now_ns() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_FALSE(session.poll()) << "over: the runtime stopped the session, the bridge ended it";
  EXPECT_FALSE(session.lost());
  EXPECT_EQ(session.validation().errors, 0);
}

TEST_F(ThroughTheLoader, RequestingExitEndsTheSession) {
  xr::XrHandSession session({});
  ASSERT_TRUE(until_focused(session));
  session.request_exit();
  int polls = 0;
  while (session.poll() && polls < 100) ++polls;
  EXPECT_LT(polls, 100) << "the session ended";
  EXPECT_FALSE(session.lost());
}

TEST_F(ThroughTheLoader, AnUnreadableLogFailsTheInstance) {
  { std::ofstream(log_) << "not a joints log\n"; }
  try {
    xr::XrHandSession session({});
    FAIL() << "the instance was made";
  } catch (const xr::XrError& e) {
    EXPECT_NE(std::string(e.what()).find("xrCreateInstance"), std::string::npos) << e.what();
    // the runtime's XR_ERROR_RUNTIME_FAILURE, as the loader passes it on (1.0.20: initialization
    // failed); the runtime names the file and line on stderr (openxr_bridge_test)
    EXPECT_NE(std::string(e.what()).find("XR_ERROR_"), std::string::npos) << e.what();
  }
}

// A bare instance through the loader, with these extensions.
XrInstance bare_instance(std::vector<const char*> extensions) {
  auto create = xr::xr_struct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
  std::snprintf(create.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "openxr_replay_test");
  create.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  create.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  create.enabledExtensionNames = extensions.data();
  XrInstance instance = XR_NULL_HANDLE;
  return xrCreateInstance(&create, &instance) == XR_SUCCESS ? instance : XR_NULL_HANDLE;
}

TEST_F(ThroughTheLoader, SpacesLocateEachOtherAndUnservedCoreFunctionsSaySo) {
  XrInstance instance = bare_instance({XR_MND_HEADLESS_EXTENSION_NAME});
  ASSERT_NE(instance, XR_NULL_HANDLE);
  auto system_info = xr::xr_struct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
  system_info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  ASSERT_EQ(xrGetSystem(instance, &system_info, &system), XR_SUCCESS);
  auto session_info = xr::xr_struct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
  session_info.systemId = system;
  XrSession session = XR_NULL_HANDLE;
  ASSERT_EQ(xrCreateSession(instance, &session_info, &session), XR_SUCCESS);
  auto local_info = xr::xr_struct<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
  local_info.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
  local_info.poseInReferenceSpace.orientation.w = 1.0f;
  auto moved_info = local_info;
  moved_info.poseInReferenceSpace.position = {0.1f, 0.2f, 0.3f};
  XrSpace local = XR_NULL_HANDLE, moved = XR_NULL_HANDLE;
  ASSERT_EQ(xrCreateReferenceSpace(session, &local_info, &local), XR_SUCCESS);
  ASSERT_EQ(xrCreateReferenceSpace(session, &moved_info, &moved), XR_SUCCESS);
  auto location = xr::xr_struct<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
  ASSERT_EQ(xrLocateSpace(moved, local, 1, &location), XR_SUCCESS);
  EXPECT_NEAR(location.pose.position.y, 0.2f, 1e-6);
  EXPECT_TRUE(location.locationFlags & XR_SPACE_LOCATION_POSITION_TRACKED_BIT);
  XrPath path = XR_NULL_PATH;
  EXPECT_EQ(xrStringToPath(instance, "/user/hand/left", &path), XR_ERROR_FUNCTION_UNSUPPORTED)
      << "a core function it does not serve returns, rather than crash";
  xrDestroyInstance(instance);  // its session and spaces with it
  EXPECT_EQ(validation_report().find("VALID_ERROR"), std::string::npos) << validation_report();
}

TEST_F(ThroughTheLoader, ARateOutOfRangeFailsTheInstance) {
  setenv("VCOCKPIT_XR_REPLAY_RATE", "1e300", 1);
  EXPECT_EQ(bare_instance({}), XR_NULL_HANDLE);
  setenv("VCOCKPIT_XR_REPLAY_RATE", "fast", 1);
  EXPECT_EQ(bare_instance({}), XR_NULL_HANDLE);
}

// What the bridge test's clean report rests on: with the layer on, a misuse is in its report.
TEST_F(ThroughTheLoader, TheValidationLayerReportsAMisuse) {
  auto create = xr::xr_struct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
  std::snprintf(create.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "misuse");
  create.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  XrInstance instance = XR_NULL_HANDLE;
  ASSERT_EQ(xrCreateInstance(&create, &instance), XR_SUCCESS);
  EXPECT_EQ(validation_report().find("VALID_ERROR"), std::string::npos) << validation_report();
  auto wrong = xr::xr_struct<XrSystemGetInfo>(XR_TYPE_INSTANCE_PROPERTIES);  // the wrong type
  wrong.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  EXPECT_NE(xrGetSystem(instance, &wrong, &system), XR_SUCCESS);
  EXPECT_NE(validation_report().find("[VALID_ERROR | VUID-XrSystemGetInfo-type-type | xrGetSystem]"),
            std::string::npos)
      << validation_report();
  xrDestroyInstance(instance);
}

}  // namespace
}  // namespace vcockpit::glove
