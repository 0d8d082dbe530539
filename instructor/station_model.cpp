#include "instructor/station_model.hpp"

#include <cmath>
#include <iterator>

#include <algorithm>
#include <cstdio>

#include "common/clock.hpp"
#include "idl/topics/bar_list.hpp"
#include "idl/topics/sim_ack_frozen.hpp"

namespace vcockpit::instructor {
namespace {

const char* node_state_name(cockpit::NodeState state) {
  switch (state) {
    case cockpit::STARTING: return "STARTING";
    case cockpit::RUNNING: return "RUNNING";
    case cockpit::DEGRADED: return "DEGRADED";
    case cockpit::STOPPING: return "STOPPING";
  }
  return "UNKNOWN";
}

const char* control_kind_name(cockpit::ControlKind kind) {
  switch (kind) {
    case cockpit::PUSH_BUTTON: return "PUSH_BUTTON";
    case cockpit::TOGGLE: return "TOGGLE";
    case cockpit::ROTARY: return "ROTARY";
    case cockpit::LEVER: return "LEVER";
    case cockpit::GUARD: return "GUARD";
  }
  return "UNKNOWN";
}

const char* control_cause_name(cockpit::ControlCause cause) {
  switch (cause) {
    case cockpit::PUSHED: return "pushed";
    case cockpit::GRASPED: return "grasped";
    case cockpit::COMMANDED: return "commanded";
    case cockpit::MECHANISM: return "mechanism";
    case cockpit::OBJECT_PUSHED: return "pushed by an object";
  }
  return "unknown";
}

const char* side_name(int64_t hand_id) { return hand_id == 1 ? "left" : "right"; }

// ControlInfo.position_names, padded to the control's count ("#k" for a name it lacks)
std::vector<std::string> split_positions(const std::string& names, uint32_t count) {
  std::vector<std::string> out = split_bar_list(names);
  if (out.size() > count) out.resize(count);
  while (out.size() < count) out.push_back("#" + std::to_string(out.size()));
  return out;
}

}  // namespace

namespace {
const char* procedure_state_word(cockpit::ProcedureRunState s) {
  switch (s) {
    case cockpit::PROCEDURE_WAITING: return "waiting";
    case cockpit::PROCEDURE_RUNNING: return "running";
    case cockpit::PROCEDURE_COMPLETE: return "complete";
    case cockpit::PROCEDURE_INCOMPLETE: return "incomplete";
  }
  return "unknown";
}

const char* step_status_word(cockpit::ProcedureStepStatus s) {
  switch (s) {
    case cockpit::STEP_PENDING: return "pending";
    case cockpit::STEP_DONE: return "done";
    case cockpit::STEP_MISSED: return "missed";
  }
  return "unknown";
}

nlohmann::json seconds_or_null(int64_t ns) {
  return ns < 0 ? nlohmann::json(nullptr) : nlohmann::json(static_cast<double>(ns) * 1e-9);
}
}  // namespace

const char* sim_command_word(cockpit::SimCommandKind kind) {
  switch (kind) {
    case cockpit::FREEZE: return "freeze";
    case cockpit::UNFREEZE: return "unfreeze";
    case cockpit::RESET_TO_START: return "reset_start";
    case cockpit::SAVE_CHECKPOINT: return "save_checkpoint";
    case cockpit::RESET_TO_CHECKPOINT: return "reset_checkpoint";
    case cockpit::RESTART_REPLAY: return "restart_replay";
  }
  return "unknown";
}

void StationModel::on_status(const cockpit::NodeStatus& status, int64_t now_ns) {
  std::lock_guard<std::mutex> lock(mutex_);
  Node& node = nodes_[status.node_name().to_string()];
  node.status = status;
  node.taken_ns = now_ns;
}

void StationModel::note_sim_time(int64_t sim_time_ns) {
  if (!have_sim_time_ || sim_time_ns > sim_time_ns_) sim_time_ns_ = sim_time_ns;
  have_sim_time_ = true;
}

void StationModel::on_hand(const cockpit::HandState& hand) {
  std::lock_guard<std::mutex> lock(mutex_);
  Hand& h = hands_[hand.hand_id()];
  h.tracking = hand.tracking();
  h.holding = hand.grasped_object_id();
  note_sim_time(hand.sim_time_ns());
}

void StationModel::on_object_info(const cockpit::ObjectInfo& info) {
  std::lock_guard<std::mutex> lock(mutex_);
  object_names_[info.object_id()] = info.name().to_string();
}

void StationModel::on_object_state(const cockpit::ObjectState& state) {
  std::lock_guard<std::mutex> lock(mutex_);
  note_sim_time(state.sim_time_ns());
}

void StationModel::on_control_info(const cockpit::ControlInfo& info) {
  std::lock_guard<std::mutex> lock(mutex_);
  Control& c = controls_[info.control_id()];
  c.name = info.name().to_string();
  c.kind = control_kind_name(info.kind());
  c.positions = split_positions(info.position_names().to_string(), std::min<uint32_t>(info.position_count(), 8));
}

void StationModel::on_control_state(const cockpit::ControlState& state) {
  std::lock_guard<std::mutex> lock(mutex_);
  Control& c = controls_[state.control_id()];
  c.have_state = true;
  c.position = state.position();
  c.coordinate = state.coordinate();
  c.lit = state.lit();
  c.held_by = state.held_by_hand_id();
}

std::string StationModel::object_name(uint32_t id) const {
  const auto it = object_names_.find(id);
  return it != object_names_.end() ? it->second : "object " + std::to_string(id);
}

void StationModel::add_event(std::string kind, int64_t sim_time_ns, std::string text) {
  add_named_event(std::move(kind), sim_time_ns, std::move(text), Naming{}, std::string());
}

void StationModel::add_named_event(std::string kind, int64_t sim_time_ns, std::string text,
                                   Naming naming, std::string tail) {
  Event e;
  e.seq = next_event_seq_++;
  e.kind = std::move(kind);
  e.sim_time_s = ns_to_seconds(sim_time_ns);
  e.text = std::move(text);
  e.tail = std::move(tail);
  e.naming = naming;
  events_.push_back(std::move(e));
  while (events_.size() > kMaxEvents) events_.pop_front();
}

std::string StationModel::event_text(const Event& e) const {
  switch (e.naming.of) {
    case Naming::Of::kNothing: return e.text;
    case Naming::Of::kObject: return e.text + object_name(e.naming.id) + e.tail;
    case Naming::Of::kControl: {
      std::string name = "control " + std::to_string(e.naming.id);
      std::string from = std::to_string(e.naming.from);
      std::string to = std::to_string(e.naming.to);
      if (const auto it = controls_.find(e.naming.id); it != controls_.end()) {
        if (!it->second.name.empty()) name = it->second.name;
        const auto& p = it->second.positions;
        if (e.naming.from < p.size()) from = p[e.naming.from];
        if (e.naming.to < p.size()) to = p[e.naming.to];
      }
      return e.text + name + " " + from + " -> " + to + e.tail;
    }
  }
  return e.text;
}

void StationModel::on_grasp_event(const cockpit::GraspEvent& event) {
  std::lock_guard<std::mutex> lock(mutex_);
  const bool grasp = event.kind() == cockpit::GRASP;
  Naming naming;
  naming.of = Naming::Of::kObject;
  naming.id = event.object_id();
  add_named_event(grasp ? "grasp" : "release", event.sim_time_ns(), grasp ? "GRASP " : "RELEASE ", naming,
            std::string(" (") + side_name(event.hand_id()) + " hand): " + event.reason().to_string());
}

void StationModel::on_control_event(const cockpit::ControlEvent& event) {
  std::lock_guard<std::mutex> lock(mutex_);
  Naming naming;
  naming.of = Naming::Of::kControl;
  naming.id = event.control_id();
  naming.from = event.from_position();
  naming.to = event.to_position();
  std::string tail = std::string(" (") + control_cause_name(event.cause());
  if (event.hand_id() >= 0) tail += std::string(", ") + side_name(event.hand_id()) + " hand";
  add_named_event("control", event.sim_time_ns(), "CONTROL ", naming, tail + ")");
}

void StationModel::on_ack(const cockpit::SimAck& ack) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (const std::optional<bool> frozen = physics_frozen_after(ack)) frozen_ = *frozen;
  if (ack.sim_time_ns() >= 0) {  // the physics node's or the systems node's: the world's time
    note_sim_time(ack.sim_time_ns());
    if (ack.accepted() && ack.kind() == cockpit::SAVE_CHECKPOINT) {
      // the name is the detail's quoted word: "checkpoint 'NAME' saved at ..."
      const std::string d = ack.detail().to_string();
      const std::size_t a = d.find('\''), b = d.find('\'', a + 1);
      if (a != std::string::npos && b != std::string::npos) {
        const std::string name = d.substr(a + 1, b - a - 1);
        if (std::find(checkpoints_.begin(), checkpoints_.end(), name) == checkpoints_.end())
          checkpoints_.push_back(name);
      }
    }
  }
  last_ack_ = {{"seq", ack.command_seq()},
               {"source", ack.command_source().to_string()},
               {"command", sim_command_word(ack.kind())},
               {"node", ack.node_name().to_string()},
               {"accepted", ack.accepted()},
               {"detail", ack.detail().to_string()}};
  add_event("sim", std::max<int64_t>(ack.sim_time_ns(), 0),
            std::string("SIM ") + sim_command_word(ack.kind()) + " by " + ack.node_name().to_string() +
                (ack.accepted() ? ": " : " refused: ") + ack.detail().to_string());
}

