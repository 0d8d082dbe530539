#include "physics_node/node/state_publisher.hpp"

#include <cmath>

#include "common/clock.hpp"
#include "idl/topics/hand_info_convert.hpp"
#include "idl/topics/pose_convert.hpp"
#include "physics_node/io/grasp_event_text.hpp"

namespace vcockpit::physics_node {
namespace {

cockpit::ShapeKind shape_to_idl(physics::ShapeKind kind) {
  switch (kind) {
    case physics::ShapeKind::kBox: return cockpit::BOX;
    case physics::ShapeKind::kSphere: return cockpit::SPHERE;
    case physics::ShapeKind::kCapsule: return cockpit::CAPSULE;
    case physics::ShapeKind::kCylinder: return cockpit::CYLINDER;
    case physics::ShapeKind::kMesh: return cockpit::MESH;
  }
  return cockpit::BOX;
}

// The residuals are magnitudes: -1 says "not available" where a value is not finite.
constexpr double kNoResidual = -1.0;
// A rate or stage time that is not finite: -1, as no measurement is negative.
constexpr double kNoMeasurement = -1.0;

bool all_finite(const std::array<Eigen::Isometry3d, hand::kLinkCount>& X_GL) {
  for (const Eigen::Isometry3d& X : X_GL)
    if (!X.matrix().allFinite()) return false;
  return true;
}

std::string hand_id_name(int hand_id) { return hand_id == 1 ? "the left hand" : "the right hand"; }

}  // namespace

StatePublisher::StatePublisher(DdsParticipant& participant, const physics::World& world)
    : info_writer_(participant.make_writer<cockpit::ObjectInfo>("state")),
      hand_info_writer_(participant.make_writer<cockpit::HandInfo>("state")),
      hand_writer_(participant.make_writer<cockpit::HandState>("stream")),
      object_writer_(participant.make_writer<cockpit::ObjectState>("state")),
      event_writer_(participant.make_writer<cockpit::GraspEvent>("event")),
      status_writer_(participant.make_writer<cockpit::NodeStatus>("state")),
      control_info_writer_(participant.make_writer<cockpit::ControlInfo>("state")),
      control_writer_(participant.make_writer<cockpit::ControlState>("state")),
      control_event_writer_(participant.make_writer<cockpit::ControlEvent>("event")),
      control_sent_(world.scene().controls.size()),
      object_last_(world.scene().objects.size()),
      control_last_(world.scene().controls.size()),
      object_span_(world.scene().objects.size()),
      control_span_(world.scene().controls.size()),
      hand_seq_(static_cast<std::size_t>(world.hand_count()), 0) {}

static_assert(static_cast<int>(physics::ControlKind::kGuard) == cockpit::GUARD &&
                  static_cast<int>(physics::ControlKind::kPushButton) == cockpit::PUSH_BUTTON,
              "ControlKind in the same order as the IDL's");
static_assert(static_cast<int>(physics::ControlCause::kObject) == cockpit::OBJECT_PUSHED &&
                  static_cast<int>(physics::ControlCause::kPushed) == cockpit::PUSHED,
              "ControlCause in the same order as the IDL's");

void StatePublisher::publish_control_info(const physics::World& world) {
  const auto& controls = world.scene().controls;
  for (std::size_t i = 0; i < controls.size(); ++i) {
    const physics::ControlSpec& c = controls[i];
    cockpit::ControlInfo info;
    info.control_id(static_cast<uint32_t>(i));
    info.name(c.name.substr(0, 64));
    info.kind(static_cast<cockpit::ControlKind>(c.kind));
    info.joint(c.joint == physics::JointKind::kPrismatic ? cockpit::PRISMATIC : cockpit::REVOLUTE);
    info.object_id(static_cast<uint32_t>(c.body));
    info.X_GJ(to_idl(c.X_GJ));
    info.limited(c.limited);
    info.travel_min(c.q_min);
    info.travel_max(c.q_max);
    info.position_count(static_cast<uint32_t>(c.positions.size()));
    std::string names;
    for (std::size_t p = 0; p < c.positions.size() && p < info.position_coordinates().size(); ++p) {
      names += c.positions[p].name + "|";  // at most 8 names of at most 32 characters
      info.position_coordinates()[p] = c.positions[p].q;
    }
    info.position_names(names);
    info.lit_position(c.lit_when);
    info.light_object_id(c.light_object);
    control_info_writer_.write(info);
  }
}

// each control whose coordinate, position or holder changed since its last sample
void StatePublisher::publish_controls(const physics::World& world) {
  const auto& controls = world.scene().controls;
  for (std::size_t i = 0; i < controls.size(); ++i) {
    const physics::ControlState& s = world.state().controls[i];
    const int held_by = world.bodies()[static_cast<std::size_t>(controls[i].body)].held_by;
    const SentControl& sent = control_sent_[i];
    if (sent.valid && s.q == sent.q && s.qd == sent.qd && s.position == sent.position &&
        held_by == sent.held_by)
      continue;
    if (!control_guard_.pass(std::isfinite(s.q) && std::isfinite(s.qd), controls[i].name,
                             "coordinate", world.time_ns()))
      continue;
    control_msg_.control_id(static_cast<uint32_t>(i));
    control_msg_.sim_time_ns(world.time_ns());
    control_msg_.coordinate(s.q);
    control_msg_.velocity(s.qd);
    control_msg_.position(static_cast<uint32_t>(s.position));
    control_msg_.lit(controls[i].lit_when >= 0 && s.position == controls[i].lit_when);
    control_msg_.held_by_hand_id(held_by);
    write_control(control_msg_);
    control_sent_[i] = {true, s.q, s.qd, s.position, held_by};
  }
  rewrite_due_controls();
}

void StatePublisher::publish_object_info(const physics::World& world) {
  const auto& objects = world.scene().objects;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const physics::ObjectSpec& o = objects[i];
    const bool finite =
        info_guard_.pass(std::isfinite(o.mass_kg) && o.shape.box_size_m.allFinite() &&
                             std::isfinite(o.shape.radius_m) && std::isfinite(o.shape.length_m),
                         o.name, "size or mass", world.time_ns()) &&
        info_guard_.pass(o.dynamic || world.bodies()[i].X_GO.matrix().allFinite(), o.name, "pose",
                         world.time_ns());
    if (!finite) continue;  // not drawn at all rather than drawn nowhere
    cockpit::ObjectInfo info;
    info.object_id(static_cast<uint32_t>(i));
    info.name(o.name.substr(0, 64));
    info.kind(o.dynamic ? cockpit::DYNAMIC_OBJECT : cockpit::STATIC_OBJECT);
    // what it looks like: its look when it has one (it collides as its shape all the same)
    const physics::Shape& drawn = o.look ? *o.look : o.shape;
    info.shape(shape_to_idl(drawn.kind));
    if (drawn.kind == physics::ShapeKind::kBox) {
      info.dimensions_m({drawn.box_size_m.x(), drawn.box_size_m.y(), drawn.box_size_m.z()});
    } else if (drawn.kind == physics::ShapeKind::kMesh) {
      const Eigen::Vector3d size_m = drawn.mesh_bounds.max_m - drawn.mesh_bounds.min_m;
      info.dimensions_m({size_m.x(), size_m.y(), size_m.z()});
      const physics::Shape::MeshSource& m = drawn.mesh_source;
      info.mesh_file(m.file.substr(0, 255));
      info.mesh_node(m.node.substr(0, 64));
      info.mesh_scale(m.scale);
      info.mesh_z_up(m.z_up);
      info.mesh_origin_m(to_idl(m.origin_m));
      info.mesh_center_m(to_idl(0.5 * (drawn.mesh_bounds.min_m + drawn.mesh_bounds.max_m)));
    } else {
      info.dimensions_m({drawn.radius_m, drawn.length_m, 0.0});
    }
    info.color_rgba({o.color_rgba[0], o.color_rgba[1], o.color_rgba[2], o.color_rgba[3]});
    info.mass_kg(o.mass_kg);
    info_writer_.write(info);
    // static objects never move: their one state sample (transient local) places them for good
    if (!o.dynamic) {
      object_msg_.object_id(static_cast<uint32_t>(i));
      object_msg_.sim_time_ns(world.time_ns());
      object_msg_.X_GO(to_idl(world.bodies()[i].X_GO));
      object_msg_.linear_velocity_mps(to_idl(Eigen::Vector3d::Zero()));
      object_msg_.angular_velocity_radps(to_idl(Eigen::Vector3d::Zero()));
      object_msg_.held_by_hand_id(cockpit::kNoObject);
      write_object(object_msg_);
    }
  }
}

