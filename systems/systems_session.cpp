#include "systems/systems_session.hpp"

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "common/json_file.hpp"

namespace vcockpit::systems {

ScheduledFailure parse_scheduled_failure(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 >= text.size())
    throw std::invalid_argument("--failure-at '" + text + "': expected SECONDS:NAME");
  const std::string seconds = text.substr(0, colon);
  char* end = nullptr;
  const double t = std::strtod(seconds.c_str(), &end);
  if (*end != '\0' || !std::isfinite(t) || t < 0.0 || t > 1e6)
    throw std::invalid_argument("--failure-at '" + text + "': '" + seconds +
                                "' is not a time in seconds (0..1e6)");
  return {std::llround(t * 1e9), text.substr(colon + 1)};
}

SystemsSession::SystemsSession(SystemsModel model, std::vector<ControlSpec> controls,
                               SessionOptions options)
    : systems_(std::move(model), std::move(controls)), run_(systems_), options_(std::move(options)) {
  for (const ScheduledFailure& f : options_.failures) {
    const int i = systems_.failure_index(f.failure);
    if (i < 0) {
      std::string names;
      for (const Failure& known : systems_.model().failures) names += (names.empty() ? "" : ", ") + known.name;
      throw std::invalid_argument("--failure-at: no failure '" + f.failure + "' (failures: " + names + ")");
    }
    schedule_.emplace_back(f.time_ns, i);
  }
  std::stable_sort(schedule_.begin(), schedule_.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  if (options_.lesson) procedures_ = std::make_unique<ProcedureRunner>(*options_.lesson, systems_);
  if (!options_.out_dir.empty()) {
    recorder_ = std::make_unique<SystemsRecorder>(options_.out_dir, systems_);
    if (procedures_) score_log_ = std::make_unique<AtomicFile>(options_.out_dir + "/procedure_events.jsonl");
  }
}

void SystemsSession::record(const SystemsEvent& event) {
  ++events_;
  if (recorder_) recorder_->write(systems_, event);
}

int SystemsSession::take(const ControlFrame& frame, const Sink& sink) {
  const auto before = [&](int64_t t) {
    outcome_.events.clear();
    outcome_.score_events.clear();
    // a resumed run has already applied the failures before its time
    while (next_scheduled_ < schedule_.size() && schedule_[next_scheduled_].first <= t) {
      const auto [at, failure] = schedule_[next_scheduled_++];
      (void)at;
      if (auto e = systems_.set_failure(failure, true, t)) outcome_.events.push_back(*e);
    }
  };
  const auto after = [&](const Systems& s, const std::vector<SystemsEvent>& events) {
    outcome_.events.insert(outcome_.events.end(), events.begin(), events.end());
    for (const SystemsEvent& e : outcome_.events) record(e);
    if (recorder_) recorder_->after_step(s);
    if (procedures_) {
      procedures_->after_step(s, outcome_.score_events);
      record_scores();
    }
    if (sink) sink(s, outcome_);
  };
  return run_.take(frame, before, after);
}

std::string score_event_json(const ProcedureRunner& runner, const ScoreEvent& e) {
  const Procedure& p = runner.lesson().procedures[static_cast<std::size_t>(e.procedure)];
  nlohmann::ordered_json j;
  j["t_ns"] = e.time_ns;
  j["procedure"] = p.name;
  if (e.step >= 0) {
    const ProcedureStep& step = p.steps[static_cast<std::size_t>(e.step)];
    j["step"] = e.step + 1;
    j["item"] = step.item;
    j["action"] = step.action;
  }
  j["event"] = e.what;
  return j.dump();
}

void SystemsSession::record_scores() {
  if (!score_log_) return;
  for (const ScoreEvent& e : outcome_.score_events)
    score_log_->write(score_event_json(*procedures_, e) + "\n");
}

void SystemsSession::restore(const SystemsState& state) {
  systems_.restore(state);
  next_scheduled_ = 0;
  while (next_scheduled_ < schedule_.size() && schedule_[next_scheduled_].first <= state.time_ns)
    ++next_scheduled_;
}

void SystemsSession::reset_to_start(const Sink& sink) {
  outcome_.events.clear();
  outcome_.score_events.clear();
  systems_.reset_to_start(outcome_.events);
  for (const SystemsEvent& e : outcome_.events) record(e);
  if (procedures_) procedures_->reset();
  if (score_log_)
    score_log_->write("{\"t_ns\":" + std::to_string(systems_.state().time_ns) + ",\"event\":\"reset\"}\n");
  if (sink) sink(systems_, outcome_);
}

std::optional<SystemsEvent> SystemsSession::set_failure(int failure, bool inserted) {
  auto e = systems_.set_failure(failure, inserted);
  if (e) record(*e);
  return e;
}

static nlohmann::ordered_json score_json(const ProcedureRunner& runner) {
  const auto seconds = [](int64_t ns) {
    // to the millisecond (the steps are 10 ms apart): "3.59", not "3.5900000000000003"
    return ns < 0 ? nlohmann::ordered_json()
                  : nlohmann::ordered_json(std::round(static_cast<double>(ns) * 1e-6) / 1e3);
  };
  nlohmann::ordered_json j;
  j["lesson"] = std::filesystem::path(runner.lesson().source).stem().string();
  j["title"] = runner.lesson().title;
  int complete = 0, errors = 0, started = 0;
  nlohmann::ordered_json procedures = nlohmann::ordered_json::array();
  for (std::size_t p = 0; p < runner.scores().size(); ++p) {
    const Procedure& proc = runner.lesson().procedures[p];
    const ProcedureScore& score = runner.scores()[p];
    nlohmann::ordered_json pj;
    pj["name"] = proc.name;
    pj["title"] = proc.title;
    pj["state"] = state_name(score.state);
    pj["started_s"] = seconds(score.started_ns);
    pj["ended_s"] = seconds(score.ended_ns);
    pj["total_s"] = score.started_ns >= 0 && score.ended_ns >= 0 ? seconds(score.ended_ns - score.started_ns)
                                                                 : nlohmann::ordered_json();
    pj["errors"] = score.errors();
    nlohmann::ordered_json steps = nlohmann::ordered_json::array();
    for (std::size_t s = 0; s < score.steps.size(); ++s) {
      const StepScore& st = score.steps[s];
      const ProcedureStep& step = proc.steps[s];
      steps.push_back({{"item", step.item}, {"action", step.action},
                       {"status", status_name(st.status)}, {"done_s", seconds(st.done_ns)},
                       {"since_previous_s", seconds(st.since_previous_ns)},
                       {"out_of_order", st.out_of_order}, {"late", st.late},
                       {"undone", st.undone}, {"undone_s", seconds(st.undone_ns)}});
    }
    pj["steps"] = steps;
    procedures.push_back(pj);
    complete += score.state == ProcedureState::kComplete ? 1 : 0;
    started += score.state != ProcedureState::kWaiting ? 1 : 0;
    errors += score.errors();
  }
  j["procedures"] = procedures;
  j["started"] = started;
  j["complete"] = complete;
  j["errors"] = errors;
  return j;
}

std::string score_json_text(const ProcedureRunner& runner) { return json_text(score_json(runner), 2); }

void SystemsSession::finish(const Sink& sink) {
  if (procedures_) {
    outcome_.events.clear();
    outcome_.score_events.clear();
    procedures_->finish(systems_.state().time_ns, outcome_.score_events);
    record_scores();
    if (sink && !outcome_.score_events.empty()) sink(systems_, outcome_);
  }
  if (!recorder_) return;
  const SystemsState& s = systems_.state();
  nlohmann::ordered_json summary;
  summary["aircraft"] = options_.aircraft_path;
  summary["rate_hz"] = systems_.model().rate_hz;
  summary["steps"] = s.step;
  summary["last_step_t_s"] = static_cast<double>(s.time_ns) * 1e-9;
  const FrameCounts& c = run_.counts();
  summary["frames"] = {{"taken", c.taken}, {"missed", c.missed}, {"off_grid", c.off_grid},
                       {"stale", c.stale}, {"jumped", c.jumped}};
  summary["events"] = events_;
  nlohmann::ordered_json final_values = nlohmann::ordered_json::object();
  for (std::size_t e = 0; e < s.value.size(); ++e) {
    const Element& el = systems_.model().elements[e];
    if (el.kind == ElementKind::kMachine) {
      final_values[el.name] = systems_.value_text(static_cast<int>(e), s.value[e]);
    } else {
      final_values[el.name] = s.value[e];
    }
  }
  summary["final"] = final_values;
  nlohmann::ordered_json failures = nlohmann::ordered_json::array();
  for (std::size_t f = 0; f < s.failure.size(); ++f)
    if (s.failure[f] != 0) failures.push_back(systems_.model().failures[f].name);
  summary["failures_inserted"] = failures;
  if (procedures_) {
    summary["procedures"] = {{"started", 0}, {"complete", 0}, {"errors", 0}};
    const nlohmann::ordered_json score = score_json(*procedures_);
    for (const char* key : {"started", "complete", "errors"}) summary["procedures"][key] = score[key];
    write_json_file(options_.out_dir + "/procedures.json", score);
    score_log_->commit();
  }
  write_json_file(options_.out_dir + "/systems_summary.json", summary);
  recorder_->commit();
}

}  // namespace vcockpit::systems
