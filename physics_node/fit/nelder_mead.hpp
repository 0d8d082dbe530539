#pragma once
// A small deterministic Nelder-Mead minimiser (the downhill simplex; Lagarias et al. 1998's
// coefficients: reflect 1, expand 2, contract 1/2, shrink 1/2). No derivatives: grip_fit's cost
// is made of hinge penalties on distances, continuous but with kinks.

#include <Eigen/Core>

#include <functional>

namespace vcockpit::fit {

struct SimplexOptions {
  int max_evaluations = 1500;
  double step = 1.0;           // the initial simplex: x0 and x0 + step along each axis
  double x_tolerance = 1e-4;   // stop when every vertex is this close to the best (each axis)...
  double f_tolerance = 1e-12;  // ... and their costs this close to the best's
};

struct SimplexResult {
  Eigen::VectorXd x;
  double f = 0.0;
  int evaluations = 0;
};

SimplexResult minimise_simplex(const std::function<double(const Eigen::VectorXd&)>& f,
                               const Eigen::VectorXd& x0, const SimplexOptions& options);

}  // namespace vcockpit::fit
