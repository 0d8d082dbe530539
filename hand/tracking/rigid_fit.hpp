#pragma once
// The rigid transform that best takes one set of points onto another: X minimising
// sum_i w_i |X a_i - b_i|^2 (Kabsch: the SVD of the weighted cross-covariance; a reflection is
// turned into the nearest rotation). The rotation is unique only for three or more points not on
// one line; with fewer, the SVD's choice is returned. No allocation.

#include <Eigen/Geometry>

#include <span>

namespace vcockpit::hand::tracking {

// a and b the same length, at least one point; weights empty (all 1) or the same length, each
// > 0. X_BA takes a point in A's frame to B's: b_i ~ X_BA a_i.
Eigen::Isometry3d rigid_fit(std::span<const Eigen::Vector3d> a, std::span<const Eigen::Vector3d> b,
                            std::span<const double> weights = {});

}  // namespace vcockpit::hand::tracking
