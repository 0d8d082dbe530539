#include "image_generator/node/hand_prediction.hpp"

#include <algorithm>

#include "idl/topics/pose_convert.hpp"

namespace vcockpit::image_generator {

Eigen::Isometry3d extrapolate_pose(const Eigen::Isometry3d& previous, const Eigen::Isometry3d& now,
                                   double dt_s, double h_s) {
  Eigen::Isometry3d out = now;
  if (!(dt_s > 0.0) || !(h_s > 0.0)) return out;
  const double k = h_s / dt_s;
  out.translation() = now.translation() + k * (now.translation() - previous.translation());
  // the rotation from previous to now, in the world frame, turned on by the same rate
  const Eigen::Quaterniond q_now(now.rotation());
  const Eigen::Quaterniond q_step = q_now * Eigen::Quaterniond(previous.rotation()).conjugate();
  Eigen::AngleAxisd step(q_step.normalized());
  if (step.angle() > M_PI) step.angle() -= 2 * M_PI;  // the short way round
  out.linear() = (Eigen::AngleAxisd(k * step.angle(), step.axis()) * q_now).toRotationMatrix();
  return out;
}

void HandPredictor::on_state(const cockpit::HandState& state) {
  if (have_newest_ && state.sample_time_ns() == newest_.sample_time_ns()) return;
  if (have_newest_) {
    previous_ = newest_;
    have_previous_ = true;
  }
  newest_ = state;
  have_newest_ = true;
}

int64_t HandPredictor::horizon_ns(int64_t display_ns) const {
  if (!have_newest_) return 0;
  return std::clamp<int64_t>(display_ns - newest_.source_stamp_ns(), 0, kMaxHorizon_ns);
}

bool HandPredictor::predict(int64_t display_ns, bool tracked, LinkPoses& out) const {
  if (!have_newest_) return false;
  const auto& now = tracked ? newest_.tracked_X_GL() : newest_.X_GL();
  for (std::size_t l = 0; l < out.size(); ++l) out[l] = to_eigen(now[l]);
  if (!have_previous_) return false;
  const int64_t dt_ns = newest_.sample_time_ns() - previous_.sample_time_ns();
  if (dt_ns <= 0 || dt_ns > kMaxPairGap_ns || !newest_.tracking()) return false;
  const int64_t h_ns = horizon_ns(display_ns);
  const auto& before = tracked ? previous_.tracked_X_GL() : previous_.X_GL();
  for (std::size_t l = 0; l < out.size(); ++l)
    out[l] = extrapolate_pose(to_eigen(before[l]), out[l], static_cast<double>(dt_ns) * 1e-9,
                              static_cast<double>(h_ns) * 1e-9);
  return true;
}

}  // namespace vcockpit::image_generator
