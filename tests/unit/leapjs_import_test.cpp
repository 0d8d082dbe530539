// LeapJS playback JSON into hand-joints frames: the real "grab" recording (tests/data/real/README.md)
// imports whole, in metres, with Leap's fixed bones, and a bad file is an error naming the frame
// and the field.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <utility>
#include <vector>

#include "hand/tracking/leapjs_import.hpp"
#include "tests/support/process.hpp"

namespace vcockpit::hand::tracking {
namespace {

std::string source_dir() { return std::getenv("VCOCKPIT_SOURCE_DIR"); }

TEST(LeapJsImport, TheRealGrabRecordingImportsWholeWithFixedBones) {
  const LeapImport in = import_leapjs(source_dir() + "/tests/data/real/leap/grab.json");
  EXPECT_EQ(in.protocol_version, 6);
  EXPECT_EQ(in.source_frames, 374);
  ASSERT_EQ(in.frames.size(), 374u) << "one right hand in every frame";
  EXPECT_EQ(in.frames_out_of_order, 0);
  EXPECT_EQ(in.frames.front().t_ns, 0);
  EXPECT_NEAR(static_cast<double>(in.frames.back().t_ns) * 1e-9, 3.304, 0.001);  // as leap_grab.csv
  double shortest_m = 1.0, longest_m = 0.0;
  for (const JointsFrame& f : in.frames) {
    EXPECT_FALSE(f.left_hand);
    ASSERT_TRUE(f[XrJoint::kPalm].valid && f[XrJoint::kPalm].has_orientation);
    EXPECT_FALSE(f[XrJoint::kWrist].valid) << "not in protocol 6";
    EXPECT_FALSE(f[XrJoint::kIndexMetacarpal].valid);
    EXPECT_TRUE(f[XrJoint::kThumbMetacarpal].valid);
    for (int finger = 0; finger < 5; ++finger) {
      const XrFingerChain chain = xr_finger_chain(finger);
      EXPECT_TRUE(f[chain.joints[static_cast<std::size_t>(chain.count - 1)]].valid);
    }
    // the palm is within a hand's reach of the device, +y above it (mm -> m)
    EXPECT_GT(f[XrJoint::kPalm].p_m.y(), 0.05);
    EXPECT_LT(f[XrJoint::kPalm].p_m.norm(), 0.6);
    // Leap's hand model keeps its bones' lengths: the index's proximal phalanx
    const double bone_m = (f[XrJoint::kIndexIntermediate].p_m - f[XrJoint::kIndexProximal].p_m).norm();
    shortest_m = std::min(shortest_m, bone_m);
    longest_m = std::max(longest_m, bone_m);
    EXPECT_GT(f[XrJoint::kIndexTip].radius_m, 0.003);
    EXPECT_LT(f[XrJoint::kIndexTip].radius_m, 0.015);
  }
  EXPECT_GT(shortest_m, 0.02);
  EXPECT_LT(longest_m, 0.06);
  EXPECT_LT(longest_m - shortest_m, 1e-3);
  // the palm joint's -Z is the hand's direction toward the fingers: from the palm toward the
  // middle finger's knuckle
  const JointsFrame& f = in.frames.front();
  const Eigen::Vector3d toward_fingers = f[XrJoint::kPalm].q * Eigen::Vector3d(0, 0, -1);
  const Eigen::Vector3d to_knuckle = (f[XrJoint::kMiddleProximal].p_m - f[XrJoint::kPalm].p_m).normalized();
  EXPECT_GT(toward_fingers.dot(to_knuckle), 0.8);
}

TEST(LeapJsImport, ImportedFramesWriteAsAJointsLogAndReadBack) {
  const LeapImport in = import_leapjs(source_dir() + "/tests/data/real/leap/grab.json");
  const std::string path = test::make_temp_dir("leapjs_import") + "/grab.csv";
  write_joints_log(path, JointsSpace::kXr, in.frames, {"LeapJS grab"});
  const JointsLog log = read_joints_log(path);
  ASSERT_EQ(log.frames.size(), in.frames.size());
  EXPECT_EQ(log.frames[100][XrJoint::kIndexTip].p_m, in.frames[100][XrJoint::kIndexTip].p_m);
  EXPECT_EQ(log.lost_joints, 374 * 5) << "the wrist and four finger metacarpals";
}

// Every recording imports: its hands, each frame's palm and fingertips, in the device's reach.
TEST(LeapJsImport, EveryRecordingImports) {
  const std::vector<std::pair<const char*, std::size_t>> recordings = {
      {"grab", 374}, {"HandSplay-110fps", 288}, {"wave", 111}, {"three-claps", 2 * 403},
      {"gun", 134}, {"brian", 500}};
  for (const auto& [name, rows] : recordings) {
    SCOPED_TRACE(name);
    const LeapImport in = import_leapjs(source_dir() + "/tests/data/real/leap/" + name + ".json");
    EXPECT_EQ(in.frames.size(), rows);
    int left = 0;
    for (const JointsFrame& f : in.frames) {
      left += f.left_hand ? 1 : 0;
      EXPECT_TRUE(f[XrJoint::kPalm].valid);
      EXPECT_LT(f[XrJoint::kPalm].p_m.norm(), 0.8);
      EXPECT_LT((f[XrJoint::kIndexTip].p_m - f[XrJoint::kPalm].p_m).norm(), 0.2);
    }
    EXPECT_EQ(left, std::string(name) == "three-claps" ? 403 : 0);
  }
}

std::string error_of(const std::string& name, const std::string& text) {
  const std::string path = test::make_temp_dir("leapjs_import_bad") + "/" + name;
  std::ofstream(path) << text;
  try {
    import_leapjs(path);
  } catch (const JointsLogError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(LeapJsImport, ABadFileNamesTheFrameAndTheField) {
  const std::string hand =
      R"({"id":1,"type":"right","palmPosition":[0,200,0],"direction":[0,0,-1],"palmNormal":[0,-1,0]})";
  const std::string finger =
      R"({"handId":1,"type":1,"mcpPosition":[0,200,-40],"pipPosition":[0,200,-80],"dipPosition":[0,200,-105],"tipPosition":[0,200,-125],"width":17})";
  const auto frame = [&](int stamp, const std::string& h, const std::string& p) {
    return "{\"timestamp\":" + std::to_string(stamp) + ",\"hands\":[" + h + "],\"pointables\":[" + p + "]}";
  };
  const std::string good = "{\"frames\":[" + frame(1000, hand, finger) + "," + frame(9000, hand, finger) + "]}";
  EXPECT_EQ(error_of("good.json", good), "(no error)");
  EXPECT_NE(error_of("a.json", "{\"frames\": [").find("a.json: not JSON"), std::string::npos);
  EXPECT_NE(error_of("b.json", "{\"hands\": []}").find("b.json: no 'frames' array"), std::string::npos);
  std::string bad = hand;
  bad.replace(bad.find("[0,200,0]"), 9, "[0,\"x\",0]");
  EXPECT_NE(error_of("c.json", "{\"frames\":[" + frame(1000, hand, finger) + "," + frame(9000, bad, finger) + "]}")
                .find("c.json: frame 1: 'hands[0].palmPosition' is not a number"),
            std::string::npos);
  bad = hand;
  bad.replace(bad.find("right"), 5, "both");
  EXPECT_NE(error_of("d.json", "{\"frames\":[" + frame(1000, bad, finger) + "]}")
                .find("frame 0: 'hands[0].type' is 'both', not left or right"),
            std::string::npos);
  std::string bad_finger = finger;
  bad_finger.replace(bad_finger.find("\"pipPosition\":[0,200,-80],"), 26, "");
  EXPECT_NE(error_of("e.json", "{\"frames\":[" + frame(1000, hand, bad_finger) + "]}")
                .find("frame 0: no 'pointables[0].pipPosition'"),
            std::string::npos);
  EXPECT_NE(error_of("f.json", "{\"frames\":[{\"timestamp\":5,\"hands\":[]}]}").find("no frame has a hand"),
            std::string::npos);
}

TEST(LeapJsImport, FramesWhoseTimeDoesNotIncreaseAreSkippedAndCounted) {
  const std::string hand =
      R"({"id":1,"type":"left","palmPosition":[0,200,0],"direction":[0,0,-1],"palmNormal":[0,-1,0]})";
  const auto frame = [&](int stamp) {
    return "{\"timestamp\":" + std::to_string(stamp) + ",\"hands\":[" + hand + "],\"pointables\":[]}";
  };
  const std::string path = test::make_temp_dir("leapjs_import_order") + "/order.json";
  std::ofstream(path) << "{\"frames\":[" + frame(1000) + "," + frame(9000) + "," + frame(9000) + "," +
                             frame(5000) + "," + frame(17000) + ",{\"timestamp\":20000,\"hands\":[]}]}";
  const LeapImport in = import_leapjs(path);
  ASSERT_EQ(in.frames.size(), 3u);
  EXPECT_EQ(in.frames_out_of_order, 2);
  EXPECT_EQ(in.frames_without_hands, 1);
  EXPECT_EQ(in.frames[2].t_ns, 16'000'000);
  EXPECT_TRUE(in.frames[0].left_hand);
  EXPECT_FALSE(in.frames[0][XrJoint::kIndexTip].valid) << "no pointables: the fingers are lost";
}

}  // namespace
}  // namespace vcockpit::hand::tracking
