#include "glove_driver/glove/sample_source.hpp"

#include <cmath>

#include "common/clock.hpp"

namespace vcockpit::glove {

bool ReplaySource::next(hand::GloveSample& out, int64_t& due_ns) { return cursor_.next(out, due_ns); }
double ReplaySource::position_s() const { return ns_to_seconds(cursor_.position_ns()); }
double ReplaySource::total_s() const { return ns_to_seconds(cursor_.pass_duration_ns()); }

bool SyntheticSource::next(hand::GloveSample& out, int64_t& due_ns) {
  const int64_t t_ns = static_cast<int64_t>(std::llround(static_cast<double>(k_) * 1e9 / rate_hz_));
  if (t_ns > script_.duration_ns()) return false;
  ++k_;
  out = script_.sample_at(t_ns);
  position_ns_ = t_ns;
  due_ns = time_scale_ > 0 ? static_cast<int64_t>(static_cast<double>(t_ns) / time_scale_) : 0;
  return true;
}
double SyntheticSource::position_s() const { return ns_to_seconds(position_ns_); }
double SyntheticSource::total_s() const { return ns_to_seconds(script_.duration_ns()); }

}  // namespace vcockpit::glove
