#include "hand/hand_model.hpp"

#include <cmath>

#include "common/assert.hpp"

namespace vcockpit::hand {
namespace {

// theta of a row for the joint angles q: theta_offset + scale * q[joint].
double row_theta(const DhRow& row, const JointAngles& q) {
  if (row.joint < 0 || row.joint >= kJointCount) return row.theta_offset_rad;
  return row.theta_offset_rad + row.scale * q[static_cast<std::size_t>(row.joint)];
}

// Reflection in the xz plane applied on both sides (M X M, M = diag(1,-1,1)): the rotation stays
// proper because the two sign flips cancel in its determinant. Exact (sign flips only).
Eigen::Isometry3d mirror_pose(const Eigen::Isometry3d& X) {
  static constexpr double kSign[3] = {1.0, -1.0, 1.0};
  Eigen::Isometry3d Y = X;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c)
      Y.linear()(r, c) = kSign[r] * kSign[c] * X.linear()(r, c);
    Y.translation()(r) = kSign[r] * X.translation()(r);
  }
  return Y;
}

// M T(theta, d, a, alpha) M = T(-theta, d, a, -alpha): negate every angle-like term of the row.
DhRow mirror_row(DhRow row) {
  row.alpha_rad = -row.alpha_rad;
  row.theta_offset_rad = -row.theta_offset_rad;
  row.scale = -row.scale;
  return row;
}

// The chain's rows from `first` on, from the frame before it (R, p): eqs. 8-10, X_HB T(0,1)
// T(1,2) ...; a row tagged with a link outputs that link's proximal joint frame (DH frame i lies
// on joint i+1's axis), turned by the next row's theta. Composed column by column (what
// dh_transform and the next row's Rz(theta) Tz(d) multiply out to), one sine and cosine per row:
// this runs several times a step. With kCached, a row's cosine and sine come from `cached` unless
// its joint is `changed_joint`; with kFill, `fill` keeps each row's frame and trig. (Template
// flags: the plain forward kinematics pays for neither.)
template <bool kCached, bool kFill>
void chain_from(const HandModel& model, Finger finger, const JointAngles& q, std::size_t first,
                Eigen::Matrix3d R, Eigen::Vector3d p, const FingerChainCache* cached,
                int changed_joint, HandLinkPoses& out, FingerChainCache* fill) {
  const FingerChain& chain = model.fingers[static_cast<std::size_t>(finger)];
  const std::size_t n = chain.rows.size();
  const auto trig = [&](std::size_t i, double& c, double& s) {
    const DhRow& row = chain.rows[i];
    if constexpr (kCached) {
      if (row.joint != changed_joint) {
        c = cached->cos_theta[i];
        s = cached->sin_theta[i];
        return;
      }
    }
    const double theta = row_theta(row, q);
    c = std::cos(theta);
    s = std::sin(theta);
  };
  // a link's frame: the frame after row i, turned by the next row's Rz(theta_next) Tz(d_next)
  const auto output_link = [&](std::size_t i, const Eigen::Matrix3d& R_i, const Eigen::Vector3d& p_i,
                               double ct_next, double st_next) {
    const DhRow& row = chain.rows[i];
    if (row.link < 0 || row.link >= kLinkCount) return;
    Eigen::Isometry3d& X_HL = out.X_HL[static_cast<std::size_t>(row.link)];
    X_HL.linear() = R_i;
    X_HL.translation() = p_i;
    if (i + 1 < n) {
      X_HL.linear().col(0) = ct_next * R_i.col(0) + st_next * R_i.col(1);
      X_HL.linear().col(1) = ct_next * R_i.col(1) - st_next * R_i.col(0);
      X_HL.translation() = p_i + chain.rows[i + 1].d_m * R_i.col(2);
    }
  };
  double ct_next = 1.0, st_next = 0.0;
  if (first < n) trig(first, ct_next, st_next);
  // the row before `first` outputs a link that row `first` turns
  if (first > 0 && first < n) output_link(first - 1, R, p, ct_next, st_next);
  for (std::size_t i = first; i < n; ++i) {
    const DhRow& row = chain.rows[i];
    const double ct = ct_next, st = st_next;
    if constexpr (kFill) {
      fill->R_before[i] = R;
      fill->p_before[i] = p;
      fill->cos_theta[i] = ct;
      fill->sin_theta[i] = st;
    }
    if (i + 1 < n) trig(i + 1, ct_next, st_next);
    // R Rz(theta), then Tz(d) Tx(a), then Rx(alpha)
    const Eigen::Vector3d x = ct * R.col(0) + st * R.col(1);
    const Eigen::Vector3d y = ct * R.col(1) - st * R.col(0);
    const Eigen::Vector3d z = R.col(2);
    p += row.a_m * x + row.d_m * z;
    // most rows have no twist (cos 0 = 1 and sin 0 = 0 exactly, so this changes no bit)
    const double ca = row.alpha_rad == 0.0 ? 1.0 : std::cos(row.alpha_rad);
    const double sa = row.alpha_rad == 0.0 ? 0.0 : std::sin(row.alpha_rad);
    R.col(0) = x;
    R.col(1) = ca * y + sa * z;
    R.col(2) = ca * z - sa * y;
    output_link(i, R, p, ct_next, st_next);
  }

  const auto links = finger_links(finger);
  const auto distal = static_cast<std::size_t>(links[2]);
  const double length_m = model.capsules[distal].length_m;
  out.p_H_tip[static_cast<std::size_t>(finger)] =
      out.X_HL[distal] * Eigen::Vector3d(length_m, 0, 0);
}

