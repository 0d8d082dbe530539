// hand.yaml: the shipped hand loads, and every bad value is an error naming file, line and key.

#include "hand/config/hand_yaml.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/pose.hpp"
#include "common/yaml_config.hpp"
#include "tests/support/process.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit {
namespace {

using test::read_text;
using test::source_dir;

using hand::Finger;
using hand::HandModel;
using hand::Joint;
using hand::Link;

std::string shipped_path() {
  return source_dir() + "/config/hand.yaml";
}

std::string write_file(const std::string& name, const std::string& text) {
  return test::write_test_file("hand_config_test", name, text);
}

std::size_t idx(Link link) {
  return static_cast<std::size_t>(link);
}
std::size_t idx(Finger finger) {
  return static_cast<std::size_t>(finger);
}

// ---- a small valid hand, generated so each case can break one thing --------------------------

std::string row(double alpha_deg, double a_m, const std::string& joint, const std::string& link) {
  std::ostringstream out;
  out << "      - {alpha_deg: " << alpha_deg << ", a: " << a_m << ", d: 0, theta_offset_deg: 0";
  if (!joint.empty()) out << ", joint: " << joint;
  if (!link.empty()) out << ", link: " << link;
  out << "}\n";
  return out.str();
}

std::string finger(const std::string& name, const std::string& base, double radius_m,
                   const std::string& abduction, const std::vector<std::string>& joints,
                   const std::vector<double>& lengths_m) {
  std::ostringstream out;
  out << "  " << name << ":\n    base: " << base << "\n    radius: " << radius_m
      << "\n    chain:\n";
  out << row(-90, 0, abduction, name + "_proximal");
  out << row(0, lengths_m[0], joints[0], name + "_middle");
  out << row(0, lengths_m[1], joints[1], name + "_distal");
  out << row(0, lengths_m[2], joints[2], "");
  return out.str();
}

std::string valid_hand(const std::string& side = "right") {
  std::ostringstream out;
  out << "side: " << side << "\n"
      << "tracker:\n  euler: zyx\n  mount: back_of_hand\n"
      << "  X_GM: {position: [0, 0, 1], rpy_deg: [0, 0, 90]}\n"
      << "joints:\n";
  for (int j = 0; j < hand::kJointCount; ++j) {
    out << "  " << hand::joint_name(static_cast<Joint>(j))
        << ": {rest_deg: 0, min_deg: -20, max_deg: 90}\n";
  }
  out << "palm: {position: [0.045, 0, -0.015], rpy_deg: [0, 0, 0], size: [0.09, 0.085, 0.03]}\n"
      << "fingers:\n"
      << finger("thumb", "{position: [0.025, 0.02, -0.022], rpy_deg: [0, 0, 30]}", 0.0095,
                "thumb_abduction", {"thumb_rotation", "thumb_mcp", "thumb_ip"},
                {0.046, 0.032, 0.025})
      << finger("index", "{position: [0.088, 0.026, -0.015], rpy_deg: [0, 0, 0]}", 0.0085,
                "middle_index_abduction", {"index_mcp", "index_pip", "index_dip"},
                {0.046, 0.026, 0.018})
      << finger("middle", "{position: [0.09, 0.006, -0.015], rpy_deg: [0, 0, 0]}", 0.0088, "",
                {"middle_mcp", "middle_pip", "middle_dip"}, {0.050, 0.030, 0.020})
      << finger("ring", "{position: [0.085, -0.013, -0.015], rpy_deg: [0, 0, 0]}", 0.0082,
                "ring_middle_abduction", {"ring_mcp", "ring_pip", "ring_dip"},
                {0.045, 0.029, 0.0195})
      << finger("little", "{position: [0.078, -0.031, -0.015], rpy_deg: [0, 0, 0]}", 0.0075,
                "little_ring_abduction", {"little_mcp", "little_pip", "little_dip"},
                {0.036, 0.021, 0.0175});
  return out.str();
}

// ---- the shipped hand -----------------------------------------------------------------------

TEST(HandConfig, ShippedHandLoadsAsARightHandWithSaneRanges) {
  const HandModel model = load_hand_model(shipped_path());
  EXPECT_FALSE(model.left);
  EXPECT_EQ(model.tracker.euler_axes, "zyx");
  EXPECT_EQ(model.tracker.mount, hand::TrackerMount::kBackOfHand);
  for (int j = 0; j < hand::kJointCount; ++j) {
    const hand::JointRange& r = model.joints[j];
    const auto name = hand::joint_name(static_cast<Joint>(j));
    EXPECT_LT(r.min_rad, r.max_rad) << name;
    EXPECT_GE(r.rest_rad, r.min_rad) << name;
    EXPECT_LE(r.rest_rad, r.max_rad) << name;
    EXPECT_GE(r.min_rad, -M_PI / 2) << name;  // no anatomical channel turns more than 120 deg
    EXPECT_LE(r.max_rad, deg_to_rad(120)) << name;
  }
  EXPECT_NEAR(model.joints[static_cast<int>(Joint::kIndexMcp)].max_rad, deg_to_rad(90), 1e-12);
  // degrees in the file, radians in the struct
  EXPECT_NEAR(model.joints[static_cast<int>(Joint::kMiddlePip)].max_rad, deg_to_rad(110), 1e-12);
}

TEST(HandConfig, ShippedHandHasAdultAnthropometry) {
  const HandModel model = load_hand_model(shipped_path());
  const auto length = [&](Link link) { return model.capsules[idx(link)].length_m; };
  EXPECT_DOUBLE_EQ(length(Link::kIndexProximal), 0.046);
  EXPECT_DOUBLE_EQ(length(Link::kIndexMiddle), 0.026);
  EXPECT_DOUBLE_EQ(length(Link::kIndexDistal), 0.018);
  EXPECT_DOUBLE_EQ(length(Link::kMiddleProximal), 0.050);
  EXPECT_DOUBLE_EQ(length(Link::kThumbProximal), 0.046);
  EXPECT_DOUBLE_EQ(length(Link::kLittleDistal), 0.018);
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const auto name = hand::link_name(static_cast<Link>(l));
    EXPECT_GE(model.capsules[l].radius_m, 0.006) << name;
    EXPECT_LE(model.capsules[l].radius_m, 0.0105) << name;
    EXPECT_GT(model.capsules[l].length_m, 0.015) << name;
  }
  EXPECT_TRUE(model.palm_size_m.isApprox(Eigen::Vector3d(0.090, 0.085, 0.030), 1e-12));

