#pragma once
// GloveSample <-> cockpit::HandSample, value for value (no normalisation, so a replayed log
// publishes exactly what the log holds).

#include <cstdint>

#include "cockpit.h"
#include "glove_driver/glove/glove_sample.hpp"

namespace vcockpit::glove {

cockpit::HandSample to_hand_sample(const GloveSample& sample, uint32_t hand_id, uint64_t seq,
                                   int64_t source_stamp_ns);
GloveSample from_hand_sample(const cockpit::HandSample& sample);

}  // namespace vcockpit::glove
