#include "physics_node/io/hand_timeline.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>

namespace vcockpit::physics_io {

HandTimeline::HandTimeline(physics::World& world, const std::vector<HandSamples>& hands,
                           const InputTiming& timing, int64_t end_ns, bool past_samples)
    : world_(world),
      end_ns_(end_ns),
      past_samples_(past_samples),
      step_ns_(std::llround(world.scene().step_s * 1e9)),
      feeds_(hands.size()) {
  const int64_t t0_ns = hands.empty() ? 0 : first_ns(hands);
  drivers_.reserve(hands.size());
  for (std::size_t k = 0; k < hands.size(); ++k) {
    const HandSamples& h = hands[k];
    if (h.samples.empty()) throw std::invalid_argument("a hand without samples");
    drivers_.emplace_back(world, world.scene().hands[static_cast<std::size_t>(h.hand)], timing,
                          h.hand);
    drivers_.back().set_origin(t0_ns);
    feeds_[k].reserve(h.samples.size());
    for (const hand::GloveSample& s : h.samples) feeds_[k].queue(s);
  }
  for (std::size_t k = 0; k < hands.size(); ++k)
    feeds_[k].take_until(drivers_[k], world.time_ns(), world.time_ns(), end_ns_);
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

bool HandTimeline::prepare_next_step() {
  if (world_.time_ns() + (past_samples_ ? 1 : step_ns_) > end_ns_) return false;
  const int64_t step_end_ns = world_.time_ns() + step_ns_;
  for (std::size_t k = 0; k < feeds_.size(); ++k)
    feeds_[k].take_until(drivers_[k], step_end_ns, world_.time_ns(), end_ns_);
  for (ReplayDriver& d : drivers_)
    if (d.has_sample()) d.input_for_step_ending(step_end_ns);
  return true;
}

}  // namespace vcockpit::physics_io
