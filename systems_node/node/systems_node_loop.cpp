#include "systems_node/node/systems_node_loop.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>

#include "common/clock.hpp"
#include "common/signals.hpp"
#include "idl/topics/bar_list.hpp"
#include "idl/topics/systems_topics.hpp"
#include "systems/systems_checkpoint.hpp"

namespace vcockpit::systems_node {
namespace {

using systems::Systems;
using systems::SystemsEvent;

constexpr std::size_t kMaxWaitingFrames = 1000;  // 10 s at 100 Hz

// A frame from DDS and the world's resets to the start when it was sent.
struct Frame {
  systems::ControlFrame controls;
  uint32_t start_resets = 0;
};

Frame from_msg(const cockpit::ControlFrame& msg) {
  Frame f;
  f.controls.time_ns = msg.sim_time_ns();
  f.controls.position.assign(msg.position().begin(), msg.position().end());
  f.controls.q.assign(msg.coordinate().begin(), msg.coordinate().end());
  f.start_resets = msg.start_resets();
  return f;
}

// Whether a frame can be stepped on: the bound controls' count, each position one of its
// control's, every coordinate finite, a time that is not negative (what control_frames.csv's
// reader demands of a file).
bool valid(const systems::ControlFrame& f, const std::vector<systems::ControlSpec>& controls) {
  if (f.time_ns < 0 || f.position.size() != controls.size() || f.q.size() != controls.size())
    return false;
  for (std::size_t c = 0; c < controls.size(); ++c) {
    if (f.position[c] < 0 || static_cast<std::size_t>(f.position[c]) >= controls[c].positions.size())
      return false;
    if (!std::isfinite(f.q[c])) return false;
  }
  return true;
}

cockpit::SystemKind kind_of(systems::ElementKind k) {
  switch (k) {
    case systems::ElementKind::kLogic: return cockpit::SYSTEM_LOGIC;
    case systems::ElementKind::kLag: return cockpit::SYSTEM_LAG;
    case systems::ElementKind::kRate: return cockpit::SYSTEM_RATE;
    case systems::ElementKind::kTimer: return cockpit::SYSTEM_TIMER;
    case systems::ElementKind::kLatch: return cockpit::SYSTEM_LATCH;
    case systems::ElementKind::kMachine: return cockpit::SYSTEM_MACHINE;
  }
  return cockpit::SYSTEM_LOGIC;
}

// At most n bytes, never splitting a UTF-8 character (a split one makes invalid JSON downstream).
std::string clipped(const std::string& s, std::size_t n) {
  if (s.size() <= n) return s;
  std::size_t end = n;
  while (end > 0 && (static_cast<unsigned char>(s[end]) & 0xC0) == 0x80) --end;
  return s.substr(0, end);
}

class Node {
 public:
  Node(DdsParticipant& participant, systems::SystemsModel model, const NodeOptions& options)
      : model_(std::move(model)),
        options_(options),
        info_reader_(participant.make_reader<cockpit::ControlInfo>("state")),
        frame_reader_(participant.make_reader<cockpit::ControlFrame>("control_frames")),
        failure_reader_(participant.make_reader<cockpit::FailureCommand>("command")),
        sim_reader_(participant.make_reader<cockpit::SimCommand>("command")),
        sim_ack_writer_(participant.make_writer<cockpit::SimAck>("event")),
        info_writer_(participant.make_writer<cockpit::SystemsInfo>("state")),
        state_writer_(participant.make_writer<cockpit::SystemsState>("state")),
        event_writer_(participant.make_writer<cockpit::SystemsEvent>("event")),
        ack_writer_(participant.make_writer<cockpit::FailureAck>("command")),
        score_writer_(participant.make_writer<cockpit::ProcedureScore>("state")),
        status_writer_(participant.make_writer<cockpit::NodeStatus>("state")) {
    if (model_.elements.size() > 128) throw systems::ModelError(model_.source + ": at most 128 systems (cockpit/systems_state)");
    if (model_.failures.size() > 32) throw systems::ModelError(model_.source + ": at most 32 failures (cockpit/systems_state)");
    if (!options_.checkpoint_path.empty()) {
      const auto dir = std::filesystem::path(options_.checkpoint_path).parent_path();
      if (!dir.empty()) std::filesystem::create_directories(dir);
    }
  }

