#include "idl/topics/hand_sample_convert.hpp"

#include "idl/topics/pose_convert.hpp"

namespace vcockpit {

cockpit::HandSample to_hand_sample(const hand::GloveSample& sample, uint32_t hand_id, uint64_t seq,
                                   int64_t source_stamp_ns) {
  cockpit::HandSample out;
  out.hand_id(hand_id);
  out.seq(seq);
  out.sample_time_ns(sample.t_ns);
  out.source_stamp_ns(source_stamp_ns);
  out.X_MT().position_m(to_idl(sample.p_MT_m));
  out.X_MT().orientation(to_idl(sample.q_MT));
  for (int j = 0; j < hand::kJointCount; ++j) out.joint_angles_rad()[j] = sample.joints_rad[j];
  out.valid(true);
  return out;
}

hand::GloveSample from_hand_sample(const cockpit::HandSample& sample) {
  hand::GloveSample out;
  out.t_ns = sample.sample_time_ns();
  out.p_MT_m = to_eigen(sample.X_MT().position_m());
  out.q_MT = to_eigen(sample.X_MT().orientation());
  for (int j = 0; j < hand::kJointCount; ++j) out.joints_rad[j] = sample.joint_angles_rad()[j];
  return out;
}

}  // namespace vcockpit
