#include "image_generator/node/scene_cache.hpp"

#include "idl/topics/pose_convert.hpp"

namespace vcockpit::image_generator {
namespace {

render::Primitive primitive_of(cockpit::ShapeKind shape) {
  switch (shape) {
    case cockpit::BOX: return render::Primitive::kBox;
    case cockpit::SPHERE: return render::Primitive::kSphere;
    case cockpit::CAPSULE: return render::Primitive::kCapsule;
    case cockpit::CYLINDER: return render::Primitive::kCylinder;
  }
  return render::Primitive::kBox;
}

constexpr std::array<float, 4> kSkin = {0.85f, 0.66f, 0.55f, 1.0f};
constexpr std::array<float, 4> kGlove = {0.20f, 0.22f, 0.26f, 1.0f};

}  // namespace

void SceneCache::on_info(const cockpit::ObjectInfo& info) {
  Object& o = objects_[info.object_id()];
  o.have_info = true;
  render::Instance& in = o.instance;
  in.primitive = primitive_of(info.shape());
  const auto& d = info.dimensions_m();
  in.size_m = Eigen::Vector3d(d[0], d[1], d[2]);
  const auto& c = info.color_rgba();
  in.rgba = {c[0], c[1], c[2], c[3]};
}

void SceneCache::on_state(const cockpit::ObjectState& state) {
  Object& o = objects_[state.object_id()];
  o.have_pose = true;
  o.instance.X_GO = to_eigen(state.X_GO());
  o.instance.highlight = state.held_by_hand_id() != cockpit::kNoObject;
  newest_sim_time_ns_ = std::max(newest_sim_time_ns_, state.sim_time_ns());
}

void SceneCache::on_hand(const cockpit::HandState& hand) {
  hand_state_ = hand;
  have_hand_ = true;
  newest_sim_time_ns_ = std::max(newest_sim_time_ns_, hand.sim_time_ns());
}

Eigen::Vector3d SceneCache::object_position(uint32_t id) const {
  auto it = objects_.find(id);
  if (it == objects_.end()) return Eigen::Vector3d::Zero();
  return it->second.instance.X_GO.translation();
}

void SceneCache::build(std::vector<render::Instance>& out) const {
  out.clear();
  for (const auto& [id, o] : objects_) {
    if (o.have_info && o.have_pose) out.push_back(o.instance);
  }
  if (!have_hand_) return;
  const auto& colour = hand_state_.tracking() ? kSkin : kGlove;  // grey while the glove is lost
  render::Instance palm;
  palm.primitive = render::Primitive::kBox;
  palm.X_GO = to_eigen(hand_state_.X_GL()[0]);
  palm.size_m = hand_.palm_size_m;
  palm.rgba = colour;
  out.push_back(palm);
  // a phalanx frame has its capsule along +x from its origin; the primitive's axis is z
  const Eigen::Isometry3d z_to_x(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const hand::Capsule& c = hand_.capsules[l];
    render::Instance phalanx;
    phalanx.primitive = render::Primitive::kCapsule;
    phalanx.X_GO = to_eigen(hand_state_.X_GL()[l]) *
                   Eigen::Translation3d(0.5 * c.length_m, 0, 0) * z_to_x;
    phalanx.size_m = Eigen::Vector3d(c.radius_m, c.length_m, 0);
    phalanx.rgba = colour;
    out.push_back(phalanx);
  }
}

}  // namespace vcockpit::image_generator