void StatePublisher::publish_hand_info(const physics::World& world) {
  for (int h = 0; h < world.hand_count(); ++h) {
    hand_info_writer_.write(to_hand_info(world.scene().hands[static_cast<std::size_t>(h)],
                                         static_cast<uint32_t>(world.hand_id(h))));
  }
}

void StatePublisher::publish_state(const physics::World& world,
                                   const std::vector<HandInputState>& hands) {
  publish_controls(world);
  const auto& objects = world.scene().objects;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const physics::BodyState& b = world.bodies()[i];
    if (!objects[i].dynamic) continue;
    const std::string& name = objects[i].name;
    const int64_t t_ns = world.time_ns();
    if (!object_guard_.pass(b.X_GO.matrix().allFinite(), name, "pose", t_ns) ||
        !object_guard_.pass(b.v_G.allFinite(), name, "linear velocity", t_ns) ||
        !object_guard_.pass(b.w_G.allFinite(), name, "angular velocity", t_ns))
      continue;  // the last good sample stands
    object_msg_.object_id(static_cast<uint32_t>(i));
    object_msg_.sim_time_ns(world.time_ns());
    object_msg_.X_GO(to_idl(b.X_GO));
    object_msg_.linear_velocity_mps(to_idl(b.v_G));
    object_msg_.angular_velocity_radps(to_idl(b.w_G));
    object_msg_.held_by_hand_id(b.held_by);
    write_object(object_msg_);
  }
  rewrite_due_objects();
  for (int h = 0; h < world.hand_count(); ++h) publish_hand(world, h, h < static_cast<int>(hands.size())
                                                                       ? hands[static_cast<std::size_t>(h)]
                                                                       : HandInputState{});
}

