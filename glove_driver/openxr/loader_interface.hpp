#pragma once
// The OpenXR loader's negotiation with a runtime library (the loader-runtime interface, version 1,
// of the OpenXR loader specification): the loader fills an XrNegotiateLoaderInfo, the runtime's
// exported xrNegotiateLoaderRuntimeInterface fills an XrNegotiateRuntimeRequest with its
// xrGetInstanceProcAddr. Debian's libopenxr-dev ships no header for it, so the two structures
// are declared here as the specification lays them out.

#include <openxr/openxr.h>

#include <cstddef>
#include <cstdint>

namespace vcockpit::glove::xr {

inline constexpr uint32_t kLoaderRuntimeVersion = 1;

enum XrLoaderInterfaceStructs {
  XR_LOADER_INTERFACE_STRUCT_UNINTIALIZED = 0,
  XR_LOADER_INTERFACE_STRUCT_LOADER_INFO,
  XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST,
  XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST,
  XR_LOADER_INTERFACE_STRUCT_API_LAYER_CREATE_INFO,
  XR_LOADER_INTERFACE_STRUCT_API_LAYER_NEXT_INFO,
};

inline constexpr uint32_t XR_LOADER_INFO_STRUCT_VERSION = 1;
struct XrNegotiateLoaderInfo {
  XrLoaderInterfaceStructs structType;  // XR_LOADER_INTERFACE_STRUCT_LOADER_INFO
  uint32_t structVersion;               // XR_LOADER_INFO_STRUCT_VERSION
  size_t structSize;                    // sizeof(XrNegotiateLoaderInfo)
  uint32_t minInterfaceVersion;
  uint32_t maxInterfaceVersion;
  XrVersion minApiVersion;
  XrVersion maxApiVersion;
};

inline constexpr uint32_t XR_RUNTIME_INFO_STRUCT_VERSION = 1;
struct XrNegotiateRuntimeRequest {
  XrLoaderInterfaceStructs structType;  // XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST
  uint32_t structVersion;               // XR_RUNTIME_INFO_STRUCT_VERSION
  size_t structSize;                    // sizeof(XrNegotiateRuntimeRequest)
  uint32_t runtimeInterfaceVersion;
  XrVersion runtimeApiVersion;
  PFN_xrGetInstanceProcAddr getInstanceProcAddr;
};

}  // namespace vcockpit::glove::xr
