#pragma once
// A grasp event in words, for logs, events.jsonl and the grasp_event topic's reason: the physics
// reports figures, the adapters word them here, e.g.
//   "stable grasp: 4 links, thumb opposed at 152 deg, |F| 0.41 N, |M| 0.012 N m"
//   "too few contacts: 2 links, thumb touching, min thumb angle 150 deg, |F| 1.20 N, |M| 0.030 N m"
//   "glove lost"
// At most 127 characters (the topic's reason is a string<128>).

#include <string>

#include "physics_node/physics/grasp_tracker.hpp"

namespace vcockpit::physics_io {

std::string grasp_event_text(const physics::GraspEvent& e);

}  // namespace vcockpit::physics_io
