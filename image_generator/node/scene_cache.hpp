#pragma once
// What the image generator knows of the world: object geometry and colour from
// cockpit/object_info, their poses from cockpit/object_state, each hand's geometry from
// cockpit/hand_info and its link poses from cockpit/hand_state. Turned into render instances each
// frame without allocating once the vectors have grown.
//
// A hand is drawn only once the hand_info of its hand_id has arrived: the geometry is the one the
// physics node simulates, never guessed. Hand states of a hand without info are kept (drawn as
// soon as the info comes) and counted.

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cockpit.h"
#include "hand/hand_model.hpp"
#include "image_generator/node/hand_prediction.hpp"
#include "image_generator/render/stereo_renderer.hpp"
#include "model/import/model_file.hpp"

namespace vcockpit::image_generator {

class SceneCache {
 public:
  static constexpr int kHandSlots = 2;  // hand_id 0 right, 1 left

  void on_info(const cockpit::ObjectInfo& info);
  // The model parts these infos name that are not drawn yet: for a ModelPrefetch over their
  // on_info calls, so a cockpit's file of many parts is read once.
  std::vector<model::ModelRequest> model_requests(const std::vector<cockpit::ObjectInfo>& infos) const;
  void on_state(const cockpit::ObjectState& state);
  // A control with a light (lit_position >= 0): its moving part and its annunciator are drawn
  // glowing while its control_state says lit, and dimmed while not.
  void on_control_info(const cockpit::ControlInfo& info);
  void on_control_state(const cockpit::ControlState& state);
  // False (and counted) when the info is unusable: hand_id beyond 1, sizes negative, zero palm or
  // not finite. A later info for the same hand replaces the geometry.
  bool on_hand_info(const cockpit::HandInfo& info);
  void on_hand(const cockpit::HandState& hand);
  // A hand tracker's joints (cockpit/tracked_joints); false (and counted with the refused hand
  // messages) for a hand_id beyond 1 or a valid joint not finite.
  bool on_tracked_joints(const cockpit::TrackedJoints& joints);
  // Draw each hand's tracked joints as small dots beside it (off by default), while they are of
  // the hand's sample time within kTrackedJointsAge_ns.
  void set_show_tracked_joints(bool show) { show_tracked_joints_ = show; }
  static constexpr int64_t kTrackedJointsAge_ns = 100'000'000;
  static constexpr double kJointDotRadius_m = 0.004;

  bool has_objects() const { return !objects_.empty(); }
  std::size_t object_count() const { return objects_.size(); }
  // A hand that is drawn (info and state), and the state of the one updated last.
  bool has_hand() const { return shown_ >= 0; }
  const cockpit::HandState& hand() const { return hands_[shown_ < 0 ? 0 : shown_].state; }
  const cockpit::HandState& hand_state(uint32_t hand_id) const { return hands_[hand_id].state; }
  bool has_hand_info(uint32_t hand_id) const {
    return hand_id < kHandSlots && hands_[hand_id].have_info;
  }
  // The hand_id of a hand whose state arrived but whose info has not (not drawn); -1 none.
  int hand_without_info() const;
  // Hand states received for a hand without info (not drawn; a few are normal at start, before
  // the transient-local info arrives), and hand states or infos refused (hand_id beyond 1, bad
  // sizes).
  uint64_t hand_states_without_info() const { return hand_states_without_info_; }
  uint64_t hand_messages_refused() const { return hand_messages_refused_; }
  // Model files (a MESH object's) that could not be loaded here: the object is drawn as the box
  // round its vertices. The last one's error, for the log.
  uint64_t models_refused() const { return models_refused_; }
  const std::string& last_model_error() const { return last_model_error_; }
  // Triangles and texture images of the model meshes loaded (each distinct file, node, scale
  // and frame once); textures their files named that were not found or not decoded (drawn
  // without), and the last such one with why, for the log.
  std::size_t model_triangles() const { return model_triangles_; }
  std::size_t model_textures() const { return model_textures_; }
  uint64_t textures_left_out() const { return textures_left_out_; }
  const std::string& last_texture_left_out() const { return last_texture_left_out_; }
  int64_t newest_sim_time_ns() const { return newest_sim_time_ns_; }
  Eigen::Vector3d object_position(uint32_t id) const;

  // The tracked hand is drawn as a ghost (thin pale bones) while it is farther than this from the
  // drawn proxy hand (HandState.tracked_offset_m); infinity: never.
  static constexpr double kDefaultGhostThreshold_m = 0.01;
  void set_ghost_threshold_m(double threshold_m) { ghost_threshold_m_ = threshold_m; }