  int run() {
    const int64_t start_ns = monotonic_now_ns();
    int64_t next_status_ns = start_ns;
    while (!shutdown_requested()) {
      const int64_t now = monotonic_now_ns();
      if (options_.duration_s > 0 && now - start_ns >= static_cast<int64_t>(options_.duration_s * 1e9)) break;
      take_infos();
      take_frames();
      if (!session_ && try_bind() && !session_) return 1;
      if (session_) {
        drain_waiting();
        take_failure_commands();
        take_sim_commands();
        maybe_checkpoint(false);
      }
      if (now >= next_status_ns) {
        publish_status(now);
        next_status_ns = now + 1'000'000'000;
      }
      // asleep until a frame comes (or 20 ms: commands, status); no polling on a busy machine
      frame_reader_.wait_for_data(20'000'000);
    }
    // The physics is stopped with us and flushes its last frames as it goes: they are taken
    // while its writer is still there (at most 1 s: a killed one stays matched until its lease
    // ends), so the run's end is scored on the whole run.
    const int64_t drain_end_ns = monotonic_now_ns() + 1'000'000'000;
    while (monotonic_now_ns() < drain_end_ns) {
      take_frames();
      if (frame_reader_.matched_count() == 0) break;
      frame_reader_.wait_for_data(20'000'000);
    }
    take_frames();
    if (session_) {
      drain_waiting();
      maybe_checkpoint(true);
      session_->finish([this](const Systems&, const systems::StepOutcome& outcome) {
        publish_scores(outcome.score_events);
      });
      // the final scores must reach the launcher's summary
      wait_for_acknowledgments({&score_writer_, &event_writer_, &state_writer_}, 500'000'000);
      const auto& c = session_->counts();
      spdlog::info("stopped at step {} (t {:.3f} s): {} frames taken, {} periods without a frame, "
                   "{} stale, {} off the grid; {} events",
                   session_->systems().state().step,
                   static_cast<double>(session_->systems().state().time_ns) * 1e-9, c.taken,
                   c.missed, c.stale, c.off_grid, session_->events());
    } else {
      spdlog::warn("stopped before the controls were known: no systems ran");
    }
    return 0;
  }

 private:
  void take_infos() {
    cockpit::ControlInfo info;
    while (info_reader_.take(info)) {
      systems::ControlSpec spec;
      spec.name = info.name().to_string();
      spec.revolute = info.joint() == cockpit::REVOLUTE;
      spec.positions = split_bar_list(info.position_names().to_string());
      controls_[info.control_id()] = spec;
    }
  }

  void take_frames() {
    cockpit::ControlFrame msg;
    while (frame_reader_.take(msg)) {
      if (msg.position().size() != msg.coordinate().size()) {
        refuse("its positions and coordinates differ in number");
        continue;
      }
      // before binding, the first frames say how many controls to wait for
      if (!session_) expected_controls_ = static_cast<int>(msg.position().size());
      if (waiting_.size() >= kMaxWaitingFrames) waiting_.pop_front();
      waiting_.push_back(from_msg(msg));
    }
  }

  void refuse(const char* why) {
    if (malformed_++ == 0) spdlog::warn("a control frame refused: {} (counted from now on)", why);
  }

