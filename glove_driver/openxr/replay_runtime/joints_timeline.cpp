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
        joint.p_m = f[XrJoint::kPalm].valid ? f[XrJoint::kPalm].p_m : Eigen::Vector3d::Zero();
      }
    }
  }
}

}  // namespace

JointsTimeline::JointsTimeline(const std::vector<JointsFrame>& frames, double rate, bool loop)
    : rate_(rate), loop_(loop) {
  if (frames.empty()) throw std::invalid_argument("the hand-joints log has no frame");
  if (!(rate > 0.0) || !std::isfinite(rate)) throw std::invalid_argument("the rate must be above 0");
  for (const JointsFrame& f : frames) hands_[f.left_hand ? 1 : 0].push_back(f);
  first_ns_ = frames.front().t_ns;
  last_ns_ = frames.front().t_ns;
  for (const JointsFrame& f : frames) {
    first_ns_ = std::min(first_ns_, f.t_ns);
    last_ns_ = std::max(last_ns_, f.t_ns);
  }
  int64_t interval_ns = 0;  // the last interval of the longer hand's frames, to wrap around
  for (auto& hand : hands_) {
    fill_lost_joints(hand);
    if (hand.size() >= 2) interval_ns = std::max(interval_ns, hand.back().t_ns - hand[hand.size() - 2].t_ns);
  }
  period_ns_ = last_ns_ - first_ns_ + std::max<int64_t>(interval_ns, 1'000'000);
}

int64_t JointsTimeline::log_time_ns(int64_t elapsed_ns) const {
  int64_t offset_ns = std::llround(static_cast<double>(std::max<int64_t>(elapsed_ns, 0)) * rate_);
  if (loop_) offset_ns %= period_ns_;
  return first_ns_ + offset_ns;
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
