#include "glove_driver/openxr/replay_runtime/joints_timeline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vcockpit::glove::xr_replay {

using hand::tracking::JointsFrame;
using hand::tracking::XrJoint;

namespace {

// Each lost joint takes the place it was last seen at (before it was seen: the palm's).
void fill_lost_joints(std::vector<JointsFrame>& frames) {
  std::array<bool, hand::tracking::kXrJointCount> seen{};
  std::array<Eigen::Vector3d, hand::tracking::kXrJointCount> last{};
  for (JointsFrame& f : frames) {
    for (std::size_t j = 0; j < f.joints.size(); ++j) {
      auto& joint = f.joints[j];
      if (joint.valid) {
        seen[j] = true;
        last[j] = joint.p_m;
      } else if (seen[j]) {
        joint.p_m = last[j];
      } else {
        // the palm (joint 0) is filled already: where it is or was last seen, if ever
        joint.p_m = f[XrJoint::kPalm].valid || seen[0] ? f[XrJoint::kPalm].p_m : Eigen::Vector3d::Zero();
      }
    }
  }
}

}  // namespace

JointsTimeline::JointsTimeline(const std::vector<JointsFrame>& frames, double rate, bool loop)
    : rate_(rate), loop_(loop) {
  if (frames.empty()) throw std::invalid_argument("the hand-joints log has no frame");
  if (!(rate > 0.0) || !std::isfinite(rate)) throw std::invalid_argument("the rate must be above 0");
  // spans held in int64 ns without overflow, whatever the times (a log of epoch times included)
  constexpr int64_t kMaxSpan_ns = int64_t{1} << 60;
  for (const JointsFrame& f : frames) hands_[f.left_hand ? 1 : 0].push_back(f);
  first_ns_ = frames.front().t_ns;
  last_ns_ = frames.front().t_ns;
  for (const JointsFrame& f : frames) {
    first_ns_ = std::min(first_ns_, f.t_ns);
    last_ns_ = std::max(last_ns_, f.t_ns);
  }
  if (static_cast<double>(last_ns_) - static_cast<double>(first_ns_) > static_cast<double>(kMaxSpan_ns))
    throw std::invalid_argument("the hand-joints log spans more than 36 years");
  int64_t interval_ns = 0;  // the last interval of the longer hand's frames, to wrap around
  for (auto& hand : hands_) {
    fill_lost_joints(hand);
    if (hand.size() >= 2) interval_ns = std::max(interval_ns, hand.back().t_ns - hand[hand.size() - 2].t_ns);
  }
  period_ns_ = last_ns_ - first_ns_ + std::max<int64_t>(interval_ns, 1'000'000);
}

int64_t JointsTimeline::log_time_ns(int64_t elapsed_ns) const {
  // in double first: any elapsed time at any rate, with no integer overflow
  double offset_ns = static_cast<double>(std::max<int64_t>(elapsed_ns, 0)) * rate_;
  if (loop_) offset_ns = std::fmod(offset_ns, static_cast<double>(period_ns_));
  // past the end (not looping): one past the last frame is as ended as any later time
  offset_ns = std::min(offset_ns, static_cast<double>(last_ns_ - first_ns_ + 1));
  return first_ns_ + std::llround(offset_ns);
}

bool JointsTimeline::ended(int64_t elapsed_ns) const {
  return !loop_ && log_time_ns(elapsed_ns) > last_ns_;
}

const JointsFrame* JointsTimeline::at(bool left_hand, int64_t elapsed_ns) const {
  if (ended(elapsed_ns)) return nullptr;
  const std::vector<JointsFrame>& hand = hands_[left_hand ? 1 : 0];
  const int64_t t_ns = log_time_ns(elapsed_ns);
  const auto after = std::upper_bound(hand.begin(), hand.end(), t_ns,
                                      [](int64_t t, const JointsFrame& f) { return t < f.t_ns; });
  if (after == hand.begin()) return nullptr;
  const JointsFrame& newest = *(after - 1);
  return t_ns - newest.t_ns <= kHandLost_ns ? &newest : nullptr;
}

}  // namespace vcockpit::glove::xr_replay
