#pragma once
// The proxy hand's finger Jacobian: how much deeper each contact point of one finger goes per
// radian of each of the finger's joints, by finite differences of the finger's forward
// kinematics; and the damped Gram matrix J J^T + lambda I, whose solve gives a damped
// least-squares step (dq = J^T (J J^T + lambda I)^-1 r, Wampler/Nakamura). The proxy slides a
// held-back finger along what stopped it (ProxyHand::slide_finger) and bends a finger out of
// what it went into (ProxyHand::bend_out) with these.

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <array>
#include <cstddef>

#include "physics_node/physics/hand_names.hpp"

namespace vcockpit::physics {

constexpr int kMaxFingerJoints = 6;

// The joints that move one finger, as joint indices in chain order.
struct FingerJoints {
  std::array<int, kMaxFingerJoints> joint{};
  int count = 0;
};

// A contact point on one of the finger's links.
struct FingerPoint {
  std::size_t link;
  Eigen::Vector3d p_L;  // in the link's frame
  Eigen::Vector3d p_H;  // in H, at the pose the Jacobian is taken at
  Eigen::Vector3d n_G;  // the contact normal (the link is body_b: moving the point by u
                        // deepens the contact by -n.u)
};

// Calls depth_per_rad(i, k, d) with d the depth gained at points[i] per radian of
// joints.joint[k], at the finger pose q_rad (the one `chain` was filled at) and the hand pose
// X_GH. Each probe re-poses only the rows its joint moves (hand::finger_kinematics_probe, bit for
// bit a full forward kinematics). probe_links: scratch (only the finger's links are written and
// read).
template <class Sink>
void finger_depth_jacobian(const HandModel& hand, const hand::FingerChainCache& chain,
                           const FingerJoints& joints, const JointAngles& q_rad,
                           const Eigen::Isometry3d& X_GH, const FingerPoint* points,
                           std::size_t point_count, HandLinkPoses& probe_links,
                           Sink&& depth_per_rad) {
  constexpr double kProbe_rad = 1e-4;
  for (int k = 0; k < joints.count; ++k) {
    const int j = joints.joint[static_cast<std::size_t>(k)];
    JointAngles probe = q_rad;
    probe[static_cast<std::size_t>(j)] += kProbe_rad;
    hand::finger_kinematics_probe(hand, chain, probe, j, probe_links);
    for (std::size_t i = 0; i < point_count; ++i) {
      const FingerPoint& p = points[i];
      const Eigen::Vector3d u_H = probe_links.X_HL[p.link] * p.p_L - p.p_H;
      depth_per_rad(i, k, -p.n_G.dot(X_GH.linear() * u_H) / kProbe_rad);
    }
  }
}

// J J^T + damping I, factored: .solve(r) then J^T gives the damped least-squares step for r.
template <class Rows>
Eigen::LDLT<Eigen::MatrixXd> damped_gram(const Eigen::MatrixBase<Rows>& J, double damping) {
  const Eigen::MatrixXd JJt =
      J * J.transpose() + damping * Eigen::MatrixXd::Identity(J.rows(), J.rows());
  return JJt.ldlt();
}

}  // namespace vcockpit::physics
