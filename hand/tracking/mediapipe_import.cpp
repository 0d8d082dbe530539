#include "hand/tracking/mediapipe_import.hpp"

#include <nlohmann/json.hpp>

#include <cmath>


namespace vcockpit::hand::tracking {
namespace {

using nlohmann::json;

// The OpenXR joint of each of MediaPipe's 21 landmarks.
constexpr XrJoint kLandmarkJoint[21] = {
    XrJoint::kWrist,
    XrJoint::kThumbMetacarpal, XrJoint::kThumbProximal, XrJoint::kThumbDistal, XrJoint::kThumbTip,
    XrJoint::kIndexProximal, XrJoint::kIndexIntermediate, XrJoint::kIndexDistal, XrJoint::kIndexTip,
    XrJoint::kMiddleProximal, XrJoint::kMiddleIntermediate, XrJoint::kMiddleDistal, XrJoint::kMiddleTip,
    XrJoint::kRingProximal, XrJoint::kRingIntermediate, XrJoint::kRingDistal, XrJoint::kRingTip,
    XrJoint::kLittleProximal, XrJoint::kLittleIntermediate, XrJoint::kLittleDistal, XrJoint::kLittleTip};

const json* member(const json& object, std::initializer_list<const char*> names) {
  for (const char* n : names)
    if (object.contains(n)) return &object[n];
  return nullptr;
}

class Importer {
 public:
  explicit Importer(const std::string& path) : path_(path), errors_(path) {}

  MediaPipeImport run() {
    const json doc = read_json_file(path_);
    const json* frames = doc.is_array() ? &doc : (doc.is_object() ? member(doc, {"frames"}) : nullptr);
    if (frames == nullptr || !frames->is_array())
      throw JointsLogError(path_ + ": neither a list of frames nor {\"frames\": [...]}");
    out_.source_frames = static_cast<int>(frames->size());
    for (std::size_t i = 0; i < frames->size(); ++i) read_frame((*frames)[i], i);
    if (out_.frames.empty()) throw JointsLogError(path_ + ": no frame has a hand");
    return std::move(out_);
  }

 private:
  [[noreturn]] void fail(std::size_t frame, const std::string& what) const { errors_.fail(frame, what); }
  double number(const json& v, std::size_t frame, const std::string& field) const {
    return errors_.number(v, frame, field);
  }

  void read_frame(const json& f, std::size_t i) {
    if (!f.is_object()) fail(i, "not an object");
    double t_s = 0.0;
    if (const json* ms = member(f, {"timestamp_ms", "timestampMs"})) {
      t_s = number(*ms, i, "timestamp_ms") * 1e-3;
    } else if (const json* s = member(f, {"t_s"})) {
      t_s = number(*s, i, "t_s");
    } else {
      fail(i, "no 'timestamp_ms' (or 'timestampMs', 't_s')");
    }
    const json* hands = member(f, {"worldLandmarks", "hand_world_landmarks"});
    if (hands == nullptr) fail(i, "no 'worldLandmarks' (or 'hand_world_landmarks')");
    if (!hands->is_array()) fail(i, "'worldLandmarks' is not a list");
    if (hands->empty()) {
      ++out_.frames_without_hands;
      return;
    }
    const json* sides = member(f, {"handednesses", "handedness"});
    if (sides == nullptr || !sides->is_array() || sides->size() != hands->size())
      fail(i, "'handednesses' does not give one entry per hand");
    if (first_t_s_ < 0.0) first_t_s_ = t_s;
    const auto t_ns = static_cast<int64_t>(std::llround((t_s - first_t_s_) * 1e9));
    bool out_of_order = false;
    std::vector<JointsFrame> rows;
    for (std::size_t h = 0; h < hands->size(); ++h) {
      const std::string owner = "worldLandmarks[" + std::to_string(h) + "]";
      JointsFrame row;
      row.t_ns = t_ns;
      row.left_hand = side_is_left((*sides)[h], i, h);
      if (!times_.take(row.left_hand, t_ns)) {
        out_of_order = true;
        continue;
      }
      const json& points = (*hands)[h];
      if (!points.is_array() || points.size() != 21) fail(i, "'" + owner + "' is not 21 landmarks");
      for (std::size_t k = 0; k < 21; ++k) {
        const json& p = points[k];
        const std::string field = owner + "[" + std::to_string(k) + "]";
        if (!p.is_object() || !p.contains("x") || !p.contains("y") || !p.contains("z"))
          fail(i, "'" + field + "' has no x, y, z");
        TrackedJoint& joint = row[kLandmarkJoint[k]];
        // MediaPipe: x right, y down, z away from the camera -> xr: x right, y up, z toward it
        joint.p_m = {number(p["x"], i, field + ".x"), -number(p["y"], i, field + ".y"),
                     -number(p["z"], i, field + ".z")};
        joint.valid = true;
      }
      rows.push_back(row);
    }
    if (out_of_order) ++out_.frames_out_of_order;
    for (const JointsFrame& r : rows) out_.frames.push_back(r);
  }

  bool side_is_left(const json& categories, std::size_t i, std::size_t h) const {
    const std::string owner = "handednesses[" + std::to_string(h) + "]";
    const json& best = categories.is_array() && !categories.empty() ? categories[0] : categories;
    const json* name = best.is_object() ? member(best, {"categoryName", "category_name", "label"}) : nullptr;
    if (name == nullptr || !name->is_string()) fail(i, "'" + owner + "' names no Left or Right");
    const std::string side = name->get<std::string>();
    if (side != "Left" && side != "Right") fail(i, "'" + owner + "' is '" + side + "', not Left or Right");
    return side == "Left";
  }

  std::string path_;
  FrameErrors errors_;
  MediaPipeImport out_;
  double first_t_s_ = -1.0;
  HandTimes times_;
};

}  // namespace

MediaPipeImport import_mediapipe(const std::string& path) { return Importer(path).run(); }

}  // namespace vcockpit::hand::tracking
