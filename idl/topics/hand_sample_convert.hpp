#pragma once
// hand::GloveSample <-> cockpit::HandSample, value for value (no normalisation, so a replayed log
// publishes exactly what the log holds).

#include <cstdint>

#include "cockpit.h"
#include "hand/glove_sample.hpp"

namespace vcockpit {

cockpit::HandSample to_hand_sample(const hand::GloveSample& sample, uint32_t hand_id, uint64_t seq,
                                   int64_t source_stamp_ns);
hand::GloveSample from_hand_sample(const cockpit::HandSample& sample);

}  // namespace vcockpit
