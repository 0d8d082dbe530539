#include "physics_node/fit/steady_moment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "hand/tracker.hpp"

namespace vcockpit::fit {
namespace {

using hand::Joint;

constexpr Joint kFlexionJoints[] = {Joint::kThumbRotation, Joint::kThumbMcp,  Joint::kThumbIp,
                                    Joint::kIndexMcp,      Joint::kIndexPip,  Joint::kIndexDip,
                                    Joint::kMiddleMcp,     Joint::kMiddlePip, Joint::kMiddleDip,
                                    Joint::kRingMcp,       Joint::kRingPip,   Joint::kRingDip,
                                    Joint::kLittleMcp,     Joint::kLittlePip, Joint::kLittleDip};

// A sample as the simulator's tracked hand sees it: joints clamped, the wrist in the world.
struct Pose {
  hand::JointAngles q_rad{};
  Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
};

Pose pose_of(const hand::HandModel& model, const hand::GloveSample& sample) {
  hand::GloveSample clamped = sample;
  hand::clamp_to_limits(model, clamped.joints_rad);
  return {clamped.joints_rad, hand::X_GH_from_sample(model, clamped)};
}

double change(const Pose& a, const Pose& b, const MomentRule& rule) {
  double joints_rad = 0.0;
  for (int j = 0; j < hand::kJointCount; ++j)
    joints_rad = std::max(joints_rad, std::abs(a.q_rad[j] - b.q_rad[j]));
  const double turn_rad = Eigen::AngleAxisd(a.X_GH.linear().transpose() * b.X_GH.linear()).angle();
  const double travel_m = (a.X_GH.translation() - b.X_GH.translation()).norm();
  return joints_rad + turn_rad + travel_m / rule.wrist_length_m;
}

int64_t window_ns(const MomentRule& rule) {
  return std::llround(rule.window_s * 1e9);
}

Moment describe(const hand::HandModel& model, const std::vector<hand::GloveSample>& samples,
                std::size_t i, double lo, double hi, const MomentRule& rule) {
  Moment m;
  m.index = i;
  m.t_ns = samples[i].t_ns;
  m.flexion_rad = hand_flexion_rad(pose_of(model, samples[i]).q_rad);
  m.closure_share = hi > lo ? (m.flexion_rad - lo) / (hi - lo) : 1.0;
  m.motion = sample_motion(model, samples, i, rule);
  m.window_whole = samples[i].t_ns - window_ns(rule) >= samples.front().t_ns &&
                   samples[i].t_ns + window_ns(rule) <= samples.back().t_ns;
  return m;
}

void flexion_range(const hand::HandModel& model, const std::vector<hand::GloveSample>& samples,
                   double& lo, double& hi) {
  lo = INFINITY;
  hi = -INFINITY;
  for (const auto& s : samples) {
    const double f = hand_flexion_rad(pose_of(model, s).q_rad);
    lo = std::min(lo, f);
    hi = std::max(hi, f);
  }
}

}  // namespace

double hand_flexion_rad(const hand::JointAngles& q_rad) {
  double sum = 0.0;
  for (Joint j : kFlexionJoints)
    sum += q_rad[static_cast<std::size_t>(j)];
  return sum;
}

double sample_motion(const hand::HandModel& model, const std::vector<hand::GloveSample>& samples,
                     std::size_t i, const MomentRule& rule) {
  const Pose here = pose_of(model, samples[i]);
  const int64_t w_ns = window_ns(rule);
  double motion = 0.0;
  for (std::size_t j = i; j-- > 0 && samples[i].t_ns - samples[j].t_ns <= w_ns;)
    motion = std::max(motion, change(here, pose_of(model, samples[j]), rule));
  for (std::size_t j = i + 1; j < samples.size() && samples[j].t_ns - samples[i].t_ns <= w_ns; ++j)
    motion = std::max(motion, change(here, pose_of(model, samples[j]), rule));
  return motion;
}

std::optional<ClosedStretch> first_closed_stretch(const hand::HandModel& model,
                                                  const std::vector<hand::GloveSample>& samples,
                                                  const MomentRule& rule) {
  if (samples.empty()) return std::nullopt;
  ClosedStretch out;
  flexion_range(model, samples, out.lo_rad, out.hi_rad);
  const double lo = out.lo_rad, hi = out.hi_rad;
  // (a tolerance so that a log of one constant flexion counts as closed despite rounding)
  const double closed_rad = lo + rule.closed_share * (hi - lo) - 1e-12;
  const double reopened_rad = lo + (rule.closed_share - rule.reopen_margin) * (hi - lo) - 1e-12;
  out.end = samples.size();
  bool in_stretch = false;
  std::vector<double> flexion(samples.size(), 0.0);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double flexion_rad = hand_flexion_rad(pose_of(model, samples[i]).q_rad);
    flexion[i] = flexion_rad;
    if (!in_stretch) {
      if (flexion_rad < closed_rad) continue;
      in_stretch = true;
      out.first = i;
    } else if (flexion_rad < reopened_rad) {
      out.end = i;  // the first closed stretch is over
      break;
    }
    if (flexion_rad < closed_rad) continue;  // a dip within the stretch: not closed
    out.closed.push_back(i);
    out.last_closed = i;
  }
  // rule 6: the closing before it
  const int64_t first_ns = samples[out.first].t_ns;
  out.closing = out.first;
  if (out.first > 0) {
    const double most_open_rad = *std::min_element(flexion.begin(), flexion.begin() + out.first);
    const double open_rad = most_open_rad + rule.closing_margin * (hi - lo) + 1e-12;
    const int64_t earliest_ns = first_ns - std::llround(rule.closing_s * 1e9);
    out.closing = 0;
    for (std::size_t i = 0; i < out.first; ++i)
      if (flexion[i] <= open_rad || samples[i].t_ns < earliest_ns) out.closing = i;
    if (samples[out.closing].t_ns < earliest_ns) ++out.closing;  // the first within closing_s
  }
  // rule 5: the last sample within opening_margin of the stretch's highest flexion
  double highest_rad = -INFINITY;
  for (std::size_t i = out.first; i < out.end; ++i)
    highest_rad = std::max(highest_rad, flexion[i]);
  const double open_below_rad = highest_rad - rule.opening_margin * (hi - lo) - 1e-12;
  out.opening = out.first;
  for (std::size_t i = out.first; i < out.end; ++i)
    if (flexion[i] >= open_below_rad) out.opening = i;
  // rule 7
  const int64_t last_ns = first_ns + std::llround(rule.search_s * 1e9);
  out.last_moment = out.first;
  for (std::size_t i = out.first; i <= out.opening && samples[i].t_ns <= last_ns; ++i)
    out.last_moment = i;
  return out;
}

