#include "systems/systems_engine.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

namespace vcockpit::systems {
namespace {

[[noreturn]] void fail(const Origin& origin, const std::string& message) {
  throw ModelError(origin + ": " + message);
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

int index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

// FNV-1a over a canonical text of the model
uint64_t fnv1a(const std::string& text) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

double truth(bool b) { return b ? 1.0 : 0.0; }

}  // namespace

const char* element_kind_name(ElementKind kind) {
  switch (kind) {
    case ElementKind::kLogic: return "logic";
    case ElementKind::kLag: return "lag";
    case ElementKind::kRate: return "rate";
    case ElementKind::kTimer: return "timer";
    case ElementKind::kLatch: return "latch";
    case ElementKind::kMachine: return "machine";
  }
  return "?";
}

class Systems::Reader final : public RefReader {
 public:
  explicit Reader(const Systems& s) : s_(s) {}
  double read(const Ref& ref) const override {
    const SystemsState& st = s_.state_;
    const auto i = static_cast<std::size_t>(ref.index);
    switch (ref.kind) {
      case RefKind::kElement: return st.value[i];
      case RefKind::kMachineIn: return truth(st.value[i] == ref.arg);
      case RefKind::kMachineTime:
        return static_cast<double>(st.step - st.since_step[i]) * s_.period_s_;
      case RefKind::kControlIn: return truth(s_.frame_.position[i] == ref.arg);
      case RefKind::kControlQ:  // the frame's SI coordinate, in the file's units (deg for angles)
        return s_.controls_[i].revolute ? s_.frame_.q[i] * (180.0 / M_PI) : s_.frame_.q[i];
      case RefKind::kControlPosition: return s_.frame_.position[i];
      case RefKind::kFailure: return st.failure[i];
      case RefKind::kTime: return static_cast<double>(st.step) * s_.period_s_;
    }
    return 0.0;
  }

