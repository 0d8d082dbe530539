#include "hand/glove_sample.hpp"

#include <cmath>

namespace vcockpit::hand {

int64_t log_seconds_to_ns(double t_s) { return std::llround(t_s * 1e9); }

// Division (not multiplication by 1e-9) gives the double nearest the exact quotient, so
// log_seconds_to_ns(ns_to_log_seconds(ns)) == ns for every stamp a log can hold.
double ns_to_log_seconds(int64_t t_ns) { return static_cast<double>(t_ns) / 1e9; }

}  // namespace vcockpit::hand
