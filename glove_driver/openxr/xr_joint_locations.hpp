#pragma once
// OpenXR's hand joint locations as the joints log's tracked joints. XR_HAND_JOINT_*_EXT numbers
// the joints as hand::tracking::XrJoint does. A joint is taken as tracked when its position is
// valid and tracked: an untracked position is the runtime's guess, and the retargeter keeps a
// finger's last angles rather than fit a guess (retarget.hpp). Orientation is kept when tracked.

#include <openxr/openxr.h>

#include <cstdint>

#include "hand/tracking/joints_log.hpp"

namespace vcockpit::glove::xr {

// `locations`: XR_HAND_JOINT_COUNT_EXT joints in a reference space (the joints log's space xr).
hand::tracking::JointsFrame joints_frame(const XrHandJointLocationEXT* locations, bool left_hand,
                                         int64_t t_ns);

}  // namespace vcockpit::glove::xr
