#include "systems/systems_run.hpp"

namespace vcockpit::systems {

int SystemsRun::take(const ControlFrame& frame, const StepStart& before_step,
                     const StepSink& after_step) {
  const int64_t period = systems_.period_ns();
  if (frame.time_ns % period != 0) {
    ++counts_.off_grid;
    return 0;
  }
  const int64_t last = systems_.state().time_ns;
  if (started() && frame.time_ns <= last) {
    ++counts_.stale;
    return 0;
  }
  ++counts_.taken;
  int steps = 0;
  stepping_ = frame;
  if (started() && (frame.time_ns - last) / period > kMaxCatchUpPeriods) {
    ++counts_.jumped;
    if (before_step) before_step(frame.time_ns);
    events_.clear();
    systems_.step(frame, events_);
    if (after_step) after_step(systems_, events_);
    return 1;
  }
  // the periods the frames skipped, each with this frame's controls at its own time
  for (int64_t t = started() ? last + period : frame.time_ns; t < frame.time_ns; t += period) {
    stepping_.time_ns = t;
    if (before_step) before_step(t);
    events_.clear();
    systems_.step(stepping_, events_);
    if (after_step) after_step(systems_, events_);
    ++counts_.missed;
    ++steps;
  }
  if (before_step) before_step(frame.time_ns);
  events_.clear();
  systems_.step(frame, events_);
  if (after_step) after_step(systems_, events_);
  return steps + 1;
}

}  // namespace vcockpit::systems
