#include "image_generator/node/scene_cache.hpp"

#include "idl/topics/hand_info_convert.hpp"
#include "idl/topics/pose_convert.hpp"
#include "model/import/model_file.hpp"

namespace vcockpit::image_generator {
namespace {

render::Primitive primitive_of(cockpit::ShapeKind shape) {
  switch (shape) {
    case cockpit::BOX:
      return render::Primitive::kBox;
    case cockpit::SPHERE:
      return render::Primitive::kSphere;
    case cockpit::CAPSULE:
      return render::Primitive::kCapsule;
    case cockpit::CYLINDER:
      return render::Primitive::kCylinder;
    case cockpit::MESH:
      return render::Primitive::kMesh;
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
  if (in.primitive == render::Primitive::kMesh) {
    in.mesh = model_mesh(info);
    in.size_m = Eigen::Vector3d::Ones();
    if (!in.mesh) {  // the box round its vertices, where they are in the object's frame
      in.primitive = render::Primitive::kBox;
      in.size_m = Eigen::Vector3d(d[0], d[1], d[2]);
      o.box_offset_m = to_eigen(info.mesh_center_m());
      in.X_GO = o.X_GO * Eigen::Translation3d(o.box_offset_m);  // (a state that came first)
    }
  }
  const auto& c = info.color_rgba();
  in.rgba = {c[0], c[1], c[2], c[3]};
  // the background layer: what does not move (a control's moving part does, whatever its kind)
  o.is_static = info.kind() == cockpit::STATIC_OBJECT;
  in.fixed = o.is_static && !o.is_control;
}

namespace {

model::ModelRequest model_request(const cockpit::ObjectInfo& info) {
  return {info.mesh_file().to_string(), info.mesh_node().to_string(), info.mesh_scale(),
          info.mesh_z_up() ? model::UpAxis::kZ : model::UpAxis::kY, true};
}

std::string model_key(const cockpit::ObjectInfo& info) {
  const Eigen::Vector3d origin_m = to_eigen(info.mesh_origin_m());
  return info.mesh_file().to_string() + '\n' + info.mesh_node().to_string() + '\n' +
         std::to_string(info.mesh_scale()) + (info.mesh_z_up() ? " z" : " y") +
         std::to_string(origin_m.x()) + ' ' + std::to_string(origin_m.y()) + ' ' +
         std::to_string(origin_m.z());
}

}  // namespace

std::vector<model::ModelRequest> SceneCache::model_requests(
    const std::vector<cockpit::ObjectInfo>& infos) const {
  std::vector<model::ModelRequest> out;
  for (const cockpit::ObjectInfo& info : infos)
    if (info.shape() == cockpit::MESH && models_.count(model_key(info)) == 0)
      out.push_back(model_request(info));
  return out;
}

std::shared_ptr<const render::MeshData> SceneCache::model_mesh(const cockpit::ObjectInfo& info) {
  const Eigen::Vector3d origin_m = to_eigen(info.mesh_origin_m());
  const std::string key = model_key(info);
  if (auto it = models_.find(key); it != models_.end()) return it->second;
  std::shared_ptr<const render::MeshData> data;
  try {
    model::TriangleMesh mesh = model::load_model_mesh(model_request(info));
    model::translate(mesh, origin_m);  // as the physics node framed it
    model_triangles_ += mesh.triangles.size();
    model_textures_ += mesh.textures.size();
    if (mesh.textures_left_out > 0) {
      textures_left_out_ += mesh.textures_left_out;
      last_texture_left_out_ = mesh.source + ": " + mesh.first_texture_left_out;
    }
    data = std::make_shared<const render::MeshData>(render::model_mesh_data(std::move(mesh)));
  } catch (const model::MeshError& e) {
    ++models_refused_;
    last_model_error_ = e.what();
  }
  models_[key] = data;  // a refused one is not tried again every info
  return data;
}

void SceneCache::on_state(const cockpit::ObjectState& state) {
  Object& o = objects_[state.object_id()];
  o.have_pose = true;
  o.X_GO = to_eigen(state.X_GO());
  o.instance.X_GO = o.X_GO * Eigen::Translation3d(o.box_offset_m);
  o.instance.highlight = state.held_by_hand_id() != cockpit::kNoObject;
  newest_sim_time_ns_ = std::max(newest_sim_time_ns_, state.sim_time_ns());
}

void SceneCache::on_control_info(const cockpit::ControlInfo& info) {
  Object& body = objects_[info.object_id()];
  body.is_control = true;
  body.instance.fixed = false;
  if (info.lit_position() < 0) return;  // no light
  ControlLights& lights = control_lights_[info.control_id()];
  lights.body = info.object_id();
  lights.light = info.light_object_id();
  // off until its state says otherwise (a state that came first is applied now)
  bool lit = false;
  if (auto pending = lit_pending_.find(info.control_id()); pending != lit_pending_.end()) {
    lit = pending->second;
    lit_pending_.erase(pending);
  }
  set_lit(lights.body, lit);
  if (lights.light >= 0) set_lit(static_cast<uint32_t>(lights.light), lit);
}

void SceneCache::on_control_state(const cockpit::ControlState& state) {
  const auto it = control_lights_.find(state.control_id());
  if (it == control_lights_.end()) {
    lit_pending_[state.control_id()] = state.lit();
    return;
  }
  set_lit(it->second.body, state.lit());
  if (it->second.light >= 0) set_lit(static_cast<uint32_t>(it->second.light), state.lit());
}

void SceneCache::set_lit(uint32_t object, bool lit) {
  objects_[object].light = lit ? 1 : -1;
}

bool SceneCache::on_hand_info(const cockpit::HandInfo& info) {
  if (info.hand_id() >= kHandSlots || !hand_info_sizes_valid(info)) {
    ++hand_messages_refused_;
    return false;
  }
  Hand& h = hands_[info.hand_id()];
  h.geometry = from_hand_info(info);
  h.have_info = true;
  if (h.have_state) {  // its state came first: drawn from now on
    if (shown_ < 0) shown_ = static_cast<int>(info.hand_id());
    newest_sim_time_ns_ = std::max(newest_sim_time_ns_, h.state.sim_time_ns());
  }
  return true;
}

void SceneCache::on_hand(const cockpit::HandState& hand) {
  if (hand.hand_id() >= kHandSlots) {
    ++hand_messages_refused_;
    return;
  }
  Hand& h = hands_[hand.hand_id()];
  h.state = hand;
  h.have_state = true;
  h.predictor.on_state(hand);
  if (!h.have_info) {
    ++hand_states_without_info_;
    return;
  }
  shown_ = static_cast<int>(hand.hand_id());
  newest_sim_time_ns_ = std::max(newest_sim_time_ns_, hand.sim_time_ns());
}

bool SceneCache::on_tracked_joints(const cockpit::TrackedJoints& joints) {
  if (joints.hand_id() >= kHandSlots) {
    ++hand_messages_refused_;
    return false;
  }
  Hand& h = hands_[joints.hand_id()];
  std::array<Eigen::Vector3d, 26> p_G{};
  for (std::size_t j = 0; j < p_G.size(); ++j) {
    p_G[j] = to_eigen(joints.p_G_m()[j]);
    if (joints.valid()[j] && !p_G[j].allFinite()) {
      ++hand_messages_refused_;
      return false;
    }
  }
  h.p_G_joint = p_G;
  for (std::size_t j = 0; j < p_G.size(); ++j)
    h.joint_valid[j] = joints.valid()[j];
  h.joints_time_ns = joints.sample_time_ns();
  h.have_joints = true;
  return true;
}

int SceneCache::hand_without_info() const {
  for (int id = 0; id < kHandSlots; ++id) {
    if (hands_[id].have_state && !hands_[id].have_info) return id;
  }
  return -1;
}

Eigen::Vector3d SceneCache::object_position(uint32_t id) const {
  auto it = objects_.find(id);
  if (it == objects_.end()) return Eigen::Vector3d::Zero();
  return it->second.instance.X_GO.translation();
}

void SceneCache::build(std::vector<render::Instance>& out) const {
  out.clear();
  for (const auto& [id, o] : objects_)
    append_object(o, out);
  for (const Hand& h : hands_) {
    if (h.have_info && h.have_state) append_hand(h, 0, out);
  }
}

void SceneCache::build_fixed(std::vector<render::Instance>& out) const {
  out.clear();
  append_objects(out, true);
}

void SceneCache::build_moving(std::vector<render::Instance>& out, int64_t display_ns) const {
  out.clear();
  append_objects(out, false);
  for (const Hand& h : hands_) {
    if (h.have_info && h.have_state) append_hand(h, display_ns, out);
  }
}

bool SceneCache::tracked_index_tip(uint32_t hand_id, int64_t display_ns,
                                   Eigen::Vector3d& p_G) const {
  if (hand_id >= kHandSlots) return false;
  const Hand& h = hands_[hand_id];
  if (!h.have_info || !h.have_state) return false;
  LinkPoses links;
  if (display_ns > 0) {
    h.predictor.predict(display_ns, true, links);
  } else {
    for (std::size_t l = 0; l < links.size(); ++l)
      links[l] = to_eigen(h.state.tracked_X_GL()[l]);
  }
  // the distal phalanx's capsule runs along its frame's x axis: its tip is length_m out
  const auto distal = static_cast<std::size_t>(hand::Link::kIndexDistal);
  p_G = links[distal] * Eigen::Vector3d(h.geometry.capsules[distal].length_m, 0, 0);
  return true;
}

void SceneCache::append_objects(std::vector<render::Instance>& out, bool fixed) const {
  for (const auto& [id, o] : objects_)
    if (o.instance.fixed == fixed) append_object(o, out);
}

void SceneCache::append_object(const Object& o, std::vector<render::Instance>& out) const {
  if (!o.have_info || !o.have_pose) return;
  out.push_back(o.instance);
  if (o.light > 0) {
    out.back().highlight = true;  // a lit cap or annunciator glows
  } else if (o.light < 0) {
    for (int k = 0; k < 3; ++k)
      out.back().rgba[k] *= kUnlitScale;  // and is dull when off
  }
}

void SceneCache::append_hand(const Hand& hand, int64_t display_ns,
                             std::vector<render::Instance>& out) const {
  const cockpit::HandState& state = hand.state;
  const auto& colour = state.tracking() ? kSkin : kGlove;  // grey while the glove is lost
  LinkPoses links, tracked;
  if (display_ns > 0) {
    hand.predictor.predict(display_ns, false, links);
    hand.predictor.predict(display_ns, true, tracked);
  } else {
    for (std::size_t l = 0; l < links.size(); ++l) {
      links[l] = to_eigen(state.X_GL()[l]);
      tracked[l] = to_eigen(state.tracked_X_GL()[l]);
    }
  }
  // drawn rounder than the physics' shapes: the palm's box with rounded edges, each phalanx's
  // capsule tapering towards the tip (the same mean radius: within 1.1 mm of the capsule at
  // either end for the medium hand)
  render::Instance palm;
  palm.primitive = render::Primitive::kRoundedBox;
  palm.X_GO = links[0];  // the palm link frame is the palm box centre (X_HP)
  palm.size_m = hand.geometry.palm_size_m;
  palm.rgba = colour;
  out.push_back(palm);
  // a phalanx frame has its capsule along +x from its origin; the primitive's axis is z
  const Eigen::Isometry3d z_to_x(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const hand::Capsule& c = hand.geometry.capsules[l];
    render::Instance phalanx;
    phalanx.primitive = render::Primitive::kTaperedCapsule;
    phalanx.X_GO =
        links[static_cast<std::size_t>(l)] * Eigen::Translation3d(0.5 * c.length_m, 0, 0) * z_to_x;
    phalanx.size_m = Eigen::Vector3d(c.radius_m, c.length_m, 0);
    phalanx.rgba = colour;
    out.push_back(phalanx);
  }
  append_ghost(hand, tracked, out);
  append_tracked_joints(hand, out);
}

// What the hand tracker saw: a small dot per tracked joint, beside the hand fitted to them, so a
// user sees how well the fit follows (hand/tracking/retarget.hpp).
void SceneCache::append_tracked_joints(const Hand& hand, std::vector<render::Instance>& out) const {
  if (!show_tracked_joints_ || !hand.have_joints) return;
  const int64_t age_ns = hand.state.sample_time_ns() - hand.joints_time_ns;
  if (age_ns > kTrackedJointsAge_ns || age_ns < -kTrackedJointsAge_ns) return;
  for (std::size_t j = 0; j < hand.p_G_joint.size(); ++j) {
    if (!hand.joint_valid[j]) continue;
    render::Instance dot;
    dot.primitive = render::Primitive::kSphere;
    dot.X_GO = Eigen::Isometry3d(Eigen::Translation3d(hand.p_G_joint[j]));
    dot.size_m = Eigen::Vector3d(kJointDotRadius_m, 0, 0);
    dot.rgba = kJointDot;
    out.push_back(dot);
  }
}

// The tracked hand, where it differs from the drawn one by more than the threshold: a thin pale
// skeleton (the renderer draws opaque) that shows the pilot where the glove really is while the
// simulated hand rests on a panel or round an object (Prachyabrued & Borst 2014).
void SceneCache::append_ghost(const Hand& hand, const LinkPoses& tracked,
                              std::vector<render::Instance>& out) const {
  const cockpit::HandState& state = hand.state;
  if (!(state.tracked_offset_m() > ghost_threshold_m_)) return;
  const Eigen::Isometry3d z_to_x(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const hand::Capsule& c = hand.geometry.capsules[l];
    render::Instance bone;
    bone.primitive = render::Primitive::kCapsule;
    bone.X_GO = tracked[static_cast<std::size_t>(l)] *
                Eigen::Translation3d(0.5 * c.length_m, 0, 0) * z_to_x;
    bone.size_m = Eigen::Vector3d(kGhostRadiusScale * c.radius_m, c.length_m, 0);
    bone.rgba = kGhost;
    out.push_back(bone);
  }
}

}  // namespace vcockpit::image_generator
