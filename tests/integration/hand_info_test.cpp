// cockpit/hand_info end to end: the image generator draws the hand the physics node simulates.
// A physics node whose scene names a hand file with every finger capsule radius doubled, a glove
// driver holding the hand still in front of a camera looking straight down on it, and an image
// generator given no hand file: across each finger's middle and distal phalanx the rendered
// finger is as wide as the doubled radius projects to (twice the default hand's, which a run with
// the shipped hand shows at its own radius). The image generator no longer takes --hand-config.

#include <gtest/gtest.h>

#include <cmath>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "hand/hand_model.hpp"
#include "hand/config/hand_yaml.hpp"
#include "image_generator/node/hmd_yaml.hpp"
#include "image_generator/render/camera.hpp"
#include "tests/support/monitor_log.hpp"
#include "tests/support/png_read.hpp"
#include "tests/support/process.hpp"
#include "tests/support/process_test.hpp"
#include "tests/support/test_env.hpp"

namespace vcockpit::test {
namespace {

using hand::Joint;
using hand::Link;

// Straight above the held hand, looking down (head x -> world -z), image up = world +x. 480x480
// per eye, 60 deg square field: about 1000 px per metre at the back of the hand.
constexpr const char* kTopDownHmd = R"(ipd_m: 0.063
width_px: 480
height_px: 480
near_m: 0.05
far_m: 20.0
fov_deg:
  left_eye:  {left: -30, right: 30, up: 30, down: -30}
  right_eye: {left: -30, right: 30, up: 30, down: -30}
head: {position: [0.34, 0.26, 1.40], rpy_deg: [0, 90, 0]}
)";

// The wrist in free air over the cockpit's left side (nothing near it: the console and its
// objects are at y < -0.15), palm down, fingers straight along +x and spread 20 deg apart so
// that even doubled fingers stand clear of each other past their proximal phalanges.
const Eigen::Vector3d kWrist_G(0.25, 0.25, 1.0);
constexpr double kSpreadDeg = 20.0;
constexpr const char* kHoldScript = R"(rate_hz: 200
shapes:
  spread: {thumb_rotation: 0, thumb_mcp: 0, thumb_ip: 0, thumb_abduction: 20,
           index_mcp: 0, index_pip: 0, index_dip: 0, middle_mcp: 0, middle_pip: 0, middle_dip: 0,
           middle_index_abduction: 20, ring_mcp: 0, ring_pip: 0, ring_dip: 0,
           ring_middle_abduction: 20, little_mcp: 0, little_pip: 0, little_dip: 0,
           little_ring_abduction: 20, palm_arch: 0}
keyframes:
  - {t_s: 0.0, position: [0.25, 0.25, 1.0], rpy_deg: [0, 0, 0], shape: spread}
  - {t_s: 120.0}
)";

// The script's joint angles as the glove driver sends them (the rest pose, then the shape).
hand::JointAngles spread_pose(const hand::HandModel& model) {
  hand::JointAngles q = model.rest_pose();
  for (Joint j : {Joint::kThumbRotation, Joint::kThumbMcp, Joint::kThumbIp, Joint::kIndexMcp,
                  Joint::kIndexPip, Joint::kIndexDip, Joint::kMiddleMcp, Joint::kMiddlePip,
                  Joint::kMiddleDip, Joint::kRingMcp, Joint::kRingPip, Joint::kRingDip,
                  Joint::kLittleMcp, Joint::kLittlePip, Joint::kLittleDip, Joint::kPalmArch}) {
    q[static_cast<int>(j)] = 0.0;
  }
  for (Joint j : {Joint::kThumbAbduction, Joint::kMiddleIndexAbduction,
                  Joint::kRingMiddleAbduction, Joint::kLittleRingAbduction}) {
    q[static_cast<int>(j)] = kSpreadDeg * M_PI / 180.0;
  }
  return q;
}

// hand.yaml with every `radius:` value (one number or [proximal, middle, distal]) doubled.
// Numbers are parsed with strtod (no <regex>: GCC 12 warns inside it under -O2 + sanitizers).
std::string with_doubled_radii(const std::string& yaml) {
  std::istringstream in(yaml);
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line)) {
    const auto key = line.find("radius:");
    if (key != std::string::npos && line.find_first_not_of(' ') == key) {
      std::string value = line.substr(key + 7);
      std::string comment;
      if (const auto hash = value.find('#'); hash != std::string::npos) {
        comment = value.substr(hash);
        value.resize(hash);
      }
      std::string doubled;
      const char* p = value.c_str();
      while (*p != '\0') {
        if (std::isdigit(static_cast<unsigned char>(*p)) || *p == '.') {
          char* end = nullptr;
          const double number = std::strtod(p, &end);
          char buf[32];
          std::snprintf(buf, sizeof buf, "%.17g", 2.0 * number);
          doubled += buf;
          p = end;
        } else {
          doubled += *p++;
        }
      }
      line = line.substr(0, key + 7) + doubled + comment;
    }
    out << line << '\n';
  }
  return out.str();
}

