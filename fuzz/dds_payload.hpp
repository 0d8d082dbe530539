#pragma once
// Fuzz bytes as a received DDS payload, taken apart by the topic's own type support (the one the
// project's readers register, idl/topics/topic_traits.hpp), as a DataReader would on take().

#include <cstring>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "idl/topics/topic_traits.hpp"

namespace vcockpit::fuzz {

// True when the type support accepts the bytes as a T.
template <class T>
bool deserialize_payload(const uint8_t* data, std::size_t size, T& out) {
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(size));
  if (size > 0) std::memcpy(payload.data, data, size);
  payload.length = static_cast<uint32_t>(size);
  typename TopicTraits<T>::PubSubType type;
  return type.deserialize(&payload, &out);
}

}  // namespace vcockpit::fuzz
