#pragma once
// The project's topics: each IDL type with its PubSubType (the generated one, made not to throw on
// a malformed sample: checked_type.hpp) and its one topic name.

#include "cockpitPubSubTypes.h"
#include "idl/topics/checked_type.hpp"

namespace vcockpit {

template <class T>
struct TopicTraits;

#define VCOCKPIT_TOPIC(Type, topic_name)                       \
  template <>                                                  \
  struct TopicTraits<cockpit::Type> {                          \
    using PubSubType = CheckedType<cockpit::Type##PubSubType>; \
    static constexpr const char* kName = topic_name;           \
  }

VCOCKPIT_TOPIC(HandSample, "cockpit/hand_sample");
VCOCKPIT_TOPIC(HandState, "cockpit/hand_state");
VCOCKPIT_TOPIC(TrackedJoints, "cockpit/tracked_joints");
VCOCKPIT_TOPIC(HandInfo, "cockpit/hand_info");
VCOCKPIT_TOPIC(ObjectInfo, "cockpit/object_info");
VCOCKPIT_TOPIC(ObjectState, "cockpit/object_state");
VCOCKPIT_TOPIC(GraspEvent, "cockpit/grasp_event");
VCOCKPIT_TOPIC(FrameInfo, "cockpit/frame_info");
VCOCKPIT_TOPIC(NodeStatus, "cockpit/node_status");
VCOCKPIT_TOPIC(HeadPose, "cockpit/head_pose");
VCOCKPIT_TOPIC(ControlInfo, "cockpit/control_info");
VCOCKPIT_TOPIC(ControlState, "cockpit/control_state");
VCOCKPIT_TOPIC(ControlEvent, "cockpit/control_event");
VCOCKPIT_TOPIC(ControlCommand, "cockpit/control_command");
VCOCKPIT_TOPIC(SimCommand, "cockpit/sim_command");
VCOCKPIT_TOPIC(SimAck, "cockpit/sim_ack");
VCOCKPIT_TOPIC(PreviewFrame, "cockpit/preview_frame");

#undef VCOCKPIT_TOPIC

}  // namespace vcockpit
