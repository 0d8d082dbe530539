#pragma once
// A run of the aircraft systems fed by control frames, the same offline (control_frames.csv) and
// in a rig (cockpit/control_frame): frames are taken in time order; the systems step once for each
// period of the grid up to a frame's time, with that frame's controls. So a frame that never
// came (lost, or the node was down) costs the steps their controls, not their time, and is
// counted. A frame off the grid, or not after the last one taken (a late joiner's history
// replayed), is skipped and counted; one far beyond the last (kMaxCatchUpPeriods) is one step.

#include <cstdint>
#include <functional>
#include <vector>

#include "systems/systems_engine.hpp"

namespace vcockpit::systems {

struct FrameCounts {
  uint64_t taken = 0;     // frames that stepped the systems
  uint64_t missed = 0;    // grid periods with no frame of their own (stepped with the next one)
  uint64_t off_grid = 0;  // frames whose time is not on the systems' period
  uint64_t stale = 0;     // frames at or before the last step's time
  uint64_t jumped = 0;    // frames over kMaxCatchUpPeriods after the last: one step, no catching up
};

// A gap this long (1 h at 100 Hz) is not stepped through period by period: the frame is taken as
// a jump of time (a world resumed from an old checkpoint, a bad stamp), one step at its time.
inline constexpr int64_t kMaxCatchUpPeriods = 360'000;

class SystemsRun {
 public:
  explicit SystemsRun(Systems& systems) : systems_(systems) {}

  // Called after each step with the events of that step (a recorder's row, a publication).
  using StepSink = std::function<void(const Systems&, const std::vector<SystemsEvent>& events)>;

  // Called before each step with the step's time (scheduled failures go in there).
  using StepStart = std::function<void(int64_t time_ns)>;

  // Steps for `frame`: none, one, or one per period since the last step, each preceded by
  // `before_step` and followed by `after_step` with its events. Returns the steps taken.
  int take(const ControlFrame& frame, const StepStart& before_step, const StepSink& after_step);
  const FrameCounts& counts() const { return counts_; }
  // The systems have stepped at least once (after a resume: the restored state counts).
  bool started() const { return systems_.state().step > 0; }

 private:
  Systems& systems_;
  FrameCounts counts_;
  ControlFrame stepping_;
  std::vector<SystemsEvent> events_;
};

}  // namespace vcockpit::systems
