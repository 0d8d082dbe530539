#include "launcher/rig_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "hand/hand_joints.hpp"
#include "idl/topics/bar_list.hpp"

namespace vcockpit::rig {

namespace {

const char* cause_name(cockpit::ControlCause cause) {
  switch (cause) {
    case cockpit::PUSHED: return "pushed";
    case cockpit::GRASPED: return "grasped";
    case cockpit::COMMANDED: return "commanded";
    case cockpit::MECHANISM: return "mechanism";
    case cockpit::OBJECT_PUSHED: return "object";
  }
  return "unknown";
}

}  // namespace

RigMonitor::RigMonitor(DdsParticipant& participant)
    : status_reader_(participant.make_reader<cockpit::NodeStatus>("state")),
      event_reader_(participant.make_reader<cockpit::GraspEvent>("event")),
      frame_reader_(participant.make_reader<cockpit::FrameInfo>("stream")),
      info_reader_(participant.make_reader<cockpit::ObjectInfo>("state")),
      state_reader_(participant.make_reader<cockpit::ObjectState>("state")),
      control_info_reader_(participant.make_reader<cockpit::ControlInfo>("state")),
      control_state_reader_(participant.make_reader<cockpit::ControlState>("state")),
      control_event_reader_(participant.make_reader<cockpit::ControlEvent>("event")),
      systems_info_reader_(participant.make_reader<cockpit::SystemsInfo>("state")),
      systems_state_reader_(participant.make_reader<cockpit::SystemsState>("state")),
      systems_event_reader_(participant.make_reader<cockpit::SystemsEvent>("event")),
      score_reader_(participant.make_reader<cockpit::ProcedureScore>("state")) {}

std::string RigMonitor::object_name(uint32_t id) const {
  auto it = names_.find(id);
  return it == names_.end() ? "object " + std::to_string(id) : it->second;
}

void RigMonitor::poll() {
  cockpit::ObjectInfo info;
  while (info_reader_.take(info)) {
    names_[info.object_id()] = info.name().to_string();
    dynamic_[info.object_id()] = info.kind() == cockpit::DYNAMIC_OBJECT;
  }
  cockpit::ObjectState state;
  while (state_reader_.take(state)) {
    if (dynamic_[state.object_id()]) final_[object_name(state.object_id())] = state;
  }
  cockpit::NodeStatus status;
  while (status_reader_.take(status)) {
    const std::string name = status.node_name().to_string();
    if (name == "physics_node" && status.input_alive()) {
      if (step_rates_++ == 0) {
        first_step_rate_hz_ = status.loop_rate_hz();
      } else {
        step_rates_sum_hz_ += status.loop_rate_hz();
      }
    }
    statuses_[name] = status;
  }
  cockpit::GraspEvent e;
  while (event_reader_.take(e)) {
    SeenEvent seen;
    seen.hand_id = static_cast<int>(e.hand_id());
    seen.t_s = static_cast<double>(e.sim_time_ns()) / 1e9;  // prints as its exact decimal
    seen.grasp = e.kind() == cockpit::GRASP;
    seen.object = object_name(e.object_id());
    seen.reason = e.reason().to_string();
    held_ = seen.grasp ? seen.object : "";
    events_.push_back(seen);
  }
  cockpit::ControlInfo control_info;
  while (control_info_reader_.take(control_info)) {
    controls_[control_info.control_id()] = {control_info.name().to_string(),
                                             split_bar_list(control_info.position_names().to_string())};
  }
  cockpit::ControlState control_state;
  while (control_state_reader_.take(control_state))
    control_positions_[control_state.control_id()] = control_state.position();
  cockpit::ControlEvent control_event;
  while (control_event_reader_.take(control_event)) {
    RawControlEvent raw;
    raw.t_s = static_cast<double>(control_event.sim_time_ns()) / 1e9;
    raw.control = control_event.control_id();
    raw.from = control_event.from_position();
    raw.to = control_event.to_position();
    raw.cause = cause_name(control_event.cause());
    if (control_event.link() >= 0 && control_event.link() < hand::kLinkCount)
      raw.link = std::string(hand::link_name(static_cast<hand::Link>(control_event.link())));
    control_events_.push_back(raw);
  }
  cockpit::SystemsInfo systems_info;
  while (systems_info_reader_.take(systems_info)) {
    systems_.clear();
    for (const cockpit::SystemInfo& si : systems_info.systems()) {
      systems_.push_back({si.name().to_string(), split_bar_list(si.state_names().to_string())});
    }
  }
  cockpit::SystemsState systems_state;
  while (systems_state_reader_.take(systems_state))
    systems_values_.assign(systems_state.values().begin(), systems_state.values().end());
  cockpit::SystemsEvent systems_event;
  while (systems_event_reader_.take(systems_event)) {
    SeenSystemsEvent seen;
    seen.t_s = static_cast<double>(systems_event.sim_time_ns()) / 1e9;
    seen.kind = systems_event.kind() == cockpit::SYSTEM_CHANGED      ? "changed"
                : systems_event.kind() == cockpit::FAILURE_INSERTED ? "failure_inserted"
                                                                     : "failure_cleared";
    seen.name = systems_event.name().to_string();
    seen.from = systems_event.from_text().to_string();
    seen.to = systems_event.to_text().to_string();
    systems_events_.push_back(seen);
  }
  cockpit::ProcedureScore score;
  while (score_reader_.take(score)) {
    const auto seconds = [](int64_t ns) { return ns < 0 ? -1.0 : static_cast<double>(ns) * 1e-9; };
    static constexpr const char* kStates[] = {"waiting", "running", "complete", "incomplete"};
    static constexpr const char* kStatus[] = {"pending", "done", "missed"};
    SeenProcedure p;
    p.lesson = score.lesson().to_string();
    p.name = score.name().to_string();
    p.title = score.title().to_string();
    p.state = kStates[std::clamp<int>(static_cast<int>(score.state()), 0, 3)];
    p.started_s = seconds(score.started_time_ns());
    p.ended_s = seconds(score.ended_time_ns());
    p.errors = score.errors();
    for (const cockpit::ProcedureStepScore& st : score.steps()) {
      SeenProcedure::Step step;
      step.item = st.item().to_string();
      step.action = st.action().to_string();
      step.status = kStatus[std::clamp<int>(static_cast<int>(st.status()), 0, 2)];
      step.out_of_order = st.out_of_order();
      step.late = st.late();
      step.undone = st.undone();
      step.done_s = seconds(st.done_time_ns());
      step.since_previous_s = seconds(st.since_previous_ns());
      p.steps.push_back(step);
    }
    procedures_[score.index()] = p;
    procedure_count_ = score.count();
  }
  cockpit::FrameInfo frame;
  while (frame_reader_.take(frame)) {
    ++frames_seen_;
    // each hand sample counts once, at the first frame that drew it
    if (frame.source_stamp_ns() <= 0 || frame.source_stamp_ns() == last_source_stamp_ns_) continue;
    last_source_stamp_ns_ = frame.source_stamp_ns();
    latency_.record_ns(frame.render_end_ns() - frame.source_stamp_ns());
    // where the latency goes: the sample's age when the frame began, and the render itself
    age_at_render_.record_ns(frame.render_start_ns() - frame.source_stamp_ns());
    render_.record_ns(frame.render_end_ns() - frame.render_start_ns());
  }
}

double RigMonitor::mean_step_rate_hz() const {
  if (step_rates_ < 2) return first_step_rate_hz_;  // 0 with none
  return step_rates_sum_hz_ / static_cast<double>(step_rates_ - 1);
}

uint64_t RigMonitor::late_steps() const {
  auto it = statuses_.find("physics_node");
  return it == statuses_.end() ? 0 : it->second.late_steps();
}

bool RigMonitor::input_consumed(const std::vector<std::string>& input_nodes) const {
  auto physics = statuses_.find("physics_node");
  if (physics == statuses_.end()) return false;
  uint64_t published = 0;
  for (const std::string& name : input_nodes) {
    int seen = 0;
    for (const auto& [status_name, status] : statuses_) {
      if (!is_status_of(status_name, name)) continue;
      if (status.state() != cockpit::STOPPING) return false;
      published += status.published();
      ++seen;
    }
    if (seen == 0) return false;
  }
  return physics->second.received() + physics->second.rejected() >= published;
}

std::string RigMonitor::status_line(double elapsed_s) const {
  auto rate = [&](const char* node) {
    auto it = statuses_.find(node);
    return it == statuses_.end() ? 0.0 : it->second.loop_rate_hz();
  };
  auto glove = statuses_.find("physics_node");
  const bool alive = glove != statuses_.end() && glove->second.input_alive();
  char line[256];
  std::snprintf(line, sizeof line,
                "%6.1f s | physics %6.0f Hz | glove %5.0f Hz %s | frames %4.0f fps | %s | "
                "latency p50 %5.1f ms",
                elapsed_s, rate("physics_node"), rate("glove_driver"), alive ? "   " : "LOST",
                rate("image_generator"), held_.empty() ? "nothing held" : ("holding " + held_).c_str(),
                static_cast<double>(latency_.percentile_ns(0.5)) * 1e-6);
  return line;
}

std::string RigMonitor::control_name(uint32_t control) const {
  const auto it = controls_.find(control);
  return it != controls_.end() ? it->second.name : "control " + std::to_string(control);
}

// a position by index, or its number when the control's info has not come
std::string RigMonitor::position_name(uint32_t control, uint32_t position) const {
  const auto it = controls_.find(control);
  if (it != controls_.end() && position < it->second.positions.size()) return it->second.positions[position];
  return std::to_string(position);
}

std::vector<SeenControlEvent> RigMonitor::control_events() const {
  std::vector<SeenControlEvent> out;
  out.reserve(control_events_.size());
  for (const RawControlEvent& raw : control_events_)
    out.push_back({raw.t_s, control_name(raw.control), position_name(raw.control, raw.from),
                   position_name(raw.control, raw.to), raw.cause, raw.link});
  return out;
}

std::map<std::string, std::string> RigMonitor::control_positions() const {
  std::map<std::string, std::string> out;
  for (const auto& [control, position] : control_positions_)
    out[control_name(control)] = position_name(control, position);
  return out;
}

std::vector<SeenProcedure> RigMonitor::procedures() const {
  std::vector<SeenProcedure> out;
  for (const auto& [index, p] : procedures_)
    if (index < procedure_count_) out.push_back(p);
  return out;
}

std::map<std::string, std::string> RigMonitor::systems_values() const {
  std::map<std::string, std::string> out;
  for (std::size_t i = 0; i < systems_.size() && i < systems_values_.size(); ++i) {
    const double v = systems_values_[i];
    const auto& states = systems_[i].states;
    if (!states.empty()) {
      out[systems_[i].name] = v >= 0 && v < static_cast<double>(states.size())
                                  ? states[static_cast<std::size_t>(v)]
                                  : "?";
    } else {
      char text[32];
      std::snprintf(text, sizeof text, "%.6g", v);
      out[systems_[i].name] = text;
    }
  }
  return out;
}

}  // namespace vcockpit::rig