  // True when it tried (bound, or failed: session_ stays empty and the node exits).
  bool try_bind() {
    if (expected_controls_ < 0) return false;
    std::vector<systems::ControlSpec> specs;
    for (int i = 0; i < expected_controls_; ++i) {
      const auto it = controls_.find(static_cast<uint32_t>(i));
      if (it == controls_.end()) return false;
      specs.push_back(it->second);
    }
    try {
      session_ = std::make_unique<systems::SystemsSession>(model_, specs, options_.session);
    } catch (const std::exception& e) {
      spdlog::error("{}", e.what());
      return true;
    }
    spdlog::info("bound to {} controls: {} systems, {} failures, a step every {} ms", specs.size(),
                 model_.elements.size(), model_.failures.size(),
                 session_->systems().period_ns() / 1'000'000);
    if (options_.resume) resume();
    publish_info();
    publish_scores({});
    next_checkpoint_ns_ = session_->systems().state().time_ns +
                          static_cast<int64_t>(options_.checkpoint_every_s * 1e9);
    return true;
  }

  void resume() {
    const std::string& path = options_.checkpoint_path;
    if (path.empty() || !std::filesystem::exists(path)) {
      spdlog::info("--resume: no checkpoint{}, starting from the start", path.empty() ? "" : " at " + path);
      return;
    }
    try {
      systems::SystemsCheckpoint saved =
          systems::read_systems_checkpoint(path, session_->systems(), session_->procedures());
      session_->restore(saved.state);
      if (session_->procedures() != nullptr) session_->procedures()->restore(saved.scores);
      spdlog::info("resumed from {}: step {}, t {:.3f} s", path, session_->systems().state().step,
                   static_cast<double>(session_->systems().state().time_ns) * 1e-9);
    } catch (const std::exception& e) {
      std::error_code ignored;
      std::filesystem::rename(path, path + ".bad", ignored);
      spdlog::warn("--resume: {} (kept as {}.bad); starting from the start", e.what(), path);
    }
  }

  void drain_waiting() {
    const auto publish = [this](const Systems& s, const systems::StepOutcome& outcome) {
      for (const SystemsEvent& e : outcome.events) publish_event(s, e);
      publish_state_if_changed(s);
      publish_scores(outcome.score_events);
    };
    while (!waiting_.empty()) {
      const Frame frame = std::move(waiting_.front());
      waiting_.pop_front();
      if (!valid(frame.controls, session_->systems().controls())) {
        refuse("not the bound controls' count, a position out of range, a coordinate not "
               "finite or a negative time");
        continue;
      }
      // the world went back to the scene's start (an instructor's reset): so do the systems and
      // the scores, at this point of the stream
      if (seen_resets_ && frame.start_resets != start_resets_) {
        session_->reset_to_start(publish);
        spdlog::info("the world was reset to its start: the systems and the scores start again at "
                     "{:.3f} s", static_cast<double>(session_->systems().state().time_ns) * 1e-9);
        if (session_->procedures() != nullptr)
          for (std::size_t p = 0; p < session_->procedures()->scores().size(); ++p)
            publish_score(*session_->procedures(), p);
        maybe_checkpoint(true);
      }
      seen_resets_ = true;
      start_resets_ = frame.start_resets;
      session_->take(frame.controls, publish);
    }
  }

  // The procedures a change touched (all of them once, when bound).
  void publish_scores(const std::vector<systems::ScoreEvent>& changes) {
    const systems::ProcedureRunner* runner = session_->procedures();
    if (runner == nullptr) return;
    std::vector<bool> changed(runner->scores().size(), changes.empty() && !scores_published_);
    for (const systems::ScoreEvent& e : changes) {
      changed[static_cast<std::size_t>(e.procedure)] = true;
      log_score_event(*runner, e);
    }
    scores_published_ = true;
    for (std::size_t p = 0; p < changed.size(); ++p)
      if (changed[p]) publish_score(*runner, p);
  }