void StatePublisher::write_object(const cockpit::ObjectState& msg) {
  object_writer_.write(msg);
  object_last_[msg.object_id()] = msg;
  object_span_.wrote(msg.object_id());
}

void StatePublisher::write_control(const cockpit::ControlState& msg) {
  control_writer_.write(msg);
  control_last_[msg.control_id()] = msg;
  control_span_.wrote(msg.control_id());
}

// static objects, and a dynamic one whose state is not finite (its last good sample)
void StatePublisher::rewrite_due_objects() {
  for (std::size_t i = 0; i < object_last_.size(); ++i)
    if (object_span_.due(i)) {
      object_writer_.write(object_last_[i]);
      object_span_.wrote(i);
    }
}

// controls at rest, while others move
void StatePublisher::rewrite_due_controls() {
  for (std::size_t i = 0; i < control_last_.size(); ++i)
    if (control_span_.due(i)) {
      control_writer_.write(control_last_[i]);
      control_span_.wrote(i);
    }
}

void StatePublisher::publish_hand(const physics::World& world, int hand, const HandInputState& input) {
  if (!world.hand_active(hand)) return;
  const std::string name = hand_id_name(world.hand_id(hand));
  if (!hand_guard_.pass(world.X_GH(hand).matrix().allFinite(), name, "pose X_GH", world.time_ns()) ||
      !hand_guard_.pass(all_finite(world.X_GL(hand)), name, "link poses X_GL", world.time_ns()))
    return;
  // the object it holds (the first, if several)
  int held = cockpit::kNoObject;
  const auto bit = static_cast<uint8_t>(1u << hand);
  for (std::size_t i = 0; i < world.bodies().size() && held == cockpit::kNoObject; ++i)
    if ((world.bodies()[i].holders & bit) != 0) held = static_cast<int>(i);
  hand_msg_.hand_id(static_cast<uint32_t>(world.hand_id(hand)));
  hand_msg_.seq(hand_seq_[static_cast<std::size_t>(hand)]++);
  hand_msg_.sample_time_ns(input.stamps.sample_time_ns);
  hand_msg_.source_stamp_ns(input.stamps.source_stamp_ns);
  hand_msg_.sim_time_ns(world.time_ns());
  hand_msg_.X_GH(to_idl(world.X_GH(hand)));
  for (int l = 0; l < hand::kLinkCount; ++l) hand_msg_.X_GL()[l] = to_idl(world.X_GL(hand)[l]);
  for (int l = 0; l < hand::kLinkCount; ++l)
    hand_msg_.tracked_X_GL()[l] = to_idl(world.tracked_X_GL(hand)[l]);
  hand_msg_.tracked_offset_m(world.tracked_offset_m(hand));
  hand_msg_.grasped_object_id(held);
  hand_msg_.tracking(input.tracking);
  hand_writer_.write(hand_msg_);
}

