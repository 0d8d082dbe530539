#include "glove_driver/glove/replay_cursor.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace vcockpit::glove {

ReplayCursor::ReplayCursor(const std::vector<hand::GloveSample>& samples, const ReplayOptions& options)
    : samples_(samples), options_(options) {
  if (samples.empty()) throw std::invalid_argument("the log has no samples");
  if (!(options.rate >= 0) || !std::isfinite(options.rate)) {
    throw std::invalid_argument("--rate must be 0 (as fast as possible) or positive");
  }
  if (!(options.start_offset_s >= 0)) throw std::invalid_argument("--start-offset must be >= 0");
  const int64_t start_ns = samples.front().t_ns + hand::log_seconds_to_ns(options.start_offset_s);
  while (first_ < samples.size() && samples[first_].t_ns < start_ns) ++first_;
  if (first_ == samples.size()) {
    throw std::invalid_argument("--start-offset " + std::to_string(options.start_offset_s) +
                                " s is beyond the log's end (" +
                                std::to_string(hand::ns_to_log_seconds(samples.back().t_ns -
                                                                 samples.front().t_ns)) +
                                " s)");
  }
  index_ = first_;
  last_index_ = first_;
  // one pass spans the played samples plus one sample interval, so a loop keeps the spacing
  const int64_t span = samples.back().t_ns - samples[first_].t_ns;
  const int64_t step = samples.size() - first_ > 1 ? samples[first_ + 1].t_ns - samples[first_].t_ns
                                                   : 1'000'000;
  pass_ns_ = span + step;
  step_ns_ = step;
}

void ReplayCursor::restart() {
  if (last_elapsed_ns_ < 0) return;  // nothing given yet: it starts at the start anyway
  index_ = first_;
  offset_ns_ = last_elapsed_ns_ + step_ns_;
}

bool ReplayCursor::next(hand::GloveSample& out, int64_t& due_ns) {
  if (index_ == samples_.size()) {
    if (!options_.loop) return false;
    ++pass_;
    index_ = first_;
    offset_ns_ += pass_ns_;
  }
  last_index_ = index_;
  const hand::GloveSample& s = samples_[index_++];
  position_ns_ = s.t_ns - samples_[first_].t_ns;
  const int64_t elapsed_ns = position_ns_ + offset_ns_;
  last_elapsed_ns_ = elapsed_ns;
  out = s;
  out.t_ns = s.t_ns + offset_ns_;
  due_ns = options_.rate > 0 ? static_cast<int64_t>(static_cast<double>(elapsed_ns) / options_.rate)
                             : 0;
  return true;
}

}  // namespace vcockpit::glove
