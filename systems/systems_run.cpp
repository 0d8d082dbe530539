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
  const auto step = [&](const ControlFrame& f) {
    if (before_step) before_step(f.time_ns);
    events_.clear();
    systems_.step(f, events_);
    if (after_step) after_step(systems_, events_);
  };
  int steps = 0;
  // the periods the frames skipped, each with this frame's controls at its own time (a jump far
  // beyond the last is taken as one step)
  if (started() && (frame.time_ns - last) / period > kMaxCatchUpPeriods) {
    ++counts_.jumped;
  } else {
    stepping_ = frame;
    for (int64_t t = started() ? last + period : frame.time_ns; t < frame.time_ns; t += period) {
      stepping_.time_ns = t;
      step(stepping_);
      ++counts_.missed;
      ++steps;
    }
  }
  step(frame);
  return steps + 1;
}

}  // namespace vcockpit::systems
