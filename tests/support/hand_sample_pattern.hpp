#pragma once
// A deterministic HandSample for sequence number `seq`: every field differs from sample to sample
// (so a lost, duplicated or reordered sample shows), with awkward doubles that only survive a
// byte-exact path.

#include <cmath>
#include <cstdint>
#include <vector>

#include "cockpitPubSubTypes.h"

namespace vcockpit::test {

inline cockpit::HandSample hand_sample_pattern(uint64_t seq) {
  cockpit::HandSample s;
  const double t = static_cast<double>(seq) * 1e-3;
  s.hand_id(0);
  s.seq(seq);
  s.sample_time_ns(static_cast<int64_t>(seq) * 1'000'000);
  s.source_stamp_ns(0);  // the publisher stamps this; the comparison ignores it
  s.X_MT().position_m().x(0.1 + 0.01 * std::sin(t));
  s.X_MT().position_m().y(-0.2 + 1.0 / (3.0 + static_cast<double>(seq)));
  s.X_MT().position_m().z(0.9 + 1e-17 * static_cast<double>(seq));
  const double half = 0.5 * t;
  s.X_MT().orientation().w(std::cos(half));
  s.X_MT().orientation().x(0.0);
  s.X_MT().orientation().y(0.0);
  s.X_MT().orientation().z(std::sin(half));
  for (std::size_t j = 0; j < s.joint_angles_rad().size(); ++j) {
    s.joint_angles_rad()[j] = std::fmod(0.001 * static_cast<double>(seq * (j + 1)), 1.5) / 3.0;
  }
  s.valid(seq % 7 != 3);
  return s;
}

// CDR bytes of a sample, for byte-identical comparisons.
inline std::vector<uint8_t> serialize(const cockpit::HandSample& sample) {
  cockpit::HandSamplePubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.m_typeSize);
  type.serialize(const_cast<cockpit::HandSample*>(&sample), &payload);
  return std::vector<uint8_t>(payload.data, payload.data + payload.length);
}

}  // namespace vcockpit::test
