#pragma once
// The names of OpenXR's results and structure types, from the headers' reflection lists, without
// an instance (xrCreateInstance's own failures) and for the replay runtime's *ToString.

#include <openxr/openxr.h>
#include <openxr/openxr_reflection.h>

namespace vcockpit::glove::xr {

// "XR_ERROR_HANDLE_INVALID", ...; nullptr for a value the headers do not name.
inline const char* xr_result_name(XrResult value) {
  switch (value) {
#define VCOCKPIT_XR_NAME_CASE(name, number) \
  case name:                               \
    return #name;
    XR_LIST_ENUM_XrResult(VCOCKPIT_XR_NAME_CASE)
    default:
      return nullptr;
  }
}

inline const char* xr_structure_type_name(XrStructureType value) {
  switch (value) {
    XR_LIST_ENUM_XrStructureType(VCOCKPIT_XR_NAME_CASE)
#undef VCOCKPIT_XR_NAME_CASE
    default:
      return nullptr;
  }
}

}  // namespace vcockpit::glove::xr
