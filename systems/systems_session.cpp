#include "systems/systems_session.hpp"

#include <algorithm>
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
  if (!options_.out_dir.empty()) recorder_ = std::make_unique<SystemsRecorder>(options_.out_dir, systems_);
}

void SystemsSession::record(const SystemsEvent& event) {
  ++events_;
  if (recorder_) recorder_->write(systems_, event);
}

int SystemsSession::take(const ControlFrame& frame, const SystemsRun::StepSink& sink) {
  const auto before = [&](int64_t t) {
    step_events_.clear();
    // a resumed run has already applied the failures before its time
    while (next_scheduled_ < schedule_.size() && schedule_[next_scheduled_].first <= t) {
      const auto [at, failure] = schedule_[next_scheduled_++];
      (void)at;
      if (auto e = systems_.set_failure(failure, true, t)) step_events_.push_back(*e);
    }
  };
  const auto after = [&](const Systems& s, const std::vector<SystemsEvent>& events) {
    for (const SystemsEvent& e : step_events_) record(e);
    for (const SystemsEvent& e : events) record(e);
    if (recorder_) recorder_->after_step(s);
    if (sink) {
      step_events_.insert(step_events_.end(), events.begin(), events.end());
      sink(s, step_events_);
    }
  };
  return run_.take(frame, before, after);
}

std::optional<SystemsEvent> SystemsSession::set_failure(int failure, bool inserted) {
  auto e = systems_.set_failure(failure, inserted);
  if (e) record(*e);
  return e;
}

void SystemsSession::finish() {
  if (!recorder_) return;
  const SystemsState& s = systems_.state();
  nlohmann::ordered_json summary;
  summary["aircraft"] = options_.aircraft_path;
  summary["rate_hz"] = systems_.model().rate_hz;
  summary["steps"] = s.step;
  summary["last_step_t_s"] = static_cast<double>(s.time_ns) * 1e-9;
  const FrameCounts& c = run_.counts();
  summary["frames"] = {{"taken", c.taken}, {"missed", c.missed}, {"off_grid", c.off_grid},
                       {"stale", c.stale}};
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
  write_json_file(options_.out_dir + "/systems_summary.json", summary);
  recorder_->commit();
}

}  // namespace vcockpit::systems
