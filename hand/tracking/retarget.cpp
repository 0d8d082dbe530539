#include "hand/tracking/retarget.hpp"

#include <algorithm>
#include <cmath>

#include "hand/tracker.hpp"
#include "hand/tracking/rigid_fit.hpp"

namespace vcockpit::hand::tracking {
namespace {

// a step smaller than this (0.006 deg) ends a finger's fit: well below the trackers' noise
constexpr double kConverged_rad = 1e-4;
constexpr int kPointCount = 3;  // a finger's joints beyond its knuckle and its tip
constexpr int kMaxParams = 4;
constexpr int kResiduals = 3 * kPointCount + kMaxParams;
using Residual = Eigen::Matrix<double, kResiduals, 1>;

struct PalmPoint {
  XrJoint tracked;
  double weight;
};

}  // namespace

Eigen::Matrix3d R_G_xr() {
  Eigen::Matrix3d R;
  // columns: where xr's x (right), y (up) and z (toward the user) point in G
  R << 0, 0, -1,
      -1, 0, 0,
       0, 1, 0;
  return R;
}

JointsFrame to_cockpit(const JointsFrame& frame, const Eigen::Isometry3d& X_GS) {
  JointsFrame out = frame;
  const Eigen::Quaterniond q_GS(X_GS.linear());
  for (TrackedJoint& j : out.joints) {
    if (!j.valid) continue;
    j.p_m = X_GS * j.p_m;
    if (j.has_orientation) j.q = (q_GS * j.q).normalized();
  }
  return out;
}

Retargeter::Retargeter(const HandModel& model, const RetargetOptions& options)
    : model_(model), options_(options) {
  reset();
}

void Retargeter::reset() {
  result_ = RetargetResult{};
  result_.q_rad = model_.rest_pose();
  result_.tip_error_m.fill(-1.0);
  have_previous_ = false;
}

const RetargetResult& Retargeter::fit(const JointsFrame& frame_G) {
  result_.tip_error_m.fill(-1.0);
  result_.placed = place_palm(frame_G);
  if (!result_.placed) return result_;
  const Eigen::Isometry3d X_HG = result_.X_GH.inverse();
  for (Finger f : {Finger::kThumb, Finger::kIndex, Finger::kMiddle, Finger::kRing, Finger::kLittle})
    fit_finger(f, frame_G, X_HG);
  forward_kinematics(model_, result_.q_rad, poses_);
  for (int f = 0; f < kFingerCount; ++f) {
    const XrFingerChain chain = xr_finger_chain(f);
    const TrackedJoint& tip = frame_G[chain.joints[static_cast<std::size_t>(chain.count - 1)]];
    if (tip.valid) {
      result_.tip_error_m[static_cast<std::size_t>(f)] =
          (result_.X_GH * poses_.p_H_tip[static_cast<std::size_t>(f)] - tip.p_m).norm();
    }
  }
  have_previous_ = true;
  return result_;
}

bool Retargeter::place_palm(const JointsFrame& frame) {
  forward_kinematics(model_, result_.q_rad, poses_);
  const auto origin = [&](Link l) { return poses_.X_HL[static_cast<std::size_t>(l)].translation(); };
  // the model's palm points in H and the tracked joint each matches; the palm's own points (its
  // centre, the thumb's base, the wrist) make the fit a plane, not the knuckles' line
  constexpr std::size_t kPalmPoints = 7;
  const std::array<std::pair<Eigen::Vector3d, PalmPoint>, kPalmPoints> points = {{
      {model_.p_H_palm_joint, {XrJoint::kPalm, 1.0}},
      {origin(Link::kIndexProximal), {XrJoint::kIndexProximal, 1.0}},
      {origin(Link::kMiddleProximal), {XrJoint::kMiddleProximal, 1.0}},
      {origin(Link::kRingProximal), {XrJoint::kRingProximal, 1.0}},
      {origin(Link::kLittleProximal), {XrJoint::kLittleProximal, 1.0}},
      {origin(Link::kThumbProximal), {XrJoint::kThumbMetacarpal, 0.5}},
      {model_.p_H_wrist_joint, {XrJoint::kWrist, 0.5}},
  }};
  std::array<Eigen::Vector3d, kPalmPoints> model_H, tracked_G;
  std::array<double, kPalmPoints> weight{};
  std::size_t count = 0;
  bool off_the_line = false;
  for (const auto& [p_H, m] : points) {
    const TrackedJoint& t = frame[m.tracked];
    if (!t.valid) continue;
    model_H[count] = p_H;
    tracked_G[count] = t.p_m;
    weight[count] = m.weight;
    ++count;
    off_the_line = off_the_line || m.tracked == XrJoint::kPalm || m.tracked == XrJoint::kWrist ||
                   m.tracked == XrJoint::kThumbMetacarpal;
  }
  if (count < 3 || !off_the_line) return false;
  result_.X_GH = rigid_fit(std::span(model_H).first(count), std::span(tracked_G).first(count),
                           std::span(weight).first(count));
  return true;
}

void Retargeter::fit_finger(Finger finger, const JointsFrame& frame, const Eigen::Isometry3d& X_HG) {
  const auto f = static_cast<std::size_t>(finger);
  const XrFingerChain chain = xr_finger_chain(static_cast<int>(finger));
  const std::array<Link, 3> links = finger_links(finger);
  // the tracked knuckle (the thumb's base) and the points beyond it, in H
  const TrackedJoint& base = frame[chain.joints[static_cast<std::size_t>(chain.count - 4)]];
  std::array<const TrackedJoint*, kPointCount> tracked{};
  std::array<Eigen::Vector3d, kPointCount> tracked_H{};
  int valid = 0;
  bool all_valid = base.valid;
  for (int k = 0; k < kPointCount; ++k) {
    tracked[static_cast<std::size_t>(k)] = &frame[chain.joints[static_cast<std::size_t>(chain.count - 3 + k)]];
    if (tracked[static_cast<std::size_t>(k)]->valid) {
      tracked_H[static_cast<std::size_t>(k)] = X_HG * tracked[static_cast<std::size_t>(k)]->p_m;
      ++valid;
    } else {
      all_valid = false;
    }
  }
  if (valid == 0) return;  // a lost finger keeps its last angles

  // the channels this finger fits: its chain's, less the palm arch and what an earlier finger
  // fitted (the little finger's chain starts on the ring's abduction)
  std::array<int, kMaxParams> params{};
  int n = 0;
  for (const DhRow& row : model_.fingers[f].rows) {
    if (row.joint < 0 || row.joint == static_cast<int>(Joint::kPalmArch)) continue;
    if (finger == Finger::kLittle && row.joint == static_cast<int>(Joint::kRingMiddleAbduction)) continue;
    if (n < kMaxParams) params[static_cast<std::size_t>(n++)] = row.joint;
  }

  finger_kinematics(model_, finger, result_.q_rad, poses_);
  const Eigen::Vector3d model_base = poses_.X_HL[static_cast<std::size_t>(links[0])].translation();
  // the tracked finger's shape on the model's knuckle, at the model's length
  double scale = 1.0;
  Eigen::Vector3d tracked_base = model_base;
  if (base.valid) {
    tracked_base = X_HG * base.p_m;
    if (all_valid) {
      const double tracked_m = (tracked_H[0] - tracked_base).norm() + (tracked_H[1] - tracked_H[0]).norm() +
                               (tracked_H[2] - tracked_H[1]).norm();
      double model_m = 0.0;
      for (Link l : links) model_m += model_.capsules[static_cast<std::size_t>(l)].length_m;
      if (tracked_m > 1e-3) scale = model_m / tracked_m;
    }
  }
  std::array<Eigen::Vector3d, kPointCount> target{};
  for (int k = 0; k < kPointCount; ++k)
    target[static_cast<std::size_t>(k)] = model_base + scale * (tracked_H[static_cast<std::size_t>(k)] - tracked_base);

  const JointAngles q_previous = result_.q_rad;
  const double smooth = have_previous_ ? options_.smoothing_m_per_rad : 0.0;
  const auto residual = [&](const JointAngles& q, Residual& r) {
    finger_kinematics(model_, finger, q, poses_);
    const std::array<Eigen::Vector3d, kPointCount> model_points = {
        poses_.X_HL[static_cast<std::size_t>(links[1])].translation(),
        poses_.X_HL[static_cast<std::size_t>(links[2])].translation(), poses_.p_H_tip[f]};
    r.setZero();
    for (int k = 0; k < kPointCount; ++k) {
      if (!tracked[static_cast<std::size_t>(k)]->valid) continue;
      const double w = k == kPointCount - 1 ? options_.tip_weight : 1.0;
      r.segment<3>(3 * k) = w * (model_points[static_cast<std::size_t>(k)] - target[static_cast<std::size_t>(k)]);
    }
    for (int i = 0; i < n; ++i) {
      const auto j = static_cast<std::size_t>(params[static_cast<std::size_t>(i)]);
      r(3 * kPointCount + i) = smooth * (q[j] - q_previous[j]);
    }
  };
  const auto clamp_param = [&](JointAngles& q, int j) {
    const JointRange& range = model_.joints[static_cast<std::size_t>(j)];
    q[static_cast<std::size_t>(j)] = std::clamp(q[static_cast<std::size_t>(j)], range.min_rad, range.max_rad);
  };

  JointAngles q = result_.q_rad;
  Residual r;
  residual(q, r);
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  Eigen::Matrix<double, kResiduals, kMaxParams> J = Eigen::Matrix<double, kResiduals, kMaxParams>::Zero();
  for (int iteration = 0; iteration < options_.max_iterations; ++iteration) {
    constexpr double kStep_rad = 1e-6;
    for (int i = 0; i < n; ++i) {
      JointAngles q_step = q;
      q_step[static_cast<std::size_t>(params[static_cast<std::size_t>(i)])] += kStep_rad;
      Residual r_step;
      residual(q_step, r_step);
      J.col(i) = (r_step - r) / kStep_rad;
    }
    const Eigen::Matrix4d A = J.transpose() * J;
    const Eigen::Vector4d g = J.transpose() * r;
    bool improved = false;
    double step_norm = 0.0;
    while (lambda < 1e8) {
      Eigen::Matrix4d M = A;
      for (int i = 0; i < kMaxParams; ++i) M(i, i) = i < n ? A(i, i) * (1.0 + lambda) + 1e-12 : 1.0;
      const Eigen::Vector4d delta = M.ldlt().solve(-g);
      JointAngles q_new = q;
      for (int i = 0; i < n; ++i) {
        q_new[static_cast<std::size_t>(params[static_cast<std::size_t>(i)])] += delta(i);
        clamp_param(q_new, params[static_cast<std::size_t>(i)]);
      }
      Residual r_new;
      residual(q_new, r_new);
      const double cost_new = r_new.squaredNorm();
      if (cost_new < cost) {
        step_norm = 0.0;
        for (int i = 0; i < n; ++i) {
          const auto j = static_cast<std::size_t>(params[static_cast<std::size_t>(i)]);
          step_norm = std::max(step_norm, std::abs(q_new[j] - q[j]));
        }
        q = q_new;
        r = r_new;
        cost = cost_new;
        lambda = std::max(lambda * 0.3, 1e-9);
        improved = true;
        break;
      }
      lambda *= 10.0;
    }
    if (!improved || step_norm < kConverged_rad) break;
  }
  result_.q_rad = q;
}

GloveSample Retargeter::glove_sample(int64_t t_ns) const {
  GloveSample s;
  s.t_ns = t_ns;
  s.joints_rad = result_.q_rad;
  const Eigen::Isometry3d X_MH = model_.tracker.X_GM.inverse() * result_.X_GH;
  const Eigen::Isometry3d X_TH = X_MH_from_tracker(model_, Eigen::Isometry3d::Identity(), result_.q_rad);
  const Eigen::Isometry3d X_MT = X_MH * X_TH.inverse();
  s.p_MT_m = X_MT.translation();
  s.q_MT = Eigen::Quaterniond(X_MT.linear()).normalized();
  return s;
}

}  // namespace vcockpit::hand::tracking
