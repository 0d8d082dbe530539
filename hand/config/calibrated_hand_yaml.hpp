#pragma once
// A calibrated hand written as a hand.yaml: the source file with the calibrated sizes put in
// (hand/tracking/hand_calibration.hpp): the palm's tracking point, each finger's base position and its
// chain rows' `a` (the phalanx lengths), and the side. Everything else (joint ranges, radii, the
// tracker, the chains' angles) is the source's, so the written file loads as the calibrated model.

#include <string>
#include <vector>

#include "hand/hand_model.hpp"

namespace vcockpit {

// `hand`: the calibrated model of `source_yaml`'s hand (either side). Written atomically; throws
// ConfigError for a bad source and FileError when it cannot be written.
void write_calibrated_hand_yaml(const std::string& source_yaml, const hand::HandModel& hand,
                                const std::string& out_path, const std::vector<std::string>& comments);

}  // namespace vcockpit