void StationModel::on_command_sent(const std::string& text) {
  std::lock_guard<std::mutex> lock(mutex_);
  add_event("sim", have_sim_time_ ? sim_time_ns_ : 0, text);
}

void StationModel::on_preview(const cockpit::PreviewFrame& frame, int64_t now_ns) {
  std::lock_guard<std::mutex> lock(mutex_);
  png_.assign(frame.png().begin(), frame.png().end());
  frame_seq_ = frame.frame_seq();
  frame_sim_time_ns_ = frame.sim_time_ns();
  frame_width_px_ = frame.width_px();
  frame_height_px_ = frame.height_px();
  frame_taken_ns_ = now_ns;
}

nlohmann::json StationModel::state_json(int64_t now_ns) const {
  std::lock_guard<std::mutex> lock(mutex_);
  nlohmann::json j;
  j["stamp_s"] = ns_to_seconds(now_ns);
  j["sim"] = {{"sim_time_s", have_sim_time_ ? nlohmann::json(ns_to_seconds(sim_time_ns_))
                                            : nlohmann::json(nullptr)},
              {"frozen", frozen_},
              {"checkpoints", checkpoints_},
              {"last_ack", last_ack_}};
  nlohmann::json nodes = nlohmann::json::array();
  for (const auto& [name, node] : nodes_) {
    const cockpit::NodeStatus& s = node.status;
    const int64_t age_ns = now_ns - node.taken_ns;
    nodes.push_back({{"name", name},
                     {"state", node_state_name(s.state())},
                     {"detail", s.detail().to_string()},
                     {"loop_rate_hz", s.loop_rate_hz()},
                     {"input_rate_hz", s.input_rate_hz()},
                     {"late_steps", s.late_steps()},
                     {"rejected", s.rejected()},
                     {"glove_lost", s.glove_lost()},
                     {"age_s", ns_to_seconds(age_ns)},
                     {"alive", age_ns <= kStaleAfter_ns && s.state() != cockpit::STOPPING}});
  }
  j["nodes"] = nodes;
  nlohmann::json hands = nlohmann::json::array();
  for (const auto& [id, h] : hands_) {
    hands.push_back({{"hand_id", id},
                     {"side", side_name(id)},
                     {"tracking", h.tracking},
                     {"holding", h.holding >= 0 ? nlohmann::json(object_name(static_cast<uint32_t>(h.holding)))
                                                : nlohmann::json(nullptr)}});
  }
  j["hands"] = hands;
  nlohmann::json controls = nlohmann::json::array();
  for (const auto& [id, c] : controls_) {
    if (c.name.empty()) continue;  // a state before its info: not shown yet
    controls.push_back({{"control_id", id},
                        {"name", c.name},
                        {"kind", c.kind},
                        {"positions", c.positions},
                        {"position", c.position},
                        {"position_name", c.position < c.positions.size() ? c.positions[c.position] : ""},
                        {"coordinate", c.coordinate},
                        {"lit", c.lit},
                        {"held_by", c.held_by}});
  }
  j["controls"] = controls;
  if (png_.empty()) {
    j["view"] = nullptr;
  } else {
    j["view"] = {{"frame_seq", frame_seq_},
                 {"sim_time_s", ns_to_seconds(frame_sim_time_ns_)},
                 {"width_px", frame_width_px_},
                 {"height_px", frame_height_px_},
                 {"age_s", ns_to_seconds(now_ns - frame_taken_ns_)}};
  }
  // the aircraft: each system's value (a machine's as its state's name too), the failures, and
  // the lesson's live score; null without a systems node
  if (systems_.empty()) {
    j["systems"] = nullptr;
  } else {
    nlohmann::json values = nlohmann::json::object();
    for (std::size_t i = 0; i < systems_.size() && i < system_values_.size(); ++i) {
      const double v = system_values_[i];
      nlohmann::json entry = {{"value", std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr)},
                              {"unit", systems_[i].unit}};
      const auto& states = systems_[i].states;
      if (!states.empty() && v >= 0 && v < static_cast<double>(states.size()))
        entry["state"] = states[static_cast<std::size_t>(v)];
      values[systems_[i].name] = entry;
    }
    j["systems"] = {{"sim_time_s", seconds_or_null(systems_time_ns_)}, {"values", values}};
  }
  nlohmann::json failures = nlohmann::json::array();
  for (const FailureEntry& f : failures_)
    failures.push_back({{"name", f.name}, {"text", f.text}, {"inserted", f.inserted}});
  j["failures"] = failures;
  nlohmann::json procedures = nlohmann::json::array();
  for (const auto& [index, p] : procedures_) procedures.push_back(p);
  j["procedures"] = {{"lesson", lesson_}, {"list", procedures}};
  j["events_next"] = next_event_seq_;
  return j;
}

