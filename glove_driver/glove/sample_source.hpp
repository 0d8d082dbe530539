#pragma once
// Where the glove driver's samples come from, with the time each is due: a recorded glove log
// (ReplaySource, through a ReplayCursor) or a keyframed gesture script (SyntheticSource). Pure:
// the caller owns the clock and the publishing.

#include <cstdint>

#include "glove_driver/glove/gesture_script.hpp"
#include "glove_driver/glove/replay_cursor.hpp"
#include "hand/glove_log.hpp"
#include "hand/tracking/joints_log.hpp"

namespace vcockpit::glove {

// A source of samples with their due times: a replay cursor or a synthetic script.
class Source {
 public:
  virtual ~Source() = default;
  virtual bool next(hand::GloveSample& out, int64_t& due_ns) = 0;
  virtual double position_s() const = 0;
  virtual double total_s() const = 0;
  // what loading counted (a log: clamped joint values, missing columns), for node_status
  virtual hand::InputCounts load_counts() const { return {}; }
  // Starts over from the beginning, time going on (an instructor's restart), if it can.
  virtual bool can_restart() const { return false; }
  virtual void restart() {}
  // A hand-tracking source: the tracker's joints (in the world) the last sample was retargeted
  // from; null for a glove's samples.
  virtual bool has_tracked_joints() const { return false; }
  virtual const hand::tracking::JointsFrame* tracked_joints() const { return nullptr; }
};

class ReplaySource : public Source {
 public:
  ReplaySource(hand::GloveLog log, const ReplayOptions& options)
      : log_(std::move(log)), cursor_(log_.samples, options) {}
  bool next(hand::GloveSample& out, int64_t& due_ns) override;
  double position_s() const override;
  double total_s() const override;
  hand::InputCounts load_counts() const override { return log_.counts; }
  bool can_restart() const override { return true; }
  void restart() override { cursor_.restart(); }

 protected:
  const ReplayCursor& cursor() const { return cursor_; }

 private:
  hand::GloveLog log_;
  ReplayCursor cursor_;
};

class SyntheticSource : public Source {
 public:
  SyntheticSource(GestureScript script, double rate_hz, double time_scale)
      : script_(std::move(script)), rate_hz_(rate_hz), time_scale_(time_scale) {}
  // Samples at rate_hz over the script; time_scale as --rate (0: all due at once).
  bool next(hand::GloveSample& out, int64_t& due_ns) override;
  double position_s() const override;
  double total_s() const override;

 private:
  GestureScript script_;
  double rate_hz_;
  double time_scale_;
  uint64_t k_ = 0;
  int64_t position_ns_ = 0;
};

}  // namespace vcockpit::glove
