#pragma once
// Walks a glove log for replay: which sample comes next and when it is due, for a time scale
// (--rate), a start offset, looping and restarting. Pure: the caller owns the clock.
//
// Each sample keeps its original relative timing: sample i is due (t_i - t_start) / rate after
// the replay started. Looping continues the timeline (pass k adds k * pass length), so sample
// times keep increasing and the receiver never sees time go backwards.

#include <cstdint>
#include <vector>

#include "hand/glove_sample.hpp"

namespace vcockpit::glove {

struct ReplayOptions {
  double rate = 1.0;           // time scale; 0 = as fast as the receiver takes them
  bool loop = false;
  double start_offset_s = 0.0;  // skip this much of the log's beginning
};

class ReplayCursor {
 public:
  // Throws std::invalid_argument if the offset is negative or beyond the log's end, or rate < 0.
  ReplayCursor(const std::vector<hand::GloveSample>& samples, const ReplayOptions& options);

  // The next sample (times shifted for loops) and when it is due after the start (ns of wall
  // time, 0 when rate is 0). False at the end of a non-looping replay.
  bool next(hand::GloveSample& out, int64_t& due_ns);
  // Starts over at the first played sample (an instructor's restart), the timeline going on:
  // the next sample comes one sample interval after the last one given, so times keep
  // increasing and nothing is due in the past or far ahead. Also after the end of a
  // non-looping replay.
  void restart();

  std::size_t first_index() const { return first_; }
  // The index in the log of the sample next() gave last (before any: first_index()).
  std::size_t last_index() const { return last_index_; }
  int64_t pass_duration_ns() const { return pass_ns_; }  // log time of one pass
  int passes_done() const { return pass_; }
  // Log time replayed so far in this pass, for progress lines.
  int64_t position_ns() const { return position_ns_; }

 private:
  const std::vector<hand::GloveSample>& samples_;
  ReplayOptions options_;
  std::size_t first_ = 0;
  std::size_t index_ = 0;
  std::size_t last_index_ = 0;
  int pass_ = 0;
  int64_t pass_ns_ = 0;
  int64_t step_ns_ = 0;           // the first two played samples' interval
  int64_t offset_ns_ = 0;         // added to the log's times: loops and restarts so far
  int64_t last_elapsed_ns_ = -1;  // timeline position of the last sample given (-1: none)
  int64_t position_ns_ = 0;
};

}  // namespace vcockpit::glove