void StatePublisher::publish_events(const physics::World& world) {
  for (const physics::ControlEvent& e : world.control_events()) {
    control_event_msg_.seq(control_event_seq_++);
    control_event_msg_.sim_time_ns(e.t_ns);
    control_event_msg_.control_id(static_cast<uint32_t>(e.control));
    control_event_msg_.from_position(static_cast<uint32_t>(e.from));
    control_event_msg_.to_position(static_cast<uint32_t>(e.to));
    control_event_msg_.cause(static_cast<cockpit::ControlCause>(e.cause));
    control_event_msg_.hand_id(e.hand_id);
    control_event_msg_.link(e.link);
    control_event_writer_.write(control_event_msg_);
  }
  for (const physics::GraspEvent& e : world.step_events()) {
    event_msg_.seq(event_seq_++);
    event_msg_.sim_time_ns(e.t_ns);
    event_msg_.hand_id(static_cast<uint32_t>(e.hand_id));
    event_msg_.object_id(static_cast<uint32_t>(e.object));
    event_msg_.kind(e.grasp ? cockpit::GRASP : cockpit::RELEASE);
    event_msg_.reason(physics_io::grasp_event_text(e).c_str());
    event_msg_.contact_count(static_cast<uint32_t>(e.contacts));
    const std::string& name = world.scene().objects[static_cast<std::size_t>(e.object)].name;
    const bool force_finite =
        event_guard_.pass(std::isfinite(e.residual_force_N), name, "residual_force_N", e.t_ns);
    const bool torque_finite =
        event_guard_.pass(std::isfinite(e.residual_torque_Nm), name, "residual_torque_Nm", e.t_ns);
    event_msg_.residual_force_N(force_finite ? e.residual_force_N : kNoResidual);
    event_msg_.residual_torque_Nm(torque_finite ? e.residual_torque_Nm : kNoResidual);
    event_writer_.write(event_msg_);
  }
}

void StatePublisher::publish_status(const cockpit::NodeStatus& status) {
  bool finite = std::isfinite(status.loop_rate_hz()) && std::isfinite(status.input_rate_hz());
  for (const double t_us : status.stage_time_us()) finite = finite && std::isfinite(t_us);
  if (finite) {
    status_writer_.write(status);
    return;
  }
  // rare: a copy with -1 in place of each value that is not finite
  cockpit::NodeStatus sent = status;
  const auto measured = [&](double value, const char* field) {
    return status_guard_.pass(std::isfinite(value), "the node", field, status.stamp_ns())
               ? value
               : kNoMeasurement;
  };
  sent.loop_rate_hz(measured(status.loop_rate_hz(), "loop_rate_hz"));
  sent.input_rate_hz(measured(status.input_rate_hz(), "input_rate_hz"));
  for (double& t_us : sent.stage_time_us()) t_us = measured(t_us, "stage_time_us");
  status_writer_.write(sent);
}

void StatePublisher::flush(int64_t timeout_ns) {
  wait_for_acknowledgments({&event_writer_, &object_writer_, &status_writer_, &info_writer_, &hand_info_writer_},
                           timeout_ns);
}

}  // namespace vcockpit::physics_node