nlohmann::json StationModel::events_json(int64_t after) const {
  std::lock_guard<std::mutex> lock(mutex_);
  nlohmann::json list = nlohmann::json::array();
  std::size_t first = 0;
  if (after < 0) {
    first = events_.size() > kEventsPerReply ? events_.size() - kEventsPerReply : 0;
  } else {
    while (first < events_.size() && events_[first].seq <= after) ++first;
  }
  for (std::size_t i = first; i < events_.size() && list.size() < kEventsPerReply; ++i) {
    const Event& e = events_[i];
    list.push_back({{"seq", e.seq}, {"kind", e.kind}, {"sim_time_s", e.sim_time_s}, {"text", event_text(e)}});
  }
  const int64_t next = list.empty() ? (after < 0 ? next_event_seq_ : std::max<int64_t>(after + 1, 0))
                                    : list.back()["seq"].get<int64_t>() + 1;
  return {{"events", list}, {"next", next}};
}

bool StationModel::view_png(std::string& out) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (png_.empty()) return false;
  out = png_;
  return true;
}

// ---- the aircraft's systems -------------------------------------------------------------------


void StationModel::on_systems_info(const cockpit::SystemsInfo& info) {
  std::lock_guard<std::mutex> lock(mutex_);
  systems_.clear();
  for (const cockpit::SystemInfo& si : info.systems())
    systems_.push_back({si.name().to_string(), si.unit().to_string(), split_bar_list(si.state_names().to_string())});
  std::vector<FailureEntry> failures;
  for (const cockpit::FailureInfo& fi : info.failures()) {
    FailureEntry f{fi.name().to_string(), fi.text().to_string(), false};
    for (const FailureEntry& old : failures_)
      if (old.name == f.name) f.inserted = old.inserted;
    failures.push_back(f);
  }
  failures_ = std::move(failures);
  failures_known_ = true;
}