void chain_kinematics(const HandModel& model, Finger finger, const JointAngles& q,
                      HandLinkPoses& out, FingerChainCache* fill) {
  const FingerChain& chain = model.fingers[static_cast<std::size_t>(finger)];
  // a malformed chain that never names a link leaves it at the base instead of garbage
  for (Link link : finger_links(finger))
    out.X_HL[static_cast<std::size_t>(link)] = chain.X_HB;
  if (fill) {
    VCOCKPIT_ASSERT(chain.rows.size() <= static_cast<std::size_t>(FingerChainCache::kMaxRows),
                    "a finger chain longer than FingerChainCache holds");
    fill->finger = finger;
  }
  if (fill)
    chain_from<false, true>(model, finger, q, 0, chain.X_HB.linear(), chain.X_HB.translation(),
                            nullptr, -1, out, fill);
  else
    chain_from<false, false>(model, finger, q, 0, chain.X_HB.linear(), chain.X_HB.translation(),
                             nullptr, -1, out, nullptr);
  if (fill) {
    for (Link link : finger_links(finger))
      fill->X_HL[static_cast<std::size_t>(link)] = out.X_HL[static_cast<std::size_t>(link)];
    fill->p_H_tip = out.p_H_tip[static_cast<std::size_t>(finger)];
  }
}

}  // namespace

JointAngles HandModel::rest_pose() const {
  JointAngles q{};
  for (int j = 0; j < kJointCount; ++j)
    q[j] = joints[j].rest_rad;
  return q;
}

// Standard (column-vector) DH: T = Rz(theta) Tz(d) Tx(a) Rx(alpha), i.e.
//   [ ct  -st*ca   st*sa  a*ct ]
//   [ st   ct*ca  -ct*sa  a*st ]
//   [ 0    sa      ca     d    ]
// The paper's printed eq. 1 has the rotation block of Rz(-theta) Rx(-alpha) (= (Rx(alpha)
// Rz(theta))^T, its row-vector/transposed reading) next to a column-form translation with -d; we
// use the consistent column form. theta_rad is the row's full theta (offset and scale applied).
Eigen::Isometry3d dh_transform(const DhRow& row, double theta_rad) {
  const double ct = std::cos(theta_rad), st = std::sin(theta_rad);
  const double ca = std::cos(row.alpha_rad), sa = std::sin(row.alpha_rad);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  // clang-format off
  T.linear() << ct, -st * ca, st * sa,
                st, ct * ca, -ct * sa,
                0.0, sa, ca;
  // clang-format on
  T.translation() = Eigen::Vector3d(row.a_m * ct, row.a_m * st, row.d_m);
  return T;
}