std::vector<std::size_t> moments_across(const ClosedStretch& stretch,
                                        const std::vector<hand::GloveSample>& samples,
                                        double step_s) {
  std::vector<std::size_t> out;
  const int64_t step_ns = std::llround(std::max(step_s, 0.0) * 1e9);
  const auto take = [&](std::size_t i) {
    if (!out.empty() && samples[i].t_ns - samples[out.back()].t_ns < step_ns) return;
    out.push_back(i);
  };
  for (std::size_t i = stretch.closing; i < stretch.first; ++i)
    take(i);
  for (std::size_t i : stretch.closed)
    if (i <= stretch.last_moment) take(i);
  return out;
}

Moment describe_moment(const hand::HandModel& model, const std::vector<hand::GloveSample>& samples,
                       std::size_t index, const ClosedStretch& stretch, const MomentRule& rule) {
  return describe(model, samples, index, stretch.lo_rad, stretch.hi_rad, rule);
}

std::optional<Moment> steadiest_closed_moment(const hand::HandModel& model,
                                              const std::vector<hand::GloveSample>& samples,
                                              const MomentRule& rule) {
  const std::optional<ClosedStretch> stretch = first_closed_stretch(model, samples, rule);
  if (!stretch) return std::nullopt;
  std::optional<Moment> best;
  for (std::size_t i : stretch->closed) {
    const Moment m = describe(model, samples, i, stretch->lo_rad, stretch->hi_rad, rule);
    const bool better = !best || (m.window_whole && !best->window_whole) ||
                        (m.window_whole == best->window_whole && m.motion < best->motion);
    if (better) best = m;
  }
  return best;
}

std::optional<Moment> moment_at(const hand::HandModel& model,
                                const std::vector<hand::GloveSample>& samples, int64_t t_ns,
                                const MomentRule& rule) {
  if (samples.empty()) return std::nullopt;
  std::size_t nearest = 0;
  for (std::size_t i = 1; i < samples.size(); ++i)
    if (std::llabs(samples[i].t_ns - t_ns) < std::llabs(samples[nearest].t_ns - t_ns)) nearest = i;
  double lo = 0.0, hi = 0.0;
  flexion_range(model, samples, lo, hi);
  return describe(model, samples, nearest, lo, hi, rule);
}

}  // namespace vcockpit::fit