  // hand length: wrist (H origin) to the middle fingertip of the flat hand, ~0.19 m
  hand::HandLinkPoses poses;
  hand::forward_kinematics(model, hand::JointAngles{}, poses);
  EXPECT_NEAR(poses.p_H_tip[idx(Finger::kMiddle)].x(), 0.19, 0.01);
  EXPECT_GT(poses.p_H_tip[idx(Finger::kThumb)].y(), 0.03);  // right hand: thumb on +y
}

// The 5th-percentile woman's and 95th-percentile man's hands: hand.yaml with every length along
// the hand scaled by hand length / 190 mm and every size across it by hand breadth / 85 mm
// (the files' sources), the same joints, ranges and tracker.
TEST(HandConfig, SmallAndLargeHandsScaleTheShippedHand) {
  const std::string dir = shipped_path().substr(0, shipped_path().rfind('/') + 1);
  const HandModel mid = load_hand_model(shipped_path());
  struct Size {
    const char* file;
    double length_m;
    double breadth_m;
  };
  for (const Size& size : {Size{"hand_small.yaml", 0.159, 0.069}, Size{"hand_large.yaml", 0.205, 0.095}}) {
    const HandModel model = load_hand_model(dir + size.file);
    const double s_length = size.length_m / 0.190, s_breadth = size.breadth_m / 0.085;
    EXPECT_FALSE(model.left) << size.file;
    hand::HandLinkPoses poses;
    hand::forward_kinematics(model, hand::JointAngles{}, poses);
    // hand length: wrist to the middle fingertip of the flat hand (0.19 m for hand.yaml)
    EXPECT_NEAR(poses.p_H_tip[idx(Finger::kMiddle)].x(), size.length_m, 0.002) << size.file;
    EXPECT_NEAR(model.palm_size_m.y(), s_breadth * mid.palm_size_m.y(), 1e-4) << size.file;
    for (int l = 1; l < hand::kLinkCount; ++l) {
      const auto name = hand::link_name(static_cast<Link>(l));
      EXPECT_NEAR(model.capsules[l].length_m, s_length * mid.capsules[l].length_m, 1e-4) << name;
      EXPECT_NEAR(model.capsules[l].radius_m, s_breadth * mid.capsules[l].radius_m, 1e-4) << name;
    }
    for (int j = 0; j < hand::kJointCount; ++j) {
      EXPECT_EQ(model.joints[j].min_rad, mid.joints[j].min_rad);
      EXPECT_EQ(model.joints[j].max_rad, mid.joints[j].max_rad);
      EXPECT_EQ(model.joints[j].rest_rad, mid.joints[j].rest_rad);
    }
    EXPECT_TRUE(model.tracker.X_GM.isApprox(mid.tracker.X_GM, 0));
  }
}