void forward_kinematics(const HandModel& model, const JointAngles& q, HandLinkPoses& out) {
  out.X_HL[static_cast<std::size_t>(Link::kPalm)] = model.X_HP;
  for (int f = 0; f < kFingerCount; ++f)
    chain_kinematics(model, static_cast<Finger>(f), q, out, nullptr);
}

void finger_kinematics(const HandModel& model, Finger finger, const JointAngles& q,
                       HandLinkPoses& out) {
  chain_kinematics(model, finger, q, out, nullptr);
}

void finger_kinematics(const HandModel& model, Finger finger, const JointAngles& q,
                       HandLinkPoses& out, FingerChainCache& cache) {
  chain_kinematics(model, finger, q, out, &cache);
}

void finger_kinematics_probe(const HandModel& model, const FingerChainCache& cache,
                             const JointAngles& q, int joint, HandLinkPoses& out) {
  const Finger finger = cache.finger;
  for (Link link : finger_links(finger))
    out.X_HL[static_cast<std::size_t>(link)] = cache.X_HL[static_cast<std::size_t>(link)];
  out.p_H_tip[static_cast<std::size_t>(finger)] = cache.p_H_tip;
  const auto& rows = model.fingers[static_cast<std::size_t>(finger)].rows;
  std::size_t first = 0;
  while (first < rows.size() && rows[first].joint != joint) ++first;
  if (first == rows.size()) return;  // a joint of another finger: nothing moves
  chain_from<true, false>(model, finger, q, first, cache.R_before[first], cache.p_before[first],
                          &cache, joint, out, nullptr);
}

// NaN is out of range too: it goes to the rest angle rather than poisoning the kinematics.
int clamp_to_limits(const HandModel& model, JointAngles& q) {
  int clamped = 0;
  for (int j = 0; j < kJointCount; ++j) {
    const JointRange& range = model.joints[j];
    double& value = q[j];
    if (std::isnan(value)) {
      value = range.rest_rad;
    } else if (value < range.min_rad) {
      value = range.min_rad;
    } else if (value > range.max_rad) {
      value = range.max_rad;
    } else {
      continue;
    }
    ++clamped;
  }
  return clamped;
}

// Joint ranges and capsules are anatomical, so they carry over unchanged; the tracker's X_GM is a
// property of the rig, not of the hand, so it stays too.
HandModel mirrored(const HandModel& model) {
  HandModel out = model;
  out.left = !model.left;
  out.X_HP = mirror_pose(model.X_HP);
  out.p_H_palm_joint = Eigen::Vector3d(model.p_H_palm_joint.x(), -model.p_H_palm_joint.y(),
                                       model.p_H_palm_joint.z());
  out.p_H_wrist_joint = Eigen::Vector3d(model.p_H_wrist_joint.x(), -model.p_H_wrist_joint.y(),
                                        model.p_H_wrist_joint.z());
  for (FingerChain& chain : out.fingers) {
    chain.X_HB = mirror_pose(chain.X_HB);
    for (DhRow& row : chain.rows)
      row = mirror_row(row);
  }
  return out;
}

// Forearm mount: the tracker frame T is the forearm frame at the wrist pivot, with the axes H has
// at zero wrist angles. The hand turns first by wrist yaw about z (radial deviation +, toward the
// thumb) and then by wrist pitch about the new y (flexion +, palm side -z):
//   X_MH = X_MT * Rz(yaw) * Ry(pitch).
// A left hand is the mirror image, so the same anatomical yaw turns it about -z.
}  // namespace vcockpit::hand