bool is_skin(const std::array<int, 4>& px) {
  // the hand's skin colour (0.85, 0.66, 0.55) lit, against the grey floor (0.22, 0.22, 0.24)
  return px[0] > px[2] + 25 && px[1] > px[2] + 5 && px[0] > 60;
}

// One phalanx crossed at its middle, perpendicular to its axis in the image.
struct Crossing {
  Link link;
  double expected_px = 0;  // the capsule's diameter as the camera model projects it
  double measured_px = 0;  // the run of skin pixels through the middle, along that direction
};

class HandInfoTest : public ProcessTest {
 protected:
  void SetUp() override {
    ProcessTest::SetUp();
    std::ofstream(dir_ + "/hmd.yaml") << kTopDownHmd;
    std::ofstream(dir_ + "/hold.yaml") << kHoldScript;
  }

  // Runs physics_node (with `scene`), a glove driver holding the hand and an image generator;
  // returns the left-eye snapshot of a frame drawn with the hand, or an empty image.
  RgbaImage render_hand(const std::string& name, const std::string& scene) {
    const std::string out = dir_ + "/" + name;
    ChildProcess monitor =
        start("test_cockpit_monitor", {"--out", out + "_monitor.txt"}, name + "_monitor.log");
    ChildProcess physics = start("physics_node", {"--scene", scene}, name + "_physics.log");
    ChildProcess glove = start("glove_driver", {"--source", "synthetic", "--script",
                                                dir_ + "/hold.yaml"},
                               name + "_glove.log");
    EXPECT_TRUE(wait_for_line(out + "_monitor.txt", "tracking=1", 30 * kSecond))
        << text(name + "_physics.log") << text(name + "_glove.log");
    ChildProcess ig = start("image_generator",
                            {"--hmd", dir_ + "/hmd.yaml", "--frames", "10", "--fps", "20", "--out",
                             out + "_frames", "--snapshot-every", "9", "--snapshot-layout", "left"},
                            name + "_ig.log");
    EXPECT_EQ(ig.wait(60 * kSecond), 0) << text(name + "_ig.log");
    EXPECT_EQ(glove.stop(), 0) << text(name + "_glove.log");
    EXPECT_EQ(physics.stop(), 0) << text(name + "_physics.log");
    EXPECT_EQ(monitor.stop(), 0);
    // the hand drawn in the snapshot, its palm where the script holds it (snapshots.csv: frame,
    // sim_time_ns, held object and its position, palm position)
    std::ifstream index(out + "_frames/snapshots.csv");
    std::string line, last;
    while (std::getline(index, line)) last = line;
    unsigned long long frame = 0;
    long long sim_ns = 0;
    int held = 0;
    double hx, hy, hz;
    Eigen::Vector3d palm_G;
    EXPECT_EQ(std::sscanf(last.c_str(), "%llu,%lld,%d,%lf,%lf,%lf,%lf,%lf,%lf", &frame, &sim_ns,
                          &held, &hx, &hy, &hz, &palm_G.x(), &palm_G.y(), &palm_G.z()),
              9)
        << last;
    EXPECT_EQ(frame, 9u) << last;
    const Eigen::Vector3d expected_palm_G =
        kWrist_G + load_hand_model(config_path("hand.yaml")).X_HP.translation();
    EXPECT_LT((palm_G - expected_palm_G).norm(), 1e-5)
        << "no hand in the snapshot: " << last << "\n" << text(name + "_ig.log");
    RgbaImage image;
    EXPECT_TRUE(read_png(out + "_frames/frame_000009_left.png", image)) << text(name + "_ig.log");
    return image;
  }

