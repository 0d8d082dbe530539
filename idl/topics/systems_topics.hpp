#pragma once
// The aircraft systems' topics (idl/systems.idl), apart from topic_traits.hpp so that only their
// users compile their types.

#include "idl/topics/topic_traits.hpp"
#include "systemsPubSubTypes.h"

namespace vcockpit {

#define VCOCKPIT_SYSTEMS_TOPIC(Type, topic_name)               \
  template <>                                                  \
  struct TopicTraits<cockpit::Type> {                          \
    using PubSubType = CheckedType<cockpit::Type##PubSubType>; \
    static constexpr const char* kName = topic_name;           \
  }

VCOCKPIT_SYSTEMS_TOPIC(ControlFrame, "cockpit/control_frame");
VCOCKPIT_SYSTEMS_TOPIC(SystemsInfo, "cockpit/systems_info");
VCOCKPIT_SYSTEMS_TOPIC(SystemsState, "cockpit/systems_state");
VCOCKPIT_SYSTEMS_TOPIC(SystemsEvent, "cockpit/systems_event");
VCOCKPIT_SYSTEMS_TOPIC(FailureCommand, "cockpit/failure_command");
VCOCKPIT_SYSTEMS_TOPIC(FailureAck, "cockpit/failure_ack");
VCOCKPIT_SYSTEMS_TOPIC(ProcedureScore, "cockpit/procedure_score");

#undef VCOCKPIT_SYSTEMS_TOPIC

}  // namespace vcockpit
