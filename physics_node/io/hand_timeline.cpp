#include "physics_node/io/hand_timeline.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>

namespace vcockpit::physics_io {

HandTimeline::HandTimeline(physics::World& world, const std::vector<HandSamples>& hands,
                           const InputTiming& timing, int64_t end_ns, bool past_samples)
    : world_(world),
      hands_(hands),
      end_ns_(end_ns),
      past_samples_(past_samples),
      step_ns_(std::llround(world.scene().step_s * 1e9)),
      next_(hands.size(), 0) {
  const int64_t t0_ns = hands.empty() ? 0 : first_ns(hands);
  drivers_.reserve(hands.size());
  for (const HandSamples& h : hands) {
    if (h.samples.empty()) throw std::invalid_argument("a hand without samples");
    drivers_.emplace_back(world, world.scene().hands[static_cast<std::size_t>(h.hand)], timing,
                          h.hand);
    drivers_.back().set_origin(t0_ns);
  }
  for (std::size_t k = 0; k < hands.size(); ++k) take_samples(k, world.time_ns());
}

int64_t HandTimeline::first_ns(const std::vector<HandSamples>& hands) {
  int64_t t_ns = INT64_MAX;
  for (const HandSamples& h : hands) t_ns = std::min(t_ns, h.samples.front().t_ns);
  return t_ns;
}

int64_t HandTimeline::span_ns(const std::vector<HandSamples>& hands) {
  if (hands.empty()) return 0;
  int64_t last_ns = INT64_MIN;
  for (const HandSamples& h : hands) last_ns = std::max(last_ns, h.samples.back().t_ns);
  return last_ns - first_ns(hands);
}

void HandTimeline::take_samples(std::size_t k, int64_t until_ns) {
  ReplayDriver& d = drivers_[k];
  const std::vector<hand::GloveSample>& samples = hands_[k].samples;
  while (next_[k] < samples.size() && (!d.has_sample() || d.newest_world_ns() < until_ns)) {
    const int64_t t_ns = d.world_time_of(samples[next_[k]]);
    if (!d.has_sample() && t_ns > world_.time_ns()) break;      // begins later
    if (d.has_sample() && d.newest_world_ns() > end_ns_) break;  // past the end already
    d.push(samples[next_[k]++]);
  }
}

bool HandTimeline::prepare_next_step() {
  if (world_.time_ns() + (past_samples_ ? 1 : step_ns_) > end_ns_) return false;
  const int64_t step_end_ns = world_.time_ns() + step_ns_;
  for (std::size_t k = 0; k < hands_.size(); ++k) take_samples(k, step_end_ns);
  for (ReplayDriver& d : drivers_)
    if (d.has_sample()) d.input_for_step_ending(step_end_ns);
  return true;
}

}  // namespace vcockpit::physics_io
