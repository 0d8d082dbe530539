#pragma once
// The hand library's names as the physics uses them: the hand (hand/) is an input of the physics,
// defined below it and shared with the other nodes; these using-declarations let the physics say
// `Link` and `HandModel` without owning them.

#include "hand/hand_joints.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit::physics {

using hand::Capsule;
using hand::Finger;
using hand::HandLinkPoses;
using hand::HandModel;
using hand::JointAngles;
using hand::Link;
using hand::finger_links;
using hand::finger_of;
using hand::forward_kinematics;
using hand::kFingerCount;
using hand::kJointCount;
using hand::kLinkCount;
using hand::link_name;

}  // namespace vcockpit::physics
