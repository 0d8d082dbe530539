#pragma once
// Golden-section search for the least value of a convex function over t in [0, 1] (a body's
// signed distance along a segment is convex): the bracket it ends with, and its two inner
// points. Callers choose from those and the ends (a monotone f is least at an end, which the
// search never evaluates).

namespace vcockpit::physics {

struct GoldenBracket {
  double lo = 0.0, hi = 1.0;  // the final bracket
  double t1 = 0.0, f1 = 0.0;  // its inner points and their values
  double t2 = 0.0, f2 = 0.0;
};

// Stops when the bracket is shorter than bracket_m along a segment of length_m, or after
// max_iterations.
template <typename F>
GoldenBracket golden_section(const F& f, double length_m, double bracket_m, int max_iterations) {
  constexpr double kInvPhi = 0.6180339887498949;
  GoldenBracket g;
  g.t1 = g.hi - kInvPhi * (g.hi - g.lo);
  g.t2 = g.lo + kInvPhi * (g.hi - g.lo);
  g.f1 = f(g.t1);
  g.f2 = f(g.t2);
  for (int i = 0; i < max_iterations && (g.hi - g.lo) * length_m > bracket_m; ++i) {
    if (g.f1 <= g.f2) {
      g.hi = g.t2;
      g.t2 = g.t1;
      g.f2 = g.f1;
      g.t1 = g.hi - kInvPhi * (g.hi - g.lo);
      g.f1 = f(g.t1);
    } else {
      g.lo = g.t1;
      g.t1 = g.t2;
      g.f1 = g.f2;
      g.t2 = g.lo + kInvPhi * (g.hi - g.lo);
      g.f2 = f(g.t2);
    }
  }
  return g;
}

}  // namespace vcockpit::physics