 private:
  const Systems& s_;
};

Systems::Systems(SystemsModel model, std::vector<ControlSpec> controls)
    : model_(std::move(model)), controls_(std::move(controls)) {
  bind();
}

void Systems::bind() {
  const double hz = model_.rate_hz;
  if (!(hz >= 1.0 && hz <= 10000.0)) fail(model_.rate_origin, "rate_hz must be within 1..10000");
  period_ns_ = std::llround(1e9 / hz);
  if (std::abs(static_cast<double>(period_ns_) - 1e9 / hz) > 1e-6)
    fail(model_.rate_origin, "rate_hz must give a whole number of nanoseconds a step");
  period_s_ = static_cast<double>(period_ns_) * 1e-9;

  // one namespace: elements, failures, controls, time_s
  std::set<std::string> taken{"time_s"};
  for (const ControlSpec& c : controls_) taken.insert(c.name);
  for (const Failure& f : model_.failures) {
    if (!taken.insert(f.name).second) fail(f.origin, "the name '" + f.name + "' is already taken");
  }
  for (const Element& e : model_.elements) {
    if (!taken.insert(e.name).second)
      fail(e.origin, "the name '" + e.name + "' is already taken (by a control, failure or system)");
  }
  std::vector<std::string> failure_names;
  for (const Failure& f : model_.failures) failure_names.push_back(f.name);

  const auto bind_expression = [&](SourceExpression& se) { this->bind_expression(se); };

  std::string canonical = std::to_string(period_ns_) + ";";
  for (const ControlSpec& c : controls_)
    canonical += "c:" + c.name + (c.revolute ? ":r:" : ":p:") + joined(c.positions) + ";";
  for (const Failure& f : model_.failures) canonical += "f:" + f.name + ";";

  lag_factor_.assign(model_.elements.size(), 0.0);
  transitions_.assign(model_.elements.size(), {});
  state_ = {};
  state_.value.assign(model_.elements.size(), 0.0);
  state_.since_step.assign(model_.elements.size(), 0);
  state_.last_input.assign(model_.elements.size(), 0.0);
  state_.failure.assign(model_.failures.size(), 0);
  for (std::size_t i = 0; i < model_.elements.size(); ++i) {
    Element& el = model_.elements[i];
    // everything that changes what a state means: a checkpoint of an edited model is refused
    char numbers[128];
    std::snprintf(numbers, sizeof numbers, ":%a:%a:%a:", el.tau_s, el.per_s, el.initial);
    canonical += "e:" + el.name + ":" + element_kind_name(el.kind) + ":" + joined(el.states) + ":" +
                 el.initial_state + numbers + el.input.expression.text() + ":" +
                 el.reset.expression.text() + ";";
    bind_expression(el.input);
    bind_expression(el.reset);
    switch (el.kind) {
      case ElementKind::kLag:
        if (!(el.tau_s > 0.0 && std::isfinite(el.tau_s))) fail(el.origin, "tau_s must be positive");
        lag_factor_[i] = -std::expm1(-period_s_ / el.tau_s);
        state_.value[i] = el.initial;
        break;
      case ElementKind::kRate:
        if (!(el.per_s > 0.0 && std::isfinite(el.per_s))) fail(el.origin, "per_s must be positive");
        state_.value[i] = el.initial;
        break;
      case ElementKind::kTimer: state_.since_step[i] = -1; break;
      case ElementKind::kMachine: {
        if (el.states.empty()) fail(el.origin, "a machine needs states");
        std::set<std::string> unique(el.states.begin(), el.states.end());
        if (unique.size() != el.states.size()) fail(el.origin, "a state is named twice");
        const std::string initial = el.initial_state.empty() ? el.states.front() : el.initial_state;
        const int s0 = index_of(el.states, initial);
        if (s0 < 0) fail(el.origin, "initial state '" + initial + "' is not among its states (" + joined(el.states) + ")");
        state_.value[i] = s0;
        for (Transition& t : el.transitions) {
          BoundTransition b;
          b.from.assign(el.states.size(), t.from.empty() ? 1 : 0);
          for (const std::string& s : t.from) {
            const int k = index_of(el.states, s);
            if (k < 0) fail(t.origin, "no state '" + s + "' (states: " + joined(el.states) + ")");
            b.from[static_cast<std::size_t>(k)] = 1;
          }
          b.to = index_of(el.states, t.to);
          if (b.to < 0) fail(t.origin, "no state '" + t.to + "' (states: " + joined(el.states) + ")");
          if (!(t.after_s >= 0.0 && t.after_s <= 1e6)) fail(t.origin, "after_s must be within 0..1e6 s");
          // the first step at or past after_s (a whole number of steps, within rounding)
          b.after_steps = static_cast<int64_t>(std::ceil(t.after_s / period_s_ - 1e-9));
          for (const std::string& c : t.clears) {
            const int f = index_of(failure_names, c);
            if (f < 0) fail(t.origin, "no failure '" + c + "' to clear");
            b.clears.push_back(f);
          }
          bind_expression(t.when);
          char after[40];
          std::snprintf(after, sizeof after, ":%a:", t.after_s);
          canonical += "t:" + joined(t.from) + ">" + t.to + after + t.when.expression.text() + ":" +
                       joined(t.clears) + ";";
          transitions_[i].push_back(std::move(b));
        }
        break;
      }
      case ElementKind::kLogic:
      case ElementKind::kLatch: break;
    }
    if (el.kind != ElementKind::kMachine && el.input.expression.empty())
      fail(el.origin, std::string("a ") + element_kind_name(el.kind) + " needs its input");
  }
  model_hash_ = fnv1a(canonical);
  initial_ = state_;
  frame_.position.assign(controls_.size(), 0);
  frame_.q.assign(controls_.size(), 0.0);
}

Ref Systems::resolve(const Name& n) const {
  std::vector<std::string> element_names, failure_names;
  for (const Element& e : model_.elements) element_names.push_back(e.name);
  for (const Failure& f : model_.failures) failure_names.push_back(f.name);
  if (n.name == "time_s" && n.member.empty()) return {RefKind::kTime, 0, 0};
  const int e = index_of(element_names, n.name);
  if (e >= 0) {
    const Element& el = model_.elements[static_cast<std::size_t>(e)];
    if (n.member.empty()) return {RefKind::kElement, e, 0};
    if (el.kind != ElementKind::kMachine)
      throw ExpressionError(n.column, "'" + n.name + "' is a " + element_kind_name(el.kind) +
                                          ": it has no ." + n.member);
    if (n.member == "time_s") return {RefKind::kMachineTime, e, 0};
    const int s = index_of(el.states, n.member);
    if (s < 0)
      throw ExpressionError(n.column, "machine '" + n.name + "' has no state '" + n.member +
                                          "' (states: " + joined(el.states) + "; or time_s)");
    return {RefKind::kMachineIn, e, s};
  }
  const int f = index_of(failure_names, n.name);
  if (f >= 0) {
    if (!n.member.empty())
      throw ExpressionError(n.column, "failure '" + n.name + "' has no ." + n.member);
    return {RefKind::kFailure, f, 0};
  }
  for (std::size_t c = 0; c < controls_.size(); ++c) {
    const ControlSpec& spec = controls_[c];
    if (spec.name != n.name) continue;
    const int ci = static_cast<int>(c);
    if (n.member == "q") return {RefKind::kControlQ, ci, 0};
    if (n.member == "position") return {RefKind::kControlPosition, ci, 0};
    const int p = index_of(spec.positions, n.member);
    if (p < 0)
      throw ExpressionError(n.column, "control '" + n.name + "' has no position '" + n.member +
                                          "' (positions: " + joined(spec.positions) +
                                          "; or q, position)");
    return {RefKind::kControlIn, ci, p};
  }
  throw ExpressionError(n.column, "no control, failure or system named '" + n.name + "'");
}

void Systems::bind_expression(SourceExpression& se) const {
  if (se.expression.empty()) return;
  try {
    se.expression.bind([this](const Name& n) { return resolve(n); });
  } catch (const ExpressionError& e) {
    fail(se.origin, std::string(e.what()) + " in \"" + se.expression.text() + "\"");
  }
}

double Systems::evaluate(const Expression& e) const { return e.evaluate(Reader(*this)); }

void Systems::step(const ControlFrame& frame, std::vector<SystemsEvent>& events) {
  if (frame.position.size() != controls_.size() || frame.q.size() != controls_.size())
    throw std::invalid_argument("a control frame of " + std::to_string(frame.position.size()) +
                                " controls, for systems bound to " +
                                std::to_string(controls_.size()));
  frame_ = frame;
  ++state_.step;
  state_.time_ns = frame.time_ns;
  const Reader reader(*this);
  for (std::size_t e = 0; e < model_.elements.size(); ++e) step_element(e, reader, events);
}

void Systems::step_element(std::size_t e, const Reader& reader, std::vector<SystemsEvent>& events) {
  const Element& el = model_.elements[e];
  double& v = state_.value[e];
  const double before = v;
  const auto input = [&] { return el.input.expression.evaluate(reader); };
  switch (el.kind) {
    case ElementKind::kLogic: v = input(); break;
    case ElementKind::kLag: v += (input() - v) * lag_factor_[e]; break;
    case ElementKind::kRate: {
      const double max_step = el.per_s * period_s_;
      v += std::clamp(input() - v, -max_step, max_step);
      break;
    }
    case ElementKind::kTimer: {
      int64_t& since = state_.since_step[e];
      if (input() != 0.0) {
        if (since < 0) since = state_.step;
        v = static_cast<double>(state_.step - since) * period_s_;
      } else {
        since = -1;
        v = 0.0;
      }
      break;
    }
    case ElementKind::kLatch: {
      const double in = input();
      const bool rose = in > state_.last_input[e];
      state_.last_input[e] = in;
      if (rose) {
        v = 1.0;
      } else if (el.reset.expression.evaluate(reader) != 0.0) {
        v = 0.0;
      }
      break;
    }
    case ElementKind::kMachine: {
      const auto s = static_cast<std::size_t>(v);
      const int64_t in_state = state_.step - state_.since_step[e];
      const auto& transitions = transitions_[e];
      for (std::size_t t = 0; t < transitions.size(); ++t) {
        const BoundTransition& b = transitions[t];
        if (b.from[s] == 0 || in_state < b.after_steps) continue;
        const SourceExpression& when = el.transitions[t].when;
        if (!when.expression.empty() && when.expression.evaluate(reader) == 0.0) continue;
        v = b.to;
        state_.since_step[e] = state_.step;
        for (int f : b.clears) {
          auto& inserted = state_.failure[static_cast<std::size_t>(f)];
          if (inserted == 0) continue;
          inserted = 0;
          cleared_.push_back(f);
        }
        break;
      }
      break;
    }
  }
  // a logic system's first value is where it starts, not a change from the 0 it held before
  const bool reports = el.kind == ElementKind::kMachine || el.kind == ElementKind::kLatch ||
                       (el.events && state_.step > 1);
  if (reports && v != before)
    events.push_back({state_.time_ns, SystemsEventKind::kChange, static_cast<int>(e), before, v});
  // a transition's cleared failures come after its change
  for (int f : cleared_) events.push_back({state_.time_ns, SystemsEventKind::kFailureCleared, f, 1.0, 0.0});
  cleared_.clear();
}

std::optional<SystemsEvent> Systems::set_failure(int failure, bool inserted, int64_t time_ns) {
  if (failure < 0 || static_cast<std::size_t>(failure) >= state_.failure.size())
    throw std::out_of_range("no failure " + std::to_string(failure));
  auto& f = state_.failure[static_cast<std::size_t>(failure)];
  if ((f != 0) == inserted) return std::nullopt;
  f = inserted ? 1 : 0;
  return SystemsEvent{time_ns >= 0 ? time_ns : state_.time_ns,
                      inserted ? SystemsEventKind::kFailureInserted : SystemsEventKind::kFailureCleared,
                      failure, inserted ? 0.0 : 1.0, inserted ? 1.0 : 0.0};
}

int Systems::element_index(const std::string& name) const {
  for (std::size_t i = 0; i < model_.elements.size(); ++i)
    if (model_.elements[i].name == name) return static_cast<int>(i);
  return -1;
}

int Systems::failure_index(const std::string& name) const {
  for (std::size_t i = 0; i < model_.failures.size(); ++i)
    if (model_.failures[i].name == name) return static_cast<int>(i);
  return -1;
}

std::string Systems::value_text(int element, double value) const {
  const Element& el = model_.elements[static_cast<std::size_t>(element)];
  if (el.kind == ElementKind::kMachine) {
    const auto s = static_cast<std::size_t>(value);
    return s < el.states.size() ? el.states[s] : "?";
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

void Systems::reset_to_start(std::vector<SystemsEvent>& events) {
  const int64_t step = state_.step;
  const int64_t time_ns = state_.time_ns;
  const SystemsState before = state_;
  state_ = initial_;
  state_.step = step;
  state_.time_ns = time_ns;
  for (std::size_t e = 0; e < model_.elements.size(); ++e) {
    const Element& el = model_.elements[e];
    if (el.kind == ElementKind::kMachine) state_.since_step[e] = step;
    const bool reports = el.kind == ElementKind::kMachine || el.kind == ElementKind::kLatch || el.events;
    if (reports && before.value[e] != state_.value[e])
      events.push_back({time_ns, SystemsEventKind::kChange, static_cast<int>(e), before.value[e], state_.value[e]});
  }
  for (std::size_t f = 0; f < state_.failure.size(); ++f)
    if (before.failure[f] != 0 && state_.failure[f] == 0)
      events.push_back({time_ns, SystemsEventKind::kFailureCleared, static_cast<int>(f), 1.0, 0.0});
}

void Systems::restore(const SystemsState& saved) {
  const std::size_t n = model_.elements.size();
  if (saved.value.size() != n || saved.since_step.size() != n || saved.last_input.size() != n ||
      saved.failure.size() != model_.failures.size())
    throw std::invalid_argument("a systems state of another model");
  for (std::size_t e = 0; e < n; ++e) {
    const Element& el = model_.elements[e];
    if (el.kind == ElementKind::kMachine &&
        !(saved.value[e] >= 0 && saved.value[e] < static_cast<double>(el.states.size()) &&
          saved.value[e] == std::floor(saved.value[e])))
      throw std::invalid_argument("machine '" + el.name + "' in no state of its own");
  }
  state_ = saved;
}

}  // namespace vcockpit::systems