  // Objects with both info and a pose, then for each drawn hand its palm box and 15 phalanx
  // capsules, and the tracked hand's 15 bones when it is a ghost.
  void build(std::vector<render::Instance>& out) const;
  // The same in two layers: the static objects (Instance::fixed, not a control's moving part),
  // and everything else (the renderer's background and moving layers).
  // display_ns > 0: the hands as predicted for that moment (hand_prediction.hpp).
  void build_fixed(std::vector<render::Instance>& out) const;
  void build_moving(std::vector<render::Instance>& out, int64_t display_ns = 0) const;
  // The tracked hand's index fingertip in the world, now (display_ns 0) or predicted for
  // display_ns; false if the hand is not drawn.
  bool tracked_index_tip(uint32_t hand_id, int64_t display_ns, Eigen::Vector3d& p_G) const;
  // How far ahead of the shown state display_ns is (for the frame log).
  int64_t prediction_horizon_ns(uint32_t hand_id, int64_t display_ns) const {
    return hand_id < kHandSlots ? hands_[hand_id].predictor.horizon_ns(display_ns) : 0;
  }

 private:
  struct Object {
    bool have_info = false;
    bool have_pose = false;
    int light = 0;  // 0 no light, 1 lit, -1 a light that is off
    bool is_static = false;   // ObjectInfo says STATIC_OBJECT
    bool is_control = false;  // a control's moving part
    // where the drawn box's centre is in the object's frame (a model drawn as its box)
    Eigen::Vector3d box_offset_m = Eigen::Vector3d::Zero();
    Eigen::Isometry3d X_GO = Eigen::Isometry3d::Identity();  // as its state said
    render::Instance instance;
  };
  struct ControlLights {
    uint32_t body = 0;
    int32_t light = -1;
  };
  void set_lit(uint32_t object, bool lit);
  struct Hand {
    bool have_info = false;
    bool have_state = false;
    hand::HandModel geometry;  // capsules and palm box only (from_hand_info)
    cockpit::HandState state;
    HandPredictor predictor;
    bool have_joints = false;
    int64_t joints_time_ns = 0;
    std::array<bool, 26> joint_valid{};
    std::array<Eigen::Vector3d, 26> p_G_joint{};
  };

  void append_objects(std::vector<render::Instance>& out, bool fixed) const;
  void append_object(const Object& o, std::vector<render::Instance>& out) const;
  void append_hand(const Hand& hand, int64_t display_ns, std::vector<render::Instance>& out) const;
  void append_ghost(const Hand& hand, const LinkPoses& tracked,
                    std::vector<render::Instance>& out) const;
  void append_tracked_joints(const Hand& hand, std::vector<render::Instance>& out) const;

  static constexpr float kUnlitScale = 0.35f;  // a light that is off, against its colour
  static constexpr double kGhostRadiusScale = 0.3;  // the ghost's bones against the drawn radii
  static constexpr std::array<float, 4> kGhost = {0.80f, 0.86f, 0.95f, 1.0f};
  double ghost_threshold_m_ = kDefaultGhostThreshold_m;
  static constexpr std::array<float, 4> kJointDot = {0.10f, 0.85f, 0.95f, 1.0f};
  bool show_tracked_joints_ = false;

  std::map<uint32_t, Object> objects_;  // by object id: drawn in id order
  std::map<uint32_t, ControlLights> control_lights_;  // by control id: the objects it lights
  std::map<uint32_t, bool> lit_pending_;  // a light's state that came before its object's info
  std::array<Hand, kHandSlots> hands_;  // by hand_id
  int shown_ = -1;                      // hand_id of the drawn hand updated last; -1 none
  uint64_t hand_states_without_info_ = 0;
  uint64_t hand_messages_refused_ = 0;
  // A MESH object's model, loaded once per file, node, scale, axes and origin.
  std::shared_ptr<const render::MeshData> model_mesh(const cockpit::ObjectInfo& info);
  std::map<std::string, std::shared_ptr<const render::MeshData>> models_;
  uint64_t models_refused_ = 0;
  std::string last_model_error_;
  std::size_t model_triangles_ = 0;
  std::size_t model_textures_ = 0;
  uint64_t textures_left_out_ = 0;
  std::string last_texture_left_out_;
  int64_t newest_sim_time_ns_ = 0;
};

}  // namespace vcockpit::image_generator
