#pragma once
// A topic's type support that never throws while taking a sample apart. The generated
// deserialize() lets Fast CDR's BadParamException escape (an unknown encapsulation, a boolean byte
// other than 0 or 1), and Fast DDS 2.9 passes it on out of DataReader::take_next_sample: one
// malformed sample from any writer on the domain would end the reading node. Returning false
// instead makes Fast DDS drop that sample, as it drops one too short for its type.

#include <fastcdr/exceptions/Exception.h>

namespace vcockpit {

template <class Generated>
class CheckedType : public Generated {
 public:
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    try {
      return Generated::deserialize(payload, data);
    } catch (const eprosima::fastcdr::exception::Exception&) {
      return false;
    }
  }
};

}  // namespace vcockpit
