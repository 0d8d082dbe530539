#include "physics_node/io/sample_interpolation.hpp"

#include <cmath>

#include "common/assert.hpp"

namespace vcockpit::physics_io {

hand::GloveSample interpolate_sample(const hand::GloveSample& a, const hand::GloveSample& b,
                                     int64_t t_ns) {
  VCOCKPIT_ASSERT(a.t_ns < b.t_ns, "interpolation needs two samples in time order");
  if (t_ns <= a.t_ns) return a;
  if (t_ns >= b.t_ns) return b;
  const double s = static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  hand::GloveSample out;
  out.t_ns = t_ns;
  out.p_MT_m = a.p_MT_m + s * (b.p_MT_m - a.p_MT_m);
  out.q_MT = a.q_MT.normalized().slerp(s, b.q_MT.normalized());
  for (std::size_t j = 0; j < out.joints_rad.size(); ++j) {
    out.joints_rad[j] = a.joints_rad[j] + s * (b.joints_rad[j] - a.joints_rad[j]);
  }
  return out;
}

int64_t interpolate_stamp_ns(int64_t a_ns, int64_t b_ns, int64_t a_t_ns, int64_t b_t_ns,
                             int64_t t_ns) {
  if (t_ns <= a_t_ns || b_t_ns <= a_t_ns) return a_ns;
  if (t_ns >= b_t_ns) return b_ns;
  const double s = static_cast<double>(t_ns - a_t_ns) / static_cast<double>(b_t_ns - a_t_ns);
  return a_ns + std::llround(s * static_cast<double>(b_ns - a_ns));
}

}  // namespace vcockpit::physics_io