  static void log_score_event(const systems::ProcedureRunner& runner, const systems::ScoreEvent& e) {
    const systems::Procedure& p = runner.lesson().procedures[static_cast<std::size_t>(e.procedure)];
    const double t_s = static_cast<double>(e.time_ns) * 1e-9;
    if (e.step < 0) {
      spdlog::info("procedure '{}' {} at {:.2f} s", p.title, e.what, t_s);
    } else {
      const systems::ProcedureStep& step = p.steps[static_cast<std::size_t>(e.step)];
      spdlog::info("procedure '{}' step {} ({} {}) {} at {:.2f} s", p.title, e.step + 1, step.item,
                   step.action, e.what, t_s);
    }
  }

  void publish_score(const systems::ProcedureRunner& runner, std::size_t p) {
    const systems::Procedure& proc = runner.lesson().procedures[p];
    const systems::ProcedureScore& score = runner.scores()[p];
    cockpit::ProcedureScore msg;
    msg.index(static_cast<uint32_t>(p));
    msg.count(static_cast<uint32_t>(runner.scores().size()));
    msg.lesson(clipped(runner.lesson().title, 64));
    msg.name(clipped(proc.name, 64));
    msg.title(clipped(proc.title, 64));
    msg.state(static_cast<cockpit::ProcedureRunState>(static_cast<int>(score.state)));
    msg.started_time_ns(score.started_ns);
    msg.ended_time_ns(score.ended_ns);
    msg.errors(static_cast<uint32_t>(score.errors()));
    for (std::size_t s = 0; s < score.steps.size(); ++s) {
      const systems::StepScore& st = score.steps[s];
      cockpit::ProcedureStepScore m;
      m.item(clipped(proc.steps[s].item, 64));
      m.action(clipped(proc.steps[s].action, 64));
      m.status(static_cast<cockpit::ProcedureStepStatus>(static_cast<int>(st.status)));
      m.out_of_order(st.out_of_order);
      m.late(st.late);
      m.undone(st.undone);
      m.done_time_ns(st.done_ns);
      m.since_previous_ns(st.since_previous_ns);
      m.undone_time_ns(st.undone_ns);
      msg.steps().push_back(m);
    }
    score_writer_.write(msg);
  }

  void take_failure_commands() {
    cockpit::FailureCommand cmd;
    while (failure_reader_.take(cmd)) {
      cockpit::FailureAck ack;
      ack.command_seq(cmd.seq());
      ack.command_source(cmd.source());
      ack.failure(cmd.failure());
      ack.sim_time_ns(session_->systems().state().time_ns);
      const std::string failure = cmd.failure().to_string();
      const std::string source = cmd.source().to_string();
      const int f = session_->systems().failure_index(failure);
      if (f < 0) {
        ack.accepted(false);
        ack.detail(clipped("no failure '" + failure + "'", 128));
        spdlog::warn("failure command from '{}': no failure '{}'", source, failure);
      } else {
        const auto event = session_->set_failure(f, cmd.inserted());
        ack.accepted(true);
        ack.detail(event ? (cmd.inserted() ? "inserted" : "cleared")
                         : (cmd.inserted() ? "was already inserted" : "was not inserted"));
        spdlog::info("failure '{}' {} by '{}'", failure, ack.detail().to_string(), source);
        if (event) publish_event(session_->systems(), *event);
        publish_state(session_->systems());
      }
      ack_writer_.write(ack);
    }
  }

  // The instructor's reset to the start is the physics': the systems and the scores start again
  // with the first control frame that counts it (drain_waiting), so they reset exactly where the
  // controls did. Here it is acknowledged. Other sim commands are the physics' and the glove
  // drivers': frozen, the physics sends no frames, and the systems wait.
  void take_sim_commands() {
    cockpit::SimCommand cmd;
    while (sim_reader_.take(cmd)) {
      if (cmd.kind() != cockpit::RESET_TO_START) continue;
      const Systems& s = session_->systems();
      spdlog::info("sim command from '{}': reset to the start, with the physics' reset",
                   cmd.source().to_string());
      cockpit::SimAck ack;
      ack.command_seq(cmd.seq());
      ack.command_source(cmd.source());
      ack.kind(cmd.kind());
      ack.node_name(clipped(options_.node_name, 32));
      ack.accepted(true);
      ack.detail("systems and procedure scores back to the start with the physics reset");
      ack.sim_time_ns(s.state().time_ns);
      ack.frozen(false);
      sim_ack_writer_.write(ack);
    }
  }

