#include "hand/config/hand_yaml.hpp"

#include <sstream>
#include <utility>

#include "common/pose.hpp"
#include "common/yaml_config.hpp"

namespace vcockpit {
namespace {

using hand::DhRow;
using hand::Finger;
using hand::HandModel;
using hand::Joint;
using hand::Link;

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// expect_keys needs an initializer list; expand the 22 channel names into one at compile time so
// the names stay defined in hand_joints.cpp only.
template <std::size_t... I>
void expect_joint_keys(const ConfigNode& node, std::index_sequence<I...>) {
  node.expect_keys({hand::joint_name(static_cast<Joint>(I))...});
}

int link_index(std::string_view name) {
  for (int i = 0; i < hand::kLinkCount; ++i) {
    if (hand::link_name(static_cast<Link>(i)) == name) return i;
  }
  return -1;
}

std::string finger_link_list(Finger finger) {
  std::string list;
  for (Link link : hand::finger_links(finger)) {
    list += (list.empty() ? "" : ", ") + std::string(hand::link_name(link));
  }
  return list;
}

double positive(const ConfigNode& node, const std::string& what) {
  const double value = node.as_double();
  if (!(value > 0.0)) node.fail(what + " must be positive, got " + format_number(value));
  return value;
}

Eigen::Isometry3d parse_pose(const ConfigNode& node) {
  node.expect_keys({"position", "rpy_deg"});
  return pose_from_position_rpy_deg(node["position"].as_doubles<3>(),
                                    node["rpy_deg"].as_doubles<3>());
}

bool parse_side_is_left(const ConfigNode& node) {
  const std::string side = node.as_string();
  if (side != "right" && side != "left") node.fail("expected right or left, got '" + side + "'");
  return side == "left";
}

hand::TrackerConfig parse_tracker(const ConfigNode& node) {
  node.expect_keys({"euler", "mount", "X_GM"});
  hand::TrackerConfig tracker;
  const ConfigNode euler = node["euler"];
  tracker.euler_axes = euler.as_string();
  if (!is_valid_euler_axes(tracker.euler_axes)) {
    euler.fail("bad Euler axes '" + tracker.euler_axes +
               "' (three of x, y, z, no axis repeated next to itself, e.g. zyx)");
  }
  const ConfigNode mount = node["mount"];
  const std::string mount_name = mount.as_string();
  if (mount_name == "back_of_hand") {
    tracker.mount = hand::TrackerMount::kBackOfHand;
  } else if (mount_name == "forearm") {
    tracker.mount = hand::TrackerMount::kForearm;
  } else {
    mount.fail("unknown tracker mount '" + mount_name + "' (back_of_hand or forearm)");
  }
  tracker.X_GM = parse_pose(node["X_GM"]);
  return tracker;
}

hand::JointRange parse_range(const ConfigNode& node) {
  node.expect_keys({"rest_deg", "min_deg", "max_deg"});
  const double rest_deg = node.get_double("rest_deg");
  const double min_deg = node.get_double("min_deg");
  const double max_deg = node.get_double("max_deg");
  if (min_deg > max_deg) {
    node["min_deg"].fail("min_deg " + format_number(min_deg) + " is greater than max_deg " +
                         format_number(max_deg));
  }
  if (rest_deg < min_deg || rest_deg > max_deg) {
    node["rest_deg"].fail("rest_deg " + format_number(rest_deg) + " is outside [" +
                          format_number(min_deg) + ", " + format_number(max_deg) + "]");
  }
  return {deg_to_rad(rest_deg), deg_to_rad(min_deg), deg_to_rad(max_deg)};
}

void parse_joints(const ConfigNode& node,
                  std::array<hand::JointRange, hand::kJointCount>& out) {
  expect_joint_keys(node, std::make_index_sequence<hand::kJointCount>{});
  for (int j = 0; j < hand::kJointCount; ++j) {
    const std::string name(hand::joint_name(static_cast<Joint>(j)));
    const auto range = node.find(name);
    if (!range) node.fail("missing joint '" + name + "' (every one of the 22 channels is needed)");
    out[j] = parse_range(*range);
  }
}

void parse_palm(const ConfigNode& node, HandModel& model) {
  node.expect_keys({"position", "rpy_deg", "size", "tracking_point", "wrist_tracking_point"});
  model.X_HP =
      pose_from_position_rpy_deg(node["position"].as_doubles<3>(), node["rpy_deg"].as_doubles<3>());
  model.p_H_palm_joint = model.X_HP.translation();
  if (const auto point = node.find("tracking_point")) {
    const auto p = point->as_doubles<3>();
    model.p_H_palm_joint = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  if (const auto point = node.find("wrist_tracking_point")) {
    const auto p = point->as_doubles<3>();
    model.p_H_wrist_joint = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  const ConfigNode size = node["size"];
  const auto size_m = size.as_doubles<3>();
  for (double s : size_m) {
    if (!(s > 0.0)) size.fail("palm size must be positive, got " + format_number(s));
  }
  model.palm_size_m = Eigen::Vector3d(size_m[0], size_m[1], size_m[2]);
}

// One radius for all three phalanges, or [proximal, middle, distal].
std::array<double, 3> parse_radii(const ConfigNode& node) {
  if (node.is_scalar()) {
    const double r = positive(node, "radius");
    return {r, r, r};
  }
  const auto radii = node.as_doubles<3>();
  for (double r : radii) {
    if (!(r > 0.0)) node.fail("radius must be positive, got " + format_number(r));
  }
  return radii;
}

int parse_row_joint(const ConfigNode& node) {
  const std::string name = node.as_string();
  const int joint = hand::joint_index(name);
  if (joint < 0) node.fail("unknown joint channel '" + name + "'");
  // the wrist turns the whole hand (see X_MH_from_tracker), never one finger
  if (joint == static_cast<int>(Joint::kWristPitch) ||
      joint == static_cast<int>(Joint::kWristYaw)) {
    node.fail("'" + name + "' moves the whole hand (tracker mount), not a finger row");
  }
  return joint;
}

int parse_row_link(const ConfigNode& node, Finger finger) {
  const std::string name = node.as_string();
  const int link = link_index(name);
  Finger owner{};
  if (link < 0 || !hand::finger_of(static_cast<Link>(link), owner) || owner != finger) {
    node.fail("unknown link '" + name + "' for the " + std::string(hand::finger_name(finger)) +
              " (one of: " + finger_link_list(finger) + ")");
  }
  return link;
}

DhRow parse_row(const ConfigNode& node, Finger finger) {
  node.expect_keys({"alpha_deg", "a", "d", "theta_offset_deg", "joint", "scale", "link"});
  DhRow row;
  row.alpha_rad = deg_to_rad(node.get_double("alpha_deg"));
  row.a_m = node.get_double("a");
  if (row.a_m < 0.0)
    node["a"].fail("a is a length and must be >= 0, got " + format_number(row.a_m));
  row.d_m = node.get_double("d");
  row.theta_offset_rad = deg_to_rad(node.get_double("theta_offset_deg"));
  if (auto joint = node.find("joint")) row.joint = parse_row_joint(*joint);
  if (auto scale = node.find("scale")) {
    if (row.joint < 0) scale->fail("scale needs a joint to scale");
    row.scale = scale->as_double();
  }
  if (auto link = node.find("link")) row.link = parse_row_link(*link, finger);
  return row;
}

// A row tagged `link` outputs that phalanx's proximal joint frame; the next row turns it and its
// `a` is the phalanx's length (the single source of truth for capsule lengths).
void check_links(const std::vector<ConfigNode>& row_nodes, Finger finger, HandModel& model,
                 const std::array<double, 3>& radii, const ConfigNode& chain_node) {
  const auto links = hand::finger_links(finger);
  const auto& rows = model.fingers[static_cast<std::size_t>(finger)].rows;
  std::size_t seen = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].link < 0) continue;
    const ConfigNode link_node = row_nodes[i]["link"];
    if (seen >= links.size() || rows[i].link != static_cast<int>(links[seen])) {
      link_node.fail("links must appear once each, in order " + finger_link_list(finger));
    }
    if (i + 1 == rows.size()) {
      link_node.fail(
          "a phalanx starts at this row's output and needs a next row to turn it and "
          "give its length (a); tag the row before its joint's row");
    }
    const double length_m = rows[i + 1].a_m;
    if (!(length_m > 0.0)) {
      row_nodes[i + 1]["a"].fail("this row's a is the length of " +
                                 std::string(hand::link_name(links[seen])) +
                                 " and must be positive");
    }
    model.capsules[static_cast<std::size_t>(links[seen])] = {radii[seen], length_m};
    ++seen;
  }
  if (seen < links.size()) {
    chain_node.fail("no row has link '" + std::string(hand::link_name(links[seen])) + "'");
  }
}

void parse_finger(const ConfigNode& node, Finger finger, HandModel& model) {
  node.expect_keys({"base", "radius", "chain"});
  hand::FingerChain& chain = model.fingers[static_cast<std::size_t>(finger)];
  chain.X_HB = parse_pose(node["base"]);
  const auto radii = parse_radii(node["radius"]);
  const ConfigNode chain_node = node["chain"];
  const std::vector<ConfigNode> row_nodes = chain_node.elements();
  if (row_nodes.empty()) chain_node.fail("the chain needs rows");
  if (row_nodes.size() > static_cast<std::size_t>(hand::FingerChainCache::kMaxRows))
    chain_node.fail("a chain has at most " + std::to_string(hand::FingerChainCache::kMaxRows) +
                    " rows");
  chain.rows.clear();
  for (const ConfigNode& row : row_nodes)
    chain.rows.push_back(parse_row(row, finger));
  check_links(row_nodes, finger, model, radii, chain_node);
}

void parse_fingers(const ConfigNode& node, HandModel& model) {
  node.expect_keys({"thumb", "index", "middle", "ring", "little"});
  for (int f = 0; f < hand::kFingerCount; ++f) {
    const auto finger = static_cast<Finger>(f);
    parse_finger(node[hand::finger_name(finger)], finger, model);
  }
}

}  // namespace

hand::HandModel parse_hand_model(const ConfigNode& root) {
  root.expect_keys({"side", "tracker", "joints", "palm", "fingers"});
  const bool left = parse_side_is_left(root["side"]);
  HandModel model;
  model.tracker = parse_tracker(root["tracker"]);
  parse_joints(root["joints"], model.joints);
  parse_palm(root["palm"], model);
  parse_fingers(root["fingers"], model);
  // the file always describes a right hand; a left one is its mirror image
  return left ? hand::mirrored(model) : model;
}

hand::HandModel load_hand_model(const std::string& path) {
  return parse_hand_model(ConfigNode::load_file(path));
}

}  // namespace vcockpit