  // Crosses the middle and distal phalanx of every finger in `image`, with the model's radii.
  std::vector<Crossing> cross_fingers(const RgbaImage& image, const hand::HandModel& model) {
    const HmdSetup hmd = load_hmd_config(dir_ + "/hmd.yaml");
    hand::HandLinkPoses poses;
    hand::forward_kinematics(model, spread_pose(model), poses);
    const Eigen::Isometry3d X_GH{Eigen::Translation3d(kWrist_G)};
    const Eigen::Vector3d view_G = hmd.X_GHead.linear() * Eigen::Vector3d::UnitX();
    std::vector<Crossing> crossings;
    for (Link link : {Link::kIndexMiddle, Link::kIndexDistal, Link::kMiddleMiddle,
                      Link::kMiddleDistal, Link::kRingMiddle, Link::kRingDistal,
                      Link::kLittleMiddle, Link::kLittleDistal}) {
      const auto l = static_cast<std::size_t>(link);
      const hand::Capsule& c = model.capsules[l];
      const Eigen::Isometry3d X_GL = X_GH * poses.X_HL[l];
      const Eigen::Vector3d mid_G = X_GL * Eigen::Vector3d(0.5 * c.length_m, 0, 0);
      const Eigen::Vector3d across_G =
          (X_GL.linear() * Eigen::Vector3d::UnitX()).cross(view_G).normalized();
      Eigen::Vector2d mid, a, b;
      EXPECT_TRUE(render::project_to_pixel(hmd.hmd, render::Eye::kLeft, hmd.X_GHead, mid_G, mid));
      EXPECT_TRUE(render::project_to_pixel(hmd.hmd, render::Eye::kLeft, hmd.X_GHead,
                                           mid_G + c.radius_m * across_G, a));
      EXPECT_TRUE(render::project_to_pixel(hmd.hmd, render::Eye::kLeft, hmd.X_GHead,
                                           mid_G - c.radius_m * across_G, b));
      Crossing crossing{link, (a - b).norm(), 0.0};
      const Eigen::Vector2d step = (a - b).normalized() * 0.25;  // quarter-pixel steps
      auto skin_at = [&](const Eigen::Vector2d& p) {
        const int col = static_cast<int>(p.x()), row = static_cast<int>(p.y());
        if (col < 0 || row < 0 || col >= image.width || row >= image.height) return false;
        return is_skin(image.at(col, row));
      };
      if (skin_at(mid)) {
        int steps = 1;
        for (Eigen::Vector2d p = mid + step; skin_at(p) && steps < 4000; p += step) ++steps;
        for (Eigen::Vector2d p = mid - step; skin_at(p) && steps < 4000; p -= step) ++steps;
        crossing.measured_px = steps * 0.25;
      }
      crossings.push_back(crossing);
    }
    return crossings;
  }
};

TEST_F(HandInfoTest, ImageGeneratorDrawsTheHandThePhysicsNodeSimulates) {
  // the physics node's scene: the shipped cockpit, its hand file replaced by a wide one
  const std::string cockpit = read_text(config_path("cockpit.yaml"));
  // (its hands on one line: the right hand's file and its mirror image on the left)
  const auto at = cockpit.find("\nhands: [hand.yaml,");
  ASSERT_NE(at, std::string::npos) << "config/cockpit.yaml names its hands on one line";
  const auto end = cockpit.find('\n', at + 1);
  std::string wide_scene = cockpit;
  wide_scene.replace(at, end - at, "\nhands: [wide_hand.yaml, {file: wide_hand.yaml, side: left}]");
  std::ofstream(dir_ + "/cockpit.yaml") << cockpit_yaml_models_absolute(wide_scene);
  const std::string shipped_hand = read_text(config_path("hand.yaml"));
  std::ofstream(dir_ + "/wide_hand.yaml") << with_doubled_radii(shipped_hand);

  const hand::HandModel normal = load_hand_model(config_path("hand.yaml"));
  const hand::HandModel wide = load_hand_model(dir_ + "/wide_hand.yaml");
  for (int l = 1; l < hand::kLinkCount; ++l) {
    ASSERT_DOUBLE_EQ(wide.capsules[l].radius_m, 2.0 * normal.capsules[l].radius_m) << l;
    ASSERT_EQ(wide.capsules[l].length_m, normal.capsules[l].length_m) << l;
  }
  ASSERT_EQ(wide.palm_size_m, normal.palm_size_m);

  const RgbaImage wide_image = render_hand("wide", dir_ + "/cockpit.yaml");
  ASSERT_EQ(wide_image.width, 480) << text("wide_ig.log");
  EXPECT_NE(text("wide_ig.log").find("hand 0 (right) from cockpit/hand_info"), std::string::npos)
      << text("wide_ig.log");
  const RgbaImage normal_image = render_hand("normal", config_path("cockpit.yaml"));
  ASSERT_EQ(normal_image.width, 480) << text("normal_ig.log");

  const auto wide_fingers = cross_fingers(wide_image, wide);
  const auto normal_fingers = cross_fingers(normal_image, normal);
  for (std::size_t i = 0; i < wide_fingers.size(); ++i) {
    const Crossing& w = wide_fingers[i];
    const Crossing& n = normal_fingers[i];
    const std::string link(hand::link_name(w.link));
    std::printf("%-14s  default hand %5.1f px (projected %5.1f)   wide hand %5.1f px (projected "
                "%5.1f)\n",
                link.c_str(), n.measured_px, n.expected_px, w.measured_px, w.expected_px);
    // each as wide as its own hand's capsule projects to (edges shade off: a few px)
    EXPECT_NEAR(n.measured_px, n.expected_px, 0.2 * n.expected_px + 2.0) << link;
    EXPECT_NEAR(w.measured_px, w.expected_px, 0.2 * w.expected_px + 2.0) << link;
    // and the simulated hand's fingers are the doubled ones
    ASSERT_GT(n.measured_px, 0.0) << link;
    EXPECT_NEAR(w.measured_px / n.measured_px, 2.0, 0.35) << link;
  }
}

TEST_F(HandInfoTest, ImageGeneratorTakesNoHandFile) {
  expect_each_refused("image_generator",
                      {{{"--hand-config", config_path("hand.yaml")}, "--hand-config"}});
}

}  // namespace
}  // namespace vcockpit::test
