#pragma once
// The hand between two glove samples: wrist position and joint angles linearly, the wrist's
// orientation by slerp (the shortest arc, constant angular velocity). Exactly `a` or `b` at their
// own stamps, so a stream whose stamps fall on step boundaries reaches every sample bit for bit.

#include <cstdint>

#include "hand/glove_sample.hpp"

namespace vcockpit::physics_io {

// a.t_ns < b.t_ns; t_ns is clamped into [a.t_ns, b.t_ns]. The result's t_ns is t_ns.
hand::GloveSample interpolate_sample(const hand::GloveSample& a, const hand::GloveSample& b,
                                     int64_t t_ns);

// The same fraction of the way between two stamps (for the source stamps that go with samples).
int64_t interpolate_stamp_ns(int64_t a_ns, int64_t b_ns, int64_t a_t_ns, int64_t b_t_ns,
                             int64_t t_ns);

}  // namespace vcockpit::physics_io
