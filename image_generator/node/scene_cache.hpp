#pragma once
// What the image generator knows of the world: object geometry and colour from
// cockpit/object_info, their poses from cockpit/object_state, the hand from cockpit/hand_state
// (geometry from the hand model). Turned into render instances each frame without allocating
// once the vectors have grown.

#include <cstdint>
#include <map>
#include <vector>

#include "cockpit.h"
#include "image_generator/render/stereo_renderer.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit::image_generator {

class SceneCache {
 public:
  explicit SceneCache(const hand::HandModel& hand) : hand_(hand) {}

  void on_info(const cockpit::ObjectInfo& info);
  void on_state(const cockpit::ObjectState& state);
  void on_hand(const cockpit::HandState& hand);

  bool has_objects() const { return !objects_.empty(); }
  std::size_t object_count() const { return objects_.size(); }
  bool has_hand() const { return have_hand_; }
  const cockpit::HandState& hand() const { return hand_state_; }
  int64_t newest_sim_time_ns() const { return newest_sim_time_ns_; }
  Eigen::Vector3d object_position(uint32_t id) const;

  // Objects with both info and a pose, then the hand's palm box and 15 phalanx capsules.
  void build(std::vector<render::Instance>& out) const;

 private:
  struct Object {
    bool have_info = false;
    bool have_pose = false;
    render::Instance instance;
  };

  const hand::HandModel& hand_;
  std::map<uint32_t, Object> objects_;  // by object id: drawn in id order
  cockpit::HandState hand_state_;
  bool have_hand_ = false;
  int64_t newest_sim_time_ns_ = 0;
};

}  // namespace vcockpit::image_generator
