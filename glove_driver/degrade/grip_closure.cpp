#include "glove_driver/degrade/grip_closure.hpp"

#include <cmath>

#include "glove_driver/degrade/sample_timeline.hpp"

namespace vcockpit::degrade {
namespace {

constexpr double kStrictFall_m = 1e-9;  // below rounding of the kinematics, above nothing

double wrist_travel_m(const std::vector<hand::GloveSample>& samples, const GripClosure& c) {
  double travel = 0.0;
  for (std::size_t i = c.first; i <= c.last; ++i) {
    travel = std::max(travel, (samples[i].p_MT_m - samples[c.first].p_MT_m).norm());
  }
  return travel;
}

}  // namespace

double grip_aperture_m(const hand::HandModel& hand, const hand::JointAngles& q) {
  hand::HandLinkPoses poses;
  forward_kinematics(hand, q, poses);
  const auto tip = [&](hand::Finger f) { return poses.p_H_tip[static_cast<int>(f)]; };
  const Eigen::Vector3d thumb = tip(hand::Finger::kThumb);
  return 0.5 * ((thumb - tip(hand::Finger::kIndex)).norm() +
                (thumb - tip(hand::Finger::kMiddle)).norm());
}

std::vector<GripClosure> find_grip_closures(const std::vector<hand::GloveSample>& samples,
                                            const hand::HandModel& hand,
                                            const GripClosureOptions& options) {
  std::vector<double> aperture(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    aperture[i] = grip_aperture_m(hand, samples[i].joints_rad);
  }
  std::vector<GripClosure> out;
  std::size_t i = 0;
  while (i + 1 < samples.size()) {
    if (!(aperture[i + 1] < aperture[i] - kStrictFall_m)) {
      ++i;
      continue;
    }
    // a fall starts at i; it lasts while the aperture stays within the hysteresis of its
    // running minimum, and ends at that minimum
    GripClosure c{i, i + 1, 0.0};
    double lowest = aperture[i + 1];
    for (std::size_t j = i + 2; j < samples.size() && aperture[j] <= lowest + options.hysteresis_m;
         ++j) {
      if (aperture[j] < lowest - kStrictFall_m) {
        lowest = aperture[j];
        c.last = j;
      }
    }
    c.closure_m = aperture[c.first] - aperture[c.last];
    if (c.closure_m >= options.min_closure_m &&
        wrist_travel_m(samples, c) <= options.max_wrist_travel_m) {
      out.push_back(c);
    }
    i = c.last;
  }
  return out;
}

int speed_up_grip_closures(std::vector<hand::GloveSample>& samples, const hand::HandModel& hand,
                           double duration_s, const GripClosureOptions& options) {
  const auto closures = find_grip_closures(samples, hand, options);
  const std::vector<hand::GloveSample> original = samples;
  const int64_t target_ns = std::llround(duration_s * 1e9);
  int changed = 0;
  for (const GripClosure& c : closures) {
    const int64_t start_ns = original[c.first].t_ns;
    const int64_t span_ns = original[c.last].t_ns - start_ns;
    if (span_ns <= target_ns) continue;
    ++changed;
    const double speed = static_cast<double>(span_ns) / static_cast<double>(target_ns);
    for (std::size_t i = c.first; i <= c.last; ++i) {
      const int64_t into_ns = original[i].t_ns - start_ns;
      // the closure at `speed` times its pace, then the closed grip held
      const int64_t source_ns =
          into_ns < target_ns
              ? start_ns + std::llround(static_cast<double>(into_ns) * speed)
              : original[c.last].t_ns;
      samples[i] = sample_at_time(original, source_ns);
      samples[i].t_ns = original[i].t_ns;
    }
  }
  return changed;
}

}  // namespace vcockpit::degrade
