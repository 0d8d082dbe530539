#include "hand/tracking/leapjs_import.hpp"

#include <nlohmann/json.hpp>

#include <cmath>


namespace vcockpit::hand::tracking {
namespace {

using nlohmann::json;

class Importer {
 public:
  explicit Importer(const std::string& path) : path_(path), errors_(path) {}

  LeapImport run() {
    const json doc = read_json_file(path_);
    if (!doc.is_object() || !doc.contains("frames") || !doc["frames"].is_array())
      throw JointsLogError(path_ + ": no 'frames' array: not a LeapJS playback recording");
    if (doc.contains("metadata") && doc["metadata"].is_object()) {
      const json& m = doc["metadata"];
      if (m.contains("protocolVersion") && m["protocolVersion"].is_number_integer())
        out_.protocol_version = m["protocolVersion"].get<int>();
    }
    const json& frames = doc["frames"];
    out_.source_frames = static_cast<int>(frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) read_frame(frames[i], i);
    if (out_.frames.empty()) throw JointsLogError(path_ + ": no frame has a hand");
    return std::move(out_);
  }

 private:
  [[noreturn]] void fail(std::size_t frame, const std::string& what) const { errors_.fail(frame, what); }
  double number(const json& v, std::size_t frame, const std::string& field) const {
    return errors_.number(v, frame, field);
  }

  Eigen::Vector3d vec3(const json& object, const char* key, std::size_t frame, const std::string& owner) const {
    const std::string field = owner + "." + key;
    if (!object.contains(key)) fail(frame, "no '" + field + "'");
    const json& v = object[key];
    if (!v.is_array() || v.size() != 3) fail(frame, "'" + field + "' is not 3 numbers");
    return {number(v[0], frame, field), number(v[1], frame, field), number(v[2], frame, field)};
  }

  void read_frame(const json& f, std::size_t i) {
    if (!f.is_object()) fail(i, "not an object");
    if (!f.contains("timestamp")) fail(i, "no 'timestamp'");
    const double stamp_us = number(f["timestamp"], i, "timestamp");
    const json hands = f.contains("hands") ? f["hands"] : json::array();
    if (!hands.is_array()) fail(i, "'hands' is not an array");
    if (hands.empty()) {
      ++out_.frames_without_hands;
      return;
    }
    if (first_stamp_us_ < 0) first_stamp_us_ = stamp_us;
    const auto t_ns = static_cast<int64_t>(std::llround((stamp_us - first_stamp_us_) * 1e3));
    const json pointables = f.contains("pointables") ? f["pointables"] : json::array();
    if (!pointables.is_array()) fail(i, "'pointables' is not an array");
    bool out_of_order = false;
    std::vector<JointsFrame> rows;
    for (std::size_t h = 0; h < hands.size(); ++h) {
      const json& hand = hands[h];
      const std::string owner = "hands[" + std::to_string(h) + "]";
      if (!hand.is_object() || !hand.contains("type") || !hand["type"].is_string())
        fail(i, "'" + owner + ".type' is not left or right");
      const std::string side = hand["type"].get<std::string>();
      if (side != "left" && side != "right") fail(i, "'" + owner + ".type' is '" + side + "', not left or right");
      JointsFrame row;
      row.t_ns = t_ns;
      row.left_hand = side == "left";
      if (!times_.take(row.left_hand, t_ns)) {
        out_of_order = true;
        continue;
      }
      read_palm(hand, i, owner, row);
      if (!hand.contains("id")) fail(i, "no '" + owner + ".id'");
      for (std::size_t p = 0; p < pointables.size(); ++p)
        read_pointable(pointables[p], hand["id"], i, p, row);
      rows.push_back(row);
    }
    if (out_of_order) ++out_.frames_out_of_order;
    for (const JointsFrame& r : rows) out_.frames.push_back(r);
  }

  void read_palm(const json& hand, std::size_t i, const std::string& owner, JointsFrame& row) const {
    TrackedJoint& palm = row[XrJoint::kPalm];
    palm.p_m = 1e-3 * vec3(hand, "palmPosition", i, owner);
    // OpenXR: -Z toward the fingers, +Y out of the back of the hand
    const Eigen::Vector3d toward_fingers = vec3(hand, "direction", i, owner);
    const Eigen::Vector3d palm_normal = vec3(hand, "palmNormal", i, owner);
    const Eigen::Vector3d z = -toward_fingers.normalized();
    Eigen::Vector3d y = -palm_normal - (-palm_normal).dot(z) * z;
    if (toward_fingers.norm() < 1e-6 || y.norm() < 1e-6) fail(i, "'" + owner + ".direction' and 'palmNormal' do not make a basis");
    y.normalize();
    Eigen::Matrix3d R;
    R.col(0) = y.cross(z);
    R.col(1) = y;
    R.col(2) = z;
    palm.q = Eigen::Quaterniond(R).normalized();
    palm.has_orientation = true;
    palm.valid = true;
  }

  void read_pointable(const json& p, const json& hand_id, std::size_t i, std::size_t k, JointsFrame& row) const {
    const std::string owner = "pointables[" + std::to_string(k) + "]";
    if (!p.is_object()) fail(i, "'" + owner + "' is not an object");
    if (!p.contains("handId") || p["handId"] != hand_id) return;
    if (p.contains("tool") && p["tool"].is_boolean() && p["tool"].get<bool>()) return;
    if (!p.contains("type") || !p["type"].is_number_integer()) fail(i, "'" + owner + ".type' is not 0..4");
    const int finger = p["type"].get<int>();
    if (finger < 0 || finger > 4) fail(i, "'" + owner + ".type' is " + std::to_string(finger) + ", not 0..4");
    const XrFingerChain chain = xr_finger_chain(finger);
    // the thumb's four joints are Leap's mcp, pip, dip, tip; a finger's last four
    const int first = chain.count - 4;
    const char* keys[4] = {"mcpPosition", "pipPosition", "dipPosition", "tipPosition"};
    double radius_m = 0.0;
    const bool has_radius = p.contains("width");
    if (has_radius) radius_m = 0.5e-3 * number(p["width"], i, owner + ".width");
    for (int b = 0; b < 4; ++b) {
      TrackedJoint& joint = row[chain.joints[static_cast<std::size_t>(first + b)]];
      joint.p_m = 1e-3 * vec3(p, keys[b], i, owner);
      joint.valid = true;
      joint.has_radius = has_radius && radius_m >= 0.0;
      joint.radius_m = joint.has_radius ? radius_m : 0.0;
    }
  }

  std::string path_;
  FrameErrors errors_;
  LeapImport out_;
  double first_stamp_us_ = -1.0;
  HandTimes times_;
};

}  // namespace

LeapImport import_leapjs(const std::string& path) { return Importer(path).run(); }

}  // namespace vcockpit::hand::tracking
