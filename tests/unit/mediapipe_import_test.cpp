// MediaPipe Hands world landmarks into hand-joints frames: a hand the model makes itself, written
// as the landmarker's JSON, imports to the right joints and retargets back to its angles; a bad
// file names the frame and the field.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "hand/config/hand_yaml.hpp"
#include "hand/tracking/mediapipe_import.hpp"
#include "hand/tracking/retarget.hpp"
#include "tests/support/process.hpp"

namespace vcockpit::hand::tracking {
namespace {

std::string source_dir() { return std::getenv("VCOCKPIT_SOURCE_DIR"); }

// MediaPipe's 21 landmarks of the model's hand at q (in xr space, about the hand's centre,
// MediaPipe's axes: x right, y down, z away from the camera).
nlohmann::json landmarks(const HandModel& model, const JointAngles& q) {
  HandLinkPoses P;
  forward_kinematics(model, q, P);
  std::vector<Eigen::Vector3d> points = {Eigen::Vector3d::Zero()};  // the wrist: H's origin
  for (int f = 0; f < kFingerCount; ++f) {
    const auto links = finger_links(static_cast<Finger>(f));
    for (Link l : links) points.push_back(P.X_HL[static_cast<std::size_t>(l)].translation());
    points.push_back(P.p_H_tip[static_cast<std::size_t>(f)]);
  }
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
  X_GH.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.2, 0.3, 0.9).normalized()).toRotationMatrix();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (auto& p : points) {
    p = R_G_xr().transpose() * (X_GH * p);
    centre += p / 21.0;
  }
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : points) {
    const Eigen::Vector3d c = p - centre;
    out.push_back({{"x", c.x()}, {"y", -c.y()}, {"z", -c.z()}});
  }
  return out;
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = test::make_temp_dir("mediapipe_import") + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(MediaPipeImport, TheModelsOwnHandImportsAndRetargetsBackToItsAngles) {
  const HandModel model = load_hand_model(source_dir() + "/config/hand.yaml");
  JointAngles q = model.rest_pose();
  q[static_cast<std::size_t>(Joint::kIndexMcp)] = 0.9;
  q[static_cast<std::size_t>(Joint::kMiddlePip)] = 1.1;
  q[static_cast<std::size_t>(Joint::kThumbIp)] = 0.6;
  nlohmann::json frames = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) {
    frames.push_back({{"timestamp_ms", 1000.0 + 33.3 * i},
                      {"worldLandmarks", {landmarks(model, q)}},
                      {"handednesses", {{{{"categoryName", "Right"}, {"score", 0.98}}}}}});
  }
  frames.push_back({{"timestamp_ms", 1200.0}, {"worldLandmarks", nlohmann::json::array()},
                    {"handednesses", nlohmann::json::array()}});
  const MediaPipeImport in = import_mediapipe(write("hand.json", frames.dump()));
  ASSERT_EQ(in.frames.size(), 3u);
  EXPECT_EQ(in.frames_without_hands, 1);
  EXPECT_EQ(in.frames[2].t_ns, 66'600'000);
  EXPECT_FALSE(in.frames[0].left_hand);
  EXPECT_TRUE(in.frames[0][XrJoint::kWrist].valid);
  EXPECT_FALSE(in.frames[0][XrJoint::kPalm].valid);
  EXPECT_FALSE(in.frames[0][XrJoint::kIndexMetacarpal].valid);
  // the index's knuckle to its tip: as long as the model's finger, whatever the axes
  const double reach = (in.frames[0][XrJoint::kIndexTip].p_m - in.frames[0][XrJoint::kIndexProximal].p_m).norm();
  HandLinkPoses P;
  forward_kinematics(model, q, P);
  EXPECT_NEAR(reach, (P.p_H_tip[1] - P.X_HL[static_cast<std::size_t>(Link::kIndexProximal)].translation()).norm(), 1e-12);

  Eigen::Isometry3d X_GS = Eigen::Isometry3d::Identity();
  X_GS.linear() = R_G_xr();
  Retargeter retarget(model);
  const RetargetResult& r = retarget.fit(to_cockpit(in.frames[0], X_GS));
  ASSERT_TRUE(r.placed) << "wrist, thumb base and knuckles place the palm";
  for (Joint j : {Joint::kIndexMcp, Joint::kMiddlePip, Joint::kThumbIp})
    EXPECT_NEAR(r.q_rad[static_cast<std::size_t>(j)], q[static_cast<std::size_t>(j)], 1e-3) << joint_name(j);
  for (double e : r.tip_error_m) EXPECT_LT(e, 1e-5);
}

TEST(MediaPipeImport, ABadFileNamesTheFrameAndTheField) {
  const auto error_of = [](const std::string& text) {
    try {
      import_mediapipe(write("bad.json", text));
    } catch (const JointsLogError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::string point = R"({"x":0.01,"y":0.02,"z":0.0})";
  std::string hand = "[";
  for (int k = 0; k < 21; ++k) hand += (k ? "," : "") + point;
  hand += "]";
  const std::string right = R"([[{"categoryName":"Right"}]])";
  EXPECT_EQ(error_of("[{\"timestamp_ms\":0,\"worldLandmarks\":[" + hand + "],\"handednesses\":" + right + "}]"),
            "(no error)");
  EXPECT_NE(error_of("{").find("bad.json: not JSON"), std::string::npos);
  EXPECT_NE(error_of("{\"hands\":1}").find("neither a list of frames"), std::string::npos);
  EXPECT_NE(error_of("[{\"worldLandmarks\":[]}]").find("frame 0: no 'timestamp_ms'"), std::string::npos);
  EXPECT_NE(error_of("[{\"timestamp_ms\":0,\"worldLandmarks\":[[" + point + "]],\"handednesses\":" + right + "}]")
                .find("frame 0: 'worldLandmarks[0]' is not 21 landmarks"),
            std::string::npos);
  std::string bad = hand;
  bad.replace(bad.find("0.02"), 4, "\"a\"");
  EXPECT_NE(error_of("[{\"timestamp_ms\":0,\"worldLandmarks\":[" + bad + "],\"handednesses\":" + right + "}]")
                .find("frame 0: 'worldLandmarks[0][0].y' is not a number"),
            std::string::npos);
  EXPECT_NE(error_of("[{\"timestamp_ms\":0,\"worldLandmarks\":[" + hand + "],\"handednesses\":[[{\"categoryName\":\"Both\"}]]}]")
                .find("'handednesses[0]' is 'Both', not Left or Right"),
            std::string::npos);
}

}  // namespace
}  // namespace vcockpit::hand::tracking