  void maybe_checkpoint(bool force) {
    if (options_.checkpoint_path.empty() || !session_->run_started()) return;
    const int64_t t = session_->systems().state().time_ns;
    if (!force && t < next_checkpoint_ns_) return;
    try {
      systems::write_systems_checkpoint(options_.checkpoint_path, session_->systems(),
                                        session_->procedures());
      ++checkpoints_;
    } catch (const std::exception& e) {
      spdlog::warn("checkpoint: {}", e.what());
    }
    next_checkpoint_ns_ = t + static_cast<int64_t>(options_.checkpoint_every_s * 1e9);
  }

  void publish_info() {
    const Systems& s = session_->systems();
    cockpit::SystemsInfo info;
    info.aircraft(clipped(options_.session.aircraft_path, 256));
    info.rate_hz(s.model().rate_hz);
    info.model_hash(s.model_hash());
    for (const systems::Element& e : s.model().elements) {
      cockpit::SystemInfo si;
      si.name(clipped(e.name, 64));
      si.kind(kind_of(e.kind));
      si.unit(clipped(e.unit, 16));
      std::string states;
      for (const std::string& st : e.states) states += st + "|";
      si.state_names(clipped(states, 512));
      info.systems().push_back(si);
    }
    for (const systems::Failure& f : s.model().failures) {
      cockpit::FailureInfo fi;
      fi.name(clipped(f.name, 64));
      fi.text(clipped(f.text, 128));
      info.failures().push_back(fi);
    }
    info_writer_.write(info);
  }