TEST(HandConfig, ShippedHandAsLeftIsItsMirrorImage) {
  std::string text = read_text(shipped_path());
  const auto at = text.find("\nside: right");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 12, "\nside: left");
  const HandModel left = parse_hand_model(ConfigNode::load_string(text, "hand_left.yaml"));
  const HandModel right = load_hand_model(shipped_path());
  EXPECT_TRUE(left.left);
  hand::HandLinkPoses pl, pr;
  hand::forward_kinematics(left, left.rest_pose(), pl);
  hand::forward_kinematics(right, right.rest_pose(), pr);
  for (int f = 0; f < hand::kFingerCount; ++f) {
    const Eigen::Vector3d& a = pl.p_H_tip[f];
    const Eigen::Vector3d& b = pr.p_H_tip[f];
    EXPECT_TRUE(a.isApprox(Eigen::Vector3d(b.x(), -b.y(), b.z()), 1e-12)) << f;
  }
  EXPECT_LT(pl.p_H_tip[idx(Finger::kThumb)].y(), -0.03);
}

TEST(HandConfig, SideLeftIsTheMirroredRightHand) {
  const HandModel right = parse_hand_model(ConfigNode::load_string(valid_hand("right"), "r.yaml"));
  const HandModel left = parse_hand_model(ConfigNode::load_string(valid_hand("left"), "l.yaml"));
  const HandModel expected = hand::mirrored(right);
  EXPECT_TRUE(left.left);
  EXPECT_FALSE(right.left);
  EXPECT_TRUE(left.X_HP.isApprox(expected.X_HP, 0.0));
  EXPECT_TRUE(left.tracker.X_GM.isApprox(right.tracker.X_GM, 0.0));
  for (int f = 0; f < hand::kFingerCount; ++f) {
    EXPECT_TRUE(left.fingers[f].X_HB.isApprox(expected.fingers[f].X_HB, 0.0));
    ASSERT_EQ(left.fingers[f].rows.size(), expected.fingers[f].rows.size());
    for (std::size_t i = 0; i < left.fingers[f].rows.size(); ++i) {
      EXPECT_EQ(left.fingers[f].rows[i].alpha_rad, expected.fingers[f].rows[i].alpha_rad);
      EXPECT_EQ(left.fingers[f].rows[i].scale, expected.fingers[f].rows[i].scale);
    }
  }
}

TEST(HandConfig, GeneratedHandIsValidAndLengthsComeFromTheNextRow) {
  const HandModel model = parse_hand_model(ConfigNode::load_string(valid_hand(), "ok.yaml"));
  EXPECT_DOUBLE_EQ(model.capsules[idx(Link::kRingDistal)].length_m, 0.0195);
  EXPECT_DOUBLE_EQ(model.capsules[idx(Link::kRingDistal)].radius_m, 0.0082);
  EXPECT_EQ(model.fingers[idx(Finger::kRing)].rows[0].link, static_cast<int>(Link::kRingProximal));
  EXPECT_EQ(model.fingers[idx(Finger::kMiddle)].rows[0].joint, -1);
  EXPECT_TRUE(model.tracker.X_GM.translation().isApprox(Eigen::Vector3d(0, 0, 1), 1e-12));
}

// ---- bad input ------------------------------------------------------------------------------

struct BadCase {
  std::string name;  // file name and test label
  std::string find;  // text of the valid hand to replace (must occur exactly once)
  std::string replace;
  std::string marker;   // text on the line the error must name (in the broken file)
  std::string key;      // key path the error must name
  std::string message;  // part of the message
};

