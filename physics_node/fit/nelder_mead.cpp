#include "physics_node/fit/nelder_mead.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace vcockpit::fit {

SimplexResult minimise_simplex(const std::function<double(const Eigen::VectorXd&)>& f,
                               const Eigen::VectorXd& x0, const SimplexOptions& options) {
  const auto n = static_cast<int>(x0.size());
  std::vector<Eigen::VectorXd> x(static_cast<std::size_t>(n + 1), x0);
  std::vector<double> fx(static_cast<std::size_t>(n + 1));
  int evaluations = 0;
  const auto eval = [&](const Eigen::VectorXd& p) {
    ++evaluations;
    return f(p);
  };
  for (int i = 0; i < n; ++i)
    x[static_cast<std::size_t>(i + 1)][i] += options.step;
  for (std::size_t i = 0; i < x.size(); ++i)
    fx[i] = eval(x[i]);
  std::vector<std::size_t> order(x.size());

  while (evaluations < options.max_evaluations) {
    // best first; equal costs keep their vertex order (stable sort: deterministic)
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return fx[a] < fx[b]; });
    const std::size_t best = order.front(), worst = order.back(), second = order[order.size() - 2];
    double spread_x = 0.0, spread_f = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      spread_x = std::max(spread_x, (x[i] - x[best]).cwiseAbs().maxCoeff());
      spread_f = std::max(spread_f, fx[i] - fx[best]);
    }
    if (spread_x <= options.x_tolerance && spread_f <= options.f_tolerance) break;

    Eigen::VectorXd centroid = Eigen::VectorXd::Zero(n);
    for (std::size_t i = 0; i < x.size(); ++i)
      if (i != worst) centroid += x[i];
    centroid /= n;
    const Eigen::VectorXd reflected = centroid + (centroid - x[worst]);
    const double f_reflected = eval(reflected);
    if (f_reflected < fx[best]) {
      const Eigen::VectorXd expanded = centroid + 2.0 * (centroid - x[worst]);
      const double f_expanded = eval(expanded);
      if (f_expanded < f_reflected) {
        x[worst] = expanded;
        fx[worst] = f_expanded;
      } else {
        x[worst] = reflected;
        fx[worst] = f_reflected;
      }
      continue;
    }
    if (f_reflected < fx[second]) {
      x[worst] = reflected;
      fx[worst] = f_reflected;
      continue;
    }
    // contract: outside if the reflection improved on the worst, else inside
    const bool outside = f_reflected < fx[worst];
    const Eigen::VectorXd contracted =
        outside ? Eigen::VectorXd(centroid + 0.5 * (reflected - centroid))
                : Eigen::VectorXd(centroid + 0.5 * (x[worst] - centroid));
    const double f_contracted = eval(contracted);
    if (f_contracted < (outside ? f_reflected : fx[worst])) {
      x[worst] = contracted;
      fx[worst] = f_contracted;
      continue;
    }
    for (std::size_t i = 0; i < x.size(); ++i) {  // shrink toward the best
      if (i == best) continue;
      x[i] = x[best] + 0.5 * (x[i] - x[best]);
      fx[i] = eval(x[i]);
    }
  }
  const auto best = static_cast<std::size_t>(std::min_element(fx.begin(), fx.end()) - fx.begin());
  return {x[best], fx[best], evaluations};
}

}  // namespace vcockpit::fit
