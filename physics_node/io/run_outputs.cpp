#include "physics_node/io/run_outputs.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "common/fixed_decimal.hpp"
#include "common/json_file.hpp"
#include "physics_node/io/grasp_event_text.hpp"

namespace vcockpit::physics_io {

std::string hand_name(int hand_id) { return hand_id == 1 ? "left" : "right"; }

namespace {
// "right", "left", or "both" while two hands hold it
std::string holders_name(const physics::BodyState& b) {
  return (b.holders & (b.holders - 1)) != 0 ? "both" : hand_name(b.held_by);
}
}  // namespace


TrajectoryWriter::TrajectoryWriter(const std::string& path) : file_(path) {
  std::fprintf(file_.get(),
               "t_s,object,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,held_by,control_q,control_position\n");
}

bool TrajectoryWriter::RowState::operator==(const RowState& o) const {
  // bit for bit: -0.0 and 0.0 print differently, and a value that changed in its last bit may
  // round to other digits
  return std::memcmp(values.data(), o.values.data(), sizeof values) == 0 && holders == o.holders &&
         held_by == o.held_by && position == o.position;
}

void TrajectoryWriter::write(const physics::World& world) {
  const auto& objects = world.scene().objects;
  if (last_.size() != objects.size()) last_.assign(objects.size(), {});
  const double t_s = static_cast<double>(world.time_ns()) / 1e9;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (!objects[i].dynamic) continue;
    const auto& b = world.bodies()[i];
    const std::string& name = objects[i].name;
    const bool finite = guard_.pass(b.X_GO.matrix().allFinite(), name, "pose", world.time_ns()) &&
                        guard_.pass(b.v_G.allFinite(), name, "linear velocity", world.time_ns()) &&
                        guard_.pass(b.w_G.allFinite(), name, "angular velocity", world.time_ns());
    if (!finite) continue;  // the row is left out
    const int control = objects[i].control;
    const physics::ControlState* control_state =
        control >= 0 ? &world.state().controls[static_cast<std::size_t>(control)] : nullptr;
    RowState now;
    std::memcpy(now.values.data(), b.X_GO.matrix().data(), 12 * sizeof(double));
    std::memcpy(now.values.data() + 12, b.v_G.data(), 3 * sizeof(double));
    std::memcpy(now.values.data() + 15, b.w_G.data(), 3 * sizeof(double));
    now.values[18] = control_state ? control_state->q : 0.0;
    now.holders = b.holders;
    now.held_by = b.held_by;
    now.position = control_state ? control_state->position : -1;
    // most objects lie still (or sleep) between rows: their row after the time is the same text
    Memo& memo = last_[i];
    if (!memo.valid || !(memo.state == now)) {
      memo.state = now;
      memo.valid = true;
      std::string& tail = memo.tail;
      const Eigen::Vector3d p = b.X_GO.translation();
      const Eigen::Quaterniond q(b.X_GO.linear());
      // append_fixed, not fprintf: the same digits (both round the exact binary value), without
      // printf's format parsing and locking per value (common/fixed_decimal.hpp)
      tail.clear();
      tail += ',';
      tail += name;
      for (const double v : {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(), b.v_G.x(),
                             b.v_G.y(), b.v_G.z(), b.w_G.x(), b.w_G.y(), b.w_G.z()}) {
        tail += ',';
        append_fixed(tail, v, 9);
      }
      tail += ',';
      if (b.held_by != physics::kNotHeld) tail += holders_name(b);
      tail += ',';
      if (control_state) {  // the control's coordinate (m or rad) and its position's name
        const auto& positions = world.scene().controls[static_cast<std::size_t>(control)].positions;
        append_fixed(tail, control_state->q, 9);
        tail += ',';
        tail += positions[static_cast<std::size_t>(control_state->position)].name;
        tail += '\n';
      } else {
        tail += ",\n";
      }
    }
    row_.clear();
    append_fixed(row_, t_s, 6);
    row_ += memo.tail;
    std::fwrite(row_.data(), 1, row_.size(), file_.get());
  }
}

EventWriter::EventWriter(const std::string& path) : file_(path) {}

void EventWriter::write(const physics::World& world) {
  for (const auto& e : world.step_events()) write(e, world.scene().objects[e.object].name);
  for (const auto& e : world.control_events()) write(e, world.scene());
}

void EventWriter::write(const physics::ControlEvent& e, const physics::Scene& scene) {
  ++controls_;
  const physics::ControlSpec& c = scene.controls[static_cast<std::size_t>(e.control)];
  nlohmann::ordered_json record = {
      {"t_s", static_cast<double>(e.t_ns) / 1e9},
      {"event", "control"},
      {"control", c.name},
      {"from", c.positions[static_cast<std::size_t>(e.from)].name},
      {"to", c.positions[static_cast<std::size_t>(e.to)].name},
      {"hand", e.hand_id >= 0 ? nlohmann::ordered_json(hand_name(e.hand_id)) : nullptr},
      {"link", e.link >= 0 ? nlohmann::ordered_json(std::string(physics::link_name(
                                 static_cast<physics::Link>(e.link))))
                           : nullptr},
      {"cause", physics::control_cause_name(e.cause)}};
  file_.write(json_text(record) + "\n");
}

