#pragma once
// A trial's human-like variation of a gesture script: what differs from one reach to the next
// when a person repeats it, drawn from a seed (the same seed, the same trial on every machine):
//   approach      the hand comes at the object from another direction and height: its path is
//                 offset by up to 2.5 cm sideways and 0-2 cm up, the offset growing over the reach
//                 and gone when the hand arrives beside the object (arrive_s), so the last part
//                 of the reach comes in from that side;
//   aperture      the hand opens wider or less wide on the way: the flexion joints of the
//                 approach x 0.85-1.15, back to the script's by the end of the closing;
//   closing       the grip closes in 0.3-0.8 s (degrade's grip_closure);
//   hand size     small, medium or large (config/hand_*.yaml);
//   input         a degradation of the glove input, from clean to harsh (glove_driver/degrade).

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

#include "glove_driver/degrade/degrade.hpp"
#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit::study {

struct TrialVariation {
  uint64_t seed = 0;
  std::string hand_size;                // small, medium, large
  std::string hand_yaml;                // its file in config/
  std::string input;                    // the degradation's name
  std::vector<std::string> presets;     // ... its degrade presets
  double grip_closure_s = 0.5;  // 0: as scripted
  double aperture_scale = 1.0;
  // the approach offset at its largest (m, world), per hand (right, left)
  Eigen::Vector3d approach_offset_G[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
};

TrialVariation draw_variation(uint64_t seed);
// No variation: the gesture as scripted, by the 50th-percentile hand, clean input.
TrialVariation plain_variation();

// The degrade spec of the variation (its presets, its closing time, its seed).
degrade::DegradeSpec degrade_spec(const TrialVariation& v);

// The script's samples with the approach and aperture varied (hand `side`: 0 right, 1 left):
// the path's offset is gone at arrive_s, the aperture back to the script's a closing span after
// approach_end_s. The closing time and the degradation are applied afterwards, by degrade().
std::vector<hand::GloveSample> vary_approach(std::vector<hand::GloveSample> samples,
                                             const TrialVariation& v, int side, double arrive_s,
                                             double approach_end_s, const hand::HandModel& hand);

}  // namespace vcockpit::study