void StationModel::on_systems_state(const cockpit::SystemsState& state) {
  std::lock_guard<std::mutex> lock(mutex_);
  system_values_.assign(state.values().begin(), state.values().end());
  systems_time_ns_ = state.sim_time_ns();
  for (std::size_t f = 0; f < failures_.size() && f < state.failures().size(); ++f)
    failures_[f].inserted = state.failures()[f];
}

void StationModel::on_systems_event(const cockpit::SystemsEvent& event) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::string name = event.name().to_string();
  if (event.kind() == cockpit::SYSTEM_CHANGED) {
    add_event("system", event.sim_time_ns(),
              "SYSTEM " + name + " " + event.from_text().to_string() + " -> " + event.to_text().to_string());
  } else {
    const bool inserted = event.kind() == cockpit::FAILURE_INSERTED;
    for (FailureEntry& f : failures_)
      if (f.name == name) f.inserted = inserted;
    add_event("failure", event.sim_time_ns(), "FAILURE " + name + (inserted ? " inserted" : " cleared"));
  }
}

void StationModel::on_failure_ack(const cockpit::FailureAck& ack) {
  std::lock_guard<std::mutex> lock(mutex_);
  add_event("failure", std::max<int64_t>(ack.sim_time_ns(), 0),
            "FAILURE " + ack.failure().to_string() + (ack.accepted() ? ": " : " refused: ") +
                ack.detail().to_string() + " (#" + std::to_string(ack.command_seq()) + " from " +
                ack.command_source().to_string() + ")");
}