void EventWriter::write(const physics::GraspEvent& e, const std::string& object_name) {
  (e.grasp ? grasps_ : releases_)++;
  if (e.hand_id >= 0 && e.hand_id < 2) (e.grasp ? hand_grasps_ : hand_releases_)[e.hand_id]++;
  nlohmann::ordered_json record = {{"t_s", static_cast<double>(e.t_ns) / 1e9},
                                   {"event", e.grasp ? "grasp" : "release"},
                                   {"hand", hand_name(e.hand_id)},
                                   {"object", object_name},
                                   {"reason", grasp_event_text(e)},
                                   {"contacts", e.contacts},
                                   {"residual_force_N", e.residual_force_N},
                                   {"residual_torque_Nm", e.residual_torque_Nm}};
  // a handover (the hand it went to or came from) or a two-handed hold (the other hand)
  if (e.other_hand_id >= 0) record["with"] = hand_name(e.other_hand_id);
  guard_.scrub(record, object_name, e.t_ns);  // a residual that is not finite is left out
  file_.write(json_text(record) + "\n");
}

void write_summary(const std::string& path, const RunSummary& s, const physics::World& world) {
  const double mean_m =
      s.penetration_points > 0 ? s.penetration_sum_m / static_cast<double>(s.penetration_points) : 0.0;
  nlohmann::ordered_json j;
  j["scene"] = s.scene_path;
  // one log: its path; several (one per hand): the list
  if (s.log_paths.empty()) {
    j["log"] = nullptr;
  } else if (s.log_paths.size() == 1) {
    j["log"] = s.log_paths.front();
  } else {
    j["log"] = s.log_paths;
  }
  j["steps"] = s.steps;
  j["simulated_s"] = s.simulated_s;
  j["wall_s"] = s.wall_s;
  j["realtime_factor"] = s.wall_s > 0 ? s.simulated_s / s.wall_s : 0.0;
  j["grasps"] = s.grasps;
  j["releases"] = s.releases;
  j["hand_penetration_max_m"] = s.penetration_max_m;
  j["hand_penetration_mean_m"] = mean_m;
  j["hand_peak_wrist_speed_mps"] = s.hand_peak_wrist_mps;
  j["hand_peak_joint_speed_radps"] = s.hand_peak_joint_radps;
  if (s.have_input) {
    nlohmann::ordered_json input = hand::input_counts_json(s.input);
    input["max_gap_s"] = static_cast<double>(s.timing.max_gap_ns) * 1e-9;
    input["glove_timeout_s"] = static_cast<double>(s.timing.glove_timeout_ns) * 1e-9;
    j["input"] = std::move(input);
    auto& hands = j["hands"] = nlohmann::ordered_json::array();
    for (const HandRunSummary& h : s.hands) {
      hands.push_back({{"hand", hand_name(h.hand_id)},
                       {"log", h.log_path},
                       {"grasps", h.grasps},
                       {"releases", h.releases},
                       {"input", hand::input_counts_json(h.input)}});
    }
  } else {
    j["input"] = nullptr;
  }
  auto& stages = j["stage_wall_s"] = nlohmann::ordered_json::object();
  for (int i = 0; i < physics::kStageCount; ++i) {
    stages[physics::stage_name(static_cast<physics::Stage>(i))] =
        i < static_cast<int>(s.stage_total_s.size()) ? s.stage_total_s[i] : 0.0;
  }
  j["stage_timing_every"] = s.stage_timing_every;  // stage_wall_s: estimates from one step in so many
  j["control_events"] = s.control_events;
  auto& controls = j["controls"] = nlohmann::ordered_json::object();
  for (std::size_t c = 0; c < world.scene().controls.size(); ++c) {
    const physics::ControlSpec& spec = world.scene().controls[c];
    controls[spec.name] =
        spec.positions[static_cast<std::size_t>(world.state().controls[c].position)].name;
  }
  auto& final_poses = j["final"] = nlohmann::ordered_json::object();
  const auto& objects = world.scene().objects;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (!objects[i].dynamic) continue;
    const auto& b = world.bodies()[i];
    const Eigen::Vector3d p = b.X_GO.translation();
    const Eigen::Quaterniond q(b.X_GO.linear());
    final_poses[objects[i].name] = {
        {"position", {p.x(), p.y(), p.z()}},
        {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}},
        {"held_by", b.held_by == physics::kNotHeld ? nlohmann::ordered_json(nullptr)
                                                   : nlohmann::ordered_json(hand_name(b.held_by))}};
  }
  NonFiniteGuard guard("summary.json");
  guard.scrub(j, "the run", world.time_ns());
  j["non_finite_refused"] = s.non_finite_refused + guard.refused();
  write_json_file(path, j);
}

}  // namespace vcockpit::physics_io
