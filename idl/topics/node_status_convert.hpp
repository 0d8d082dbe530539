#pragma once
// hand::InputCounts into cockpit/node_status's count fields: the glove driver's and the physics
// node's statuses say their input the same way.

#include "cockpit.h"
#include "hand/input_counts.hpp"

namespace vcockpit {

// received is the caller's (what it counts as accepted differs by node); rejected is the total
// of the three reasons, longest_interval_s in seconds.
void set_input_counts(const hand::InputCounts& c, cockpit::NodeStatus& status);

}  // namespace vcockpit
