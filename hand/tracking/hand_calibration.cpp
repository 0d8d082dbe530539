#include "hand/tracking/hand_calibration.hpp"

#include <algorithm>

#include "hand/tracking/retarget.hpp"

namespace vcockpit::hand::tracking {
namespace {

constexpr double kSteadyPalmSpeed_mps = 0.5;
constexpr int kKnucklePasses = 3;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The frames whose palm moves slower than kSteadyPalmSpeed_mps to the next frame.
std::vector<std::size_t> steady(const std::vector<JointsFrame>& frames) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i + 1 < frames.size(); ++i) {
    const TrackedJoint& a = frames[i][XrJoint::kPalm];
    const TrackedJoint& b = frames[i + 1][XrJoint::kPalm];
    const double dt_s = static_cast<double>(frames[i + 1].t_ns - frames[i].t_ns) * 1e-9;
    if (a.valid && b.valid && dt_s > 0.0 && (b.p_m - a.p_m).norm() / dt_s < kSteadyPalmSpeed_mps)
      out.push_back(i);
  }
  return out;
}

// The row whose `a` is the length of the link tagged on row `tagged` (the next row).
std::size_t length_row(const FingerChain& chain, Link link) {
  for (std::size_t i = 0; i + 1 < chain.rows.size(); ++i)
    if (chain.rows[i].link == static_cast<int>(link)) return i + 1;
  return chain.rows.size();
}

}  // namespace

HandCalibration estimate_hand(const HandModel& model, const std::vector<JointsFrame>& frames_G) {
  HandCalibration c;
  const std::vector<std::size_t> use = steady(frames_G);
  c.steady_frames = static_cast<int>(use.size());
  for (int f = 0; f < kFingerCount; ++f) {
    const XrFingerChain chain = xr_finger_chain(f);
    std::array<std::vector<double>, 3> lengths;
    for (std::size_t i : use) {
      const JointsFrame& frame = frames_G[i];
      bool whole = true;
      for (int k = 0; k < 4; ++k) whole = whole && frame[chain.joints[static_cast<std::size_t>(chain.count - 4 + k)]].valid;
      if (!whole) continue;
      for (int k = 0; k < 3; ++k) {
        const auto& a = frame[chain.joints[static_cast<std::size_t>(chain.count - 4 + k)]].p_m;
        const auto& b = frame[chain.joints[static_cast<std::size_t>(chain.count - 3 + k)]].p_m;
        lengths[static_cast<std::size_t>(k)].push_back((b - a).norm());
      }
    }
    if (lengths[0].empty()) continue;
    c.bones_measured[static_cast<std::size_t>(f)] = true;
    for (int k = 0; k < 3; ++k) c.bone_m[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)] = median(lengths[static_cast<std::size_t>(k)]);
  }

  HandModel now = calibrated(model, c);
  for (int pass = 0; pass < kKnucklePasses; ++pass) {
    Retargeter retarget(now);
    std::array<std::array<std::vector<double>, 3>, kFingerCount> knuckles;
    std::array<std::vector<double>, 3> palm;
    for (std::size_t i : use) {
      const JointsFrame& frame = frames_G[i];
      const RetargetResult& r = retarget.fit(frame);
      if (!r.placed) continue;
      const Eigen::Isometry3d X_HG = r.X_GH.inverse();
      if (frame[XrJoint::kPalm].valid) {
        const Eigen::Vector3d p_H = X_HG * frame[XrJoint::kPalm].p_m;
        for (int d = 0; d < 3; ++d) palm[static_cast<std::size_t>(d)].push_back(p_H[d]);
      }
      for (int f = 0; f < kFingerCount; ++f) {
        const XrFingerChain chain = xr_finger_chain(f);
        const TrackedJoint& k = frame[chain.joints[static_cast<std::size_t>(chain.count - 4)]];
        if (!k.valid) continue;
        const Eigen::Vector3d p_H = X_HG * k.p_m;
        for (int d = 0; d < 3; ++d) knuckles[static_cast<std::size_t>(f)][static_cast<std::size_t>(d)].push_back(p_H[d]);
      }
    }
    for (int f = 0; f < kFingerCount; ++f) {
      auto& k = knuckles[static_cast<std::size_t>(f)];
      if (k[0].empty()) continue;
      c.knuckle_measured[static_cast<std::size_t>(f)] = true;
      c.knuckle_H[static_cast<std::size_t>(f)] = {median(k[0]), median(k[1]), median(k[2])};
    }
    if (!palm[0].empty()) {
      c.palm_measured = true;
      c.palm_H = {median(palm[0]), median(palm[1]), median(palm[2])};
    }

    now = calibrated(model, c);
  }
  return c;
}

HandModel calibrated(const HandModel& model, const HandCalibration& c) {
  HandModel out = model;
  if (c.palm_measured) out.p_H_palm_joint = c.palm_H;

  HandLinkPoses rest;
  forward_kinematics(model, model.rest_pose(), rest);
  for (int f = 0; f < kFingerCount; ++f) {
    const auto fi = static_cast<std::size_t>(f);
    FingerChain& chain = out.fingers[fi];
    const std::array<Link, 3> links = finger_links(static_cast<Finger>(f));
    if (c.bones_measured[fi]) {
      for (int k = 0; k < 3; ++k) {
        const std::size_t row = length_row(chain, links[static_cast<std::size_t>(k)]);
        if (row >= chain.rows.size()) continue;
        chain.rows[row].a_m = c.bone_m[fi][static_cast<std::size_t>(k)];
        out.capsules[static_cast<std::size_t>(links[static_cast<std::size_t>(k)])].length_m = chain.rows[row].a_m;
      }
    }
    if (c.knuckle_measured[fi]) {
      const Eigen::Vector3d knuckle = rest.X_HL[static_cast<std::size_t>(links[0])].translation();
      chain.X_HB.translation() += c.knuckle_H[fi] - knuckle;
    }
  }
  return out;
}

}  // namespace vcockpit::hand::tracking