std::size_t line_of(const std::string& text, std::size_t pos) {
  return 1 + static_cast<std::size_t>(
                 std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

void expect_error(const BadCase& c) {
  SCOPED_TRACE(c.name);
  std::string text = valid_hand();
  const auto at = text.find(c.find);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(text.find(c.find, at + 1), std::string::npos) << "ambiguous: " << c.find;
  text.replace(at, c.find.size(), c.replace);
  const auto marker_at = text.find(c.marker);
  ASSERT_NE(marker_at, std::string::npos);
  const std::string path = write_file(c.name + ".yaml", text);
  std::string msg = "(no error)";
  try {
    load_hand_model(path);
  } catch (const ConfigError& e) {
    msg = e.what();
  }
  const std::string where = path + ":" + std::to_string(line_of(text, marker_at)) + ":";
  EXPECT_NE(msg.find(where), std::string::npos) << "want " << where << " in: " << msg;
  EXPECT_NE(msg.find(": " + c.key + ": "), std::string::npos)
      << "want key " << c.key << " in: " << msg;
  EXPECT_NE(msg.find(c.message), std::string::npos) << "want '" << c.message << "' in: " << msg;
}

TEST(HandConfig, EveryBadValueNamesFileLineAndKey) {
  const std::vector<BadCase> cases = {
      {"unknown_top_key", "side: right\n", "side: right\nsides: left\n", "sides:", "sides",
       "unknown key 'sides'"},
      {"bad_side", "side: right", "side: both", "side: both", "side", "right or left"},
      {"unknown_row_key", "joint: index_pip,", "joint: index_pip, scael: 1,", "scael",
       "fingers.index.chain[2].scael", "unknown key"},
      {"missing_row_field", "a: 0.026, d: 0, ", "a: 0.026, ", "a: 0.026", "fingers.index.chain[2]",
       "missing required key 'd'"},
      {"missing_finger_field", "    radius: 0.0085\n", "", "base: {position: [0.088",
       "fingers.index", "missing required key 'radius'"},
      {"missing_joint", "  index_dip: {rest_deg: 0, min_deg: -20, max_deg: 90}\n", "",
       "thumb_rotation: {", "joints", "missing joint 'index_dip'"},
      {"unknown_joint_key", "  index_dip: {", "  index_dpi: {", "index_dpi", "joints.index_dpi",
       "unknown key 'index_dpi'"},
      {"unknown_row_joint", "joint: index_dip}", "joint: index_dipp}", "index_dipp",
       "fingers.index.chain[3].joint", "unknown joint channel 'index_dipp'"},
      {"wrist_in_row", "joint: index_dip}", "joint: wrist_pitch}", "wrist_pitch}",
       "fingers.index.chain[3].joint", "moves the whole hand"},
      {"unknown_link", "link: index_distal", "link: index_tip", "index_tip",
       "fingers.index.chain[2].link", "unknown link 'index_tip'"},
      {"link_of_other_finger", "link: index_distal", "link: middle_distal", "link: middle_distal}",
       "fingers.index.chain[2].link", "unknown link 'middle_distal' for the index"},
      {"link_out_of_order", "link: index_middle", "link: index_distal", "link: index_distal",
       "fingers.index.chain[1].link", "once each, in order"},
      {"link_missing", ", link: index_distal", "", "joint: middle_index_abduction",
       "fingers.index.chain", "no row has link 'index_distal'"},
      {"min_above_max", "index_mcp: {rest_deg: 0, min_deg: -20",
       "index_mcp: {rest_deg: 0, min_deg: 95", "index_mcp:", "joints.index_mcp.min_deg",
       "greater than max_deg"},
      {"rest_outside", "index_pip: {rest_deg: 0,", "index_pip: {rest_deg: 100,",
       "index_pip:", "joints.index_pip.rest_deg", "outside [-20, 90]"},
      {"negative_radius", "radius: 0.0085", "radius: -0.0085", "radius: -", "fingers.index.radius",
       "must be positive"},
      {"negative_length", "a: 0.026", "a: -0.026", "a: -0.026", "fingers.index.chain[2].a",
       "must be >= 0"},
      {"zero_phalanx_length", "a: 0.018", "a: 0", "joint: index_dip", "fingers.index.chain[3].a",
       "length of index_distal"},
      {"not_a_number", "a: 0.046, d: 0, theta_offset_deg: 0, joint: index_mcp",
       "a: long, d: 0, theta_offset_deg: 0, joint: index_mcp", "a: long",
       "fingers.index.chain[1].a", "expected a number"},
      {"negative_palm_size", "size: [0.09,", "size: [-0.09,", "size: [-0.09", "palm.size",
       "must be positive"},
      {"bad_euler", "euler: zyx", "euler: zzx", "euler: zzx", "tracker.euler", "bad Euler axes"},
      {"unknown_mount", "mount: back_of_hand", "mount: elbow", "mount: elbow", "tracker.mount",
       "unknown tracker mount 'elbow'"},
      {"scale_without_joint", "link: middle_proximal}", "link: middle_proximal, scale: 2}",
       "scale: 2", "fingers.middle.chain[0].scale", "needs a joint"},
      {"unknown_finger", "  little:\n", "  pinky:\n", "pinky:", "fingers.pinky",
       "unknown key 'pinky'"},
      {"bad_pose_list", "rpy_deg: [0, 0, 30]", "rpy_deg: [0, 30]", "rpy_deg: [0, 30]",
       "fingers.thumb.base.rpy_deg", "list of 3 numbers"},
  };
  for (const BadCase& c : cases)
    expect_error(c);
}

TEST(HandConfig, LinkOnTheLastRowIsExplained) {
  // the common slip: tagging each phalanx on its own joint's row instead of the row before
  std::string text = valid_hand();
  const std::string good = row(-90, 0, "middle_index_abduction", "index_proximal") +
                           row(0, 0.046, "index_mcp", "index_middle") +
                           row(0, 0.026, "index_pip", "index_distal") +
                           row(0, 0.018, "index_dip", "");
  const std::string slip =
      row(-90, 0, "middle_index_abduction", "") + row(0, 0.046, "index_mcp", "index_proximal") +
      row(0, 0.026, "index_pip", "index_middle") + row(0, 0.018, "index_dip", "index_distal");
  const auto at = text.find(good);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, good.size(), slip);
  std::string msg = "(no error)";
  try {
    parse_hand_model(ConfigNode::load_string(text, "slip.yaml"));
  } catch (const ConfigError& e) {
    msg = e.what();
  }
  const std::string where =
      "slip.yaml:" + std::to_string(line_of(text, text.find("index_distal}"))) + ":";
  EXPECT_NE(msg.find(where), std::string::npos) << msg;
  EXPECT_NE(msg.find(": fingers.index.chain[3].link: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("needs a next row"), std::string::npos) << msg;
}

// A finger's chain holds at most 16 rows (the proxy's chain cache, hand::FingerChainCache): 17
// (the index's 4 and 13 fixed ones after them, each valid alone) are refused, naming the chain.
TEST(HandConfig, AChainOfMoreThanSixteenRowsIsRefused) {
  std::string text = valid_hand();
  const std::string last = row(0, 0.018, "index_dip", "");
  const auto at = text.find(last);
  ASSERT_NE(at, std::string::npos);
  std::string longer = last;
  for (int i = 0; i < 12; ++i) longer += row(0, 0.0, "", "");
  // 16 rows: loads
  text.replace(at, last.size(), longer);
  EXPECT_NO_THROW(parse_hand_model(ConfigNode::load_string(text, "sixteen.yaml")));
  // 17: refused
  text.replace(at, longer.size(), longer + row(0, 0.0, "", ""));
  std::string msg = "(no error)";
  try {
    parse_hand_model(ConfigNode::load_string(text, "seventeen.yaml"));
  } catch (const ConfigError& e) {
    msg = e.what();
  }
  EXPECT_NE(msg.find("seventeen.yaml:"), std::string::npos) << msg;
  EXPECT_NE(msg.find(": fingers.index.chain: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("at most 16 rows"), std::string::npos) << msg;
}

TEST(HandConfig, MissingFileIsAnError) {
  EXPECT_THROW(load_hand_model("/nonexistent_vcockpit_dir/none.yaml"), ConfigError);
}

}  // namespace
}  // namespace vcockpit