  // After every step whose values or failures changed, and at least every second of simulated
  // time (a resting aircraft costs its readers one sample a second: at 100 a second beside the
  // renderer and the monitor, the rig's glove-to-frame p99 rose from 35 to 54 ms on two cores);
  // after a command or a reset too. A reader keeps the last (transient local).
  void publish_state_if_changed(const Systems& s) {
    if (s.state().value == last_values_ && s.state().failure == last_failures_ &&
        s.state().time_ns - last_state_ns_ < 1'000'000'000)
      return;
    publish_state(s);
  }

  void publish_state(const Systems& s) {
    last_values_ = s.state().value;
    last_failures_ = s.state().failure;
    last_state_ns_ = s.state().time_ns;
    state_msg_.step(static_cast<uint64_t>(s.state().step));
    state_msg_.sim_time_ns(s.state().time_ns);
    state_msg_.values().assign(s.state().value.begin(), s.state().value.end());
    state_msg_.failures().clear();
    for (uint8_t f : s.state().failure) state_msg_.failures().push_back(f != 0);
    state_writer_.write(state_msg_);
    ++states_published_;
  }

  void publish_event(const Systems& s, const SystemsEvent& e) {
    cockpit::SystemsEvent msg;
    msg.seq(++event_seq_);
    msg.sim_time_ns(e.time_ns);
    msg.index(static_cast<uint32_t>(e.index));
    msg.from_value(e.from);
    msg.to_value(e.to);
    if (e.kind == systems::SystemsEventKind::kChange) {
      msg.kind(cockpit::SYSTEM_CHANGED);
      msg.name(clipped(s.model().elements[static_cast<std::size_t>(e.index)].name, 64));
      msg.from_text(clipped(s.value_text(e.index, e.from), 64));
      msg.to_text(clipped(s.value_text(e.index, e.to), 64));
    } else {
      msg.kind(e.kind == systems::SystemsEventKind::kFailureInserted ? cockpit::FAILURE_INSERTED
                                                                     : cockpit::FAILURE_CLEARED);
      msg.name(clipped(s.model().failures[static_cast<std::size_t>(e.index)].name, 64));
      msg.from_text(e.from != 0.0 ? "inserted" : "clear");
      msg.to_text(e.to != 0.0 ? "inserted" : "clear");
    }
    event_writer_.write(msg);
  }

  void publish_status(int64_t now_ns) {
    cockpit::NodeStatus st;
    st.node_name(options_.node_name);
    st.stamp_ns(now_ns);
    st.state(session_ ? cockpit::RUNNING : cockpit::STARTING);
    if (session_) {
      const auto& c = session_->counts();
      const double dt_s = last_status_ns_ > 0 ? static_cast<double>(now_ns - last_status_ns_) * 1e-9 : 0.0;
      const uint64_t steps = static_cast<uint64_t>(session_->systems().state().step);
      st.loop_rate_hz(dt_s > 0 ? static_cast<double>(steps - last_steps_) / dt_s : 0.0);
      st.input_rate_hz(dt_s > 0 ? static_cast<double>(c.taken - last_taken_) / dt_s : 0.0);
      last_steps_ = steps;
      last_taken_ = c.taken;
      st.received(c.taken);
      st.rejected_stale(c.stale);
      st.rejected(c.stale + c.off_grid + malformed_);
      st.detail(clipped("t " + std::to_string(static_cast<double>(session_->systems().state().time_ns) * 1e-9) +
                            " s, " + std::to_string(c.missed) + " periods without a frame, " +
                            std::to_string(checkpoints_) + " checkpoints",
                        128));
    } else {
      st.detail(expected_controls_ < 0 ? "waiting for cockpit/control_frame"
                                       : "waiting for every control's cockpit/control_info");
    }
    st.published(states_published_);
    st.input_alive(session_ != nullptr);
    last_status_ns_ = now_ns;
    status_writer_.write(st);
  }

  systems::SystemsModel model_;
  const NodeOptions& options_;
  Reader<cockpit::ControlInfo> info_reader_;
  Reader<cockpit::ControlFrame> frame_reader_;
  Reader<cockpit::FailureCommand> failure_reader_;
  Reader<cockpit::SimCommand> sim_reader_;
  Writer<cockpit::SimAck> sim_ack_writer_;
  Writer<cockpit::SystemsInfo> info_writer_;
  Writer<cockpit::SystemsState> state_writer_;
  Writer<cockpit::SystemsEvent> event_writer_;
  Writer<cockpit::FailureAck> ack_writer_;
  Writer<cockpit::ProcedureScore> score_writer_;
  Writer<cockpit::NodeStatus> status_writer_;
  std::map<uint32_t, systems::ControlSpec> controls_;
  int expected_controls_ = -1;
  std::deque<Frame> waiting_;
  bool seen_resets_ = false;    // a frame has said how many resets the world has had
  uint32_t start_resets_ = 0;
  std::unique_ptr<systems::SystemsSession> session_;
  cockpit::SystemsState state_msg_;
  std::vector<double> last_values_;    // what the last systems_state said
  std::vector<uint8_t> last_failures_;
  int64_t last_state_ns_ = 0;
  uint64_t event_seq_ = 0;
  uint64_t states_published_ = 0;
  uint64_t malformed_ = 0;
  bool scores_published_ = false;
  uint64_t checkpoints_ = 0;
  int64_t next_checkpoint_ns_ = 0;
  int64_t last_status_ns_ = 0;
  uint64_t last_steps_ = 0;
  uint64_t last_taken_ = 0;
};

}  // namespace

int run_node(DdsParticipant& participant, systems::SystemsModel model, const NodeOptions& options) {
  Node node(participant, std::move(model), options);
  return node.run();
}

}  // namespace vcockpit::systems_node
