#include "systems/procedure_runner.hpp"

#include <cstdio>
#include <stdexcept>

namespace vcockpit::systems {

int ProcedureScore::errors() const {
  int n = 0;
  for (const StepScore& s : steps)
    n += (s.out_of_order ? 1 : 0) + (s.late ? 1 : 0) + (s.undone ? 1 : 0) +
         (s.status == StepStatus::kMissed ? 1 : 0);
  return n;
}

const char* state_name(ProcedureState s) {
  switch (s) {
    case ProcedureState::kWaiting: return "waiting";
    case ProcedureState::kRunning: return "running";
    case ProcedureState::kComplete: return "complete";
    case ProcedureState::kIncomplete: return "incomplete";
  }
  return "?";
}

const char* status_name(StepStatus s) {
  switch (s) {
    case StepStatus::kPending: return "pending";
    case StepStatus::kDone: return "done";
    case StepStatus::kMissed: return "missed";
  }
  return "?";
}

ProcedureRunner::ProcedureRunner(Lesson lesson, const Systems& systems) : lesson_(std::move(lesson)) {
  std::string canonical;
  char numbers[96];
  for (Procedure& p : lesson_.procedures) {
    if (p.steps.empty()) throw ModelError(p.origin + ": a procedure needs steps");
    systems.bind_expression(p.starts_when);
    std::snprintf(numbers, sizeof numbers, ":%a;", p.time_limit_s);
    canonical += "p:" + p.name + ":" + p.starts_when.expression.text() + numbers;
    for (ProcedureStep& s : p.steps) {
      systems.bind_expression(s.when);
      std::snprintf(numbers, sizeof numbers, ":%a:%d:%d:%d;", s.within_s, s.rises ? 1 : 0,
                    s.momentary ? 1 : 0, s.group);
      canonical += "s:" + s.when.expression.text() + numbers;
    }
  }
  uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (unsigned char c : canonical) {
    h ^= c;
    h *= 1099511628211ull;
  }
  lesson_hash_ = h;
  reset();
}

void ProcedureRunner::reset() {
  scores_.assign(lesson_.procedures.size(), {});
  for (std::size_t p = 0; p < scores_.size(); ++p)
    scores_[p].steps.assign(lesson_.procedures[p].steps.size(), {});
}

void ProcedureRunner::restore(const std::vector<ProcedureScore>& scores) {
  if (scores.size() != scores_.size()) throw std::invalid_argument("a score of another lesson");
  for (std::size_t p = 0; p < scores.size(); ++p)
    if (scores[p].steps.size() != scores_[p].steps.size())
      throw std::invalid_argument("a score of another lesson");
  scores_ = scores;
}

void ProcedureRunner::after_step(const Systems& systems, std::vector<ScoreEvent>& events) {
  const int64_t t = systems.state().time_ns;
  for (std::size_t p = 0; p < scores_.size(); ++p) {
    ProcedureScore& score = scores_[p];
    if (score.state == ProcedureState::kWaiting) {
      const Procedure& proc = lesson_.procedures[p];
      bool starts = false;
      if (!proc.starts_when.expression.empty()) {
        starts = systems.evaluate(proc.starts_when.expression) != 0.0;
      } else {
        starts = p == 0 || (scores_[p - 1].state == ProcedureState::kComplete ||
                            scores_[p - 1].state == ProcedureState::kIncomplete);
      }
      if (!starts) continue;
      start(p, systems, t, events);
    }
    if (score.state == ProcedureState::kRunning) score_steps(p, systems, t, events);
  }
}

void ProcedureRunner::start(std::size_t p, const Systems& systems, int64_t t,
                            std::vector<ScoreEvent>& events) {
  ProcedureScore& score = scores_[p];
  score.state = ProcedureState::kRunning;
  score.started_ns = t;
  score.last_done_ns = t;
  const Procedure& proc = lesson_.procedures[p];
  for (std::size_t s = 0; s < proc.steps.size(); ++s) {
    const bool holds = systems.evaluate(proc.steps[s].when.expression) != 0.0;
    score.steps[s].held_at_start = holds;
    score.steps[s].held_last = holds;
  }
  events.push_back({t, static_cast<int>(p), -1, "started"});
}

void ProcedureRunner::score_steps(std::size_t p, const Systems& systems, int64_t t,
                                  std::vector<ScoreEvent>& events) {
  ProcedureScore& score = scores_[p];
  const Procedure& proc = lesson_.procedures[p];
  bool all_done = true;
  for (std::size_t s = 0; s < proc.steps.size(); ++s) {
    const ProcedureStep& step = proc.steps[s];
    StepScore& st = score.steps[s];
    const bool holds = systems.evaluate(step.when.expression) != 0.0;
    const bool rose = holds && !st.held_last;
    st.held_last = holds;
    if (st.status == StepStatus::kPending) {
      // a rises step: only a change after the procedure started counts (a condition that
      // already held then does not)
      const bool done = step.rises ? rose : holds;
      if (done) {
        st.status = StepStatus::kDone;
        st.done_ns = t;
        st.since_previous_ns = t - score.last_done_ns;
        score.last_done_ns = t;
        for (std::size_t e = 0; e < s; ++e) {
          const bool same_group = step.group >= 0 && proc.steps[e].group == step.group;
          if (!same_group && score.steps[e].status != StepStatus::kDone) st.out_of_order = true;
        }
        if (step.within_s >= 0 && static_cast<double>(st.since_previous_ns) > step.within_s * 1e9)
          st.late = true;
        events.push_back({t, static_cast<int>(p), static_cast<int>(s), "done"});
      }
    } else if (st.status == StepStatus::kDone && !holds && !st.undone && !step.momentary && !step.rises) {
      st.undone = true;
      st.undone_ns = t;
      events.push_back({t, static_cast<int>(p), static_cast<int>(s), "undone"});
    }
    if (st.status != StepStatus::kDone) all_done = false;
  }
  if (all_done) {
    end(p, ProcedureState::kComplete, t, events);
  } else if (proc.time_limit_s >= 0 &&
             static_cast<double>(t - score.started_ns) > proc.time_limit_s * 1e9) {
    end(p, ProcedureState::kIncomplete, t, events);
  }
}

void ProcedureRunner::end(std::size_t p, ProcedureState state, int64_t t,
                          std::vector<ScoreEvent>& events) {
  ProcedureScore& score = scores_[p];
  score.state = state;
  score.ended_ns = t;
  for (std::size_t s = 0; s < score.steps.size(); ++s) {
    if (score.steps[s].status != StepStatus::kPending) continue;
    score.steps[s].status = StepStatus::kMissed;
    events.push_back({t, static_cast<int>(p), static_cast<int>(s), "missed"});
  }
  events.push_back({t, static_cast<int>(p), -1, state_name(state)});
}

void ProcedureRunner::finish(int64_t time_ns, std::vector<ScoreEvent>& events) {
  for (std::size_t p = 0; p < scores_.size(); ++p)
    if (scores_[p].state == ProcedureState::kRunning) end(p, ProcedureState::kIncomplete, time_ns, events);
}

}  // namespace vcockpit::systems
