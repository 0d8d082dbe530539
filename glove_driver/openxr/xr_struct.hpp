#pragma once
// An OpenXR structure zeroed with its type set: OpenXR's `XrFoo foo{XR_TYPE_FOO};` idiom without
// the missing-initializer warnings.

#include <openxr/openxr.h>

namespace vcockpit::glove::xr {

template <typename T>
T xr_struct(XrStructureType type) {
  T value{};
  value.type = type;
  return value;
}

}  // namespace vcockpit::glove::xr
