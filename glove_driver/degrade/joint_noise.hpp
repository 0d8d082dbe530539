#pragma once
// The glove's joint channels as its sensors deliver them: Gaussian noise on every channel (bend
// sensors of a CyberGlove: sub-degree resolution, about 1 deg of noise), then quantisation of
// each channel to `bits` bits over its calibrated range [min, max] of hand.yaml (the CyberGlove's
// 8-bit A/D: 255 steps, 0.35 deg over a 90 deg MCP range). Quantisation keeps the grid beyond the
// range (a reading past the calibrated range stays past it, on the same grid).

#include <cstdint>
#include <vector>

#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit::degrade {

void add_joint_noise(std::vector<hand::GloveSample>& samples, double sigma_rad, uint64_t seed);

// bits in [1, 24]: step = (max - min) / (2^bits - 1); value = min + round((q - min) / step) step.
void quantize_joints(std::vector<hand::GloveSample>& samples, const hand::HandModel& hand,
                     int bits);

}  // namespace vcockpit::degrade