void StationModel::on_procedure_score(const cockpit::ProcedureScore& score) {
  std::lock_guard<std::mutex> lock(mutex_);
  lesson_ = score.lesson().to_string();
  nlohmann::json steps = nlohmann::json::array();
  for (const cockpit::ProcedureStepScore& st : score.steps()) {
    steps.push_back({{"item", st.item().to_string()},
                     {"action", st.action().to_string()},
                     {"status", step_status_word(st.status())},
                     {"out_of_order", st.out_of_order()},
                     {"late", st.late()},
                     {"undone", st.undone()},
                     {"done_s", seconds_or_null(st.done_time_ns())},
                     {"since_previous_s", seconds_or_null(st.since_previous_ns())}});
  }
  procedures_[score.index()] = {{"index", score.index()},
                                {"name", score.name().to_string()},
                                {"title", score.title().to_string()},
                                {"state", procedure_state_word(score.state())},
                                {"started_s", seconds_or_null(score.started_time_ns())},
                                {"ended_s", seconds_or_null(score.ended_time_ns())},
                                {"errors", score.errors()},
                                {"steps", steps}};
  // a lesson of fewer procedures (another systems node): drop those beyond it
  while (!procedures_.empty() && procedures_.rbegin()->first >= score.count())
    procedures_.erase(std::prev(procedures_.end()));
}

bool StationModel::knows_failures() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failures_known_;
}

bool StationModel::has_failure(const std::string& name) const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const FailureEntry& f : failures_)
    if (f.name == name) return true;
  return false;
}

bool StationModel::has_control_position(uint32_t control_id, uint32_t position) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = controls_.find(control_id);
  return it != controls_.end() && position < it->second.positions.size();
}

}  // namespace vcockpit::instructor
