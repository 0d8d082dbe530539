#include "glove_driver/openxr/xr_hand_session.hpp"

#define XR_USE_TIMESPEC
#include <time.h>

#include <openxr/openxr_platform.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "glove_driver/openxr/xr_joint_locations.hpp"
#include "glove_driver/openxr/xr_names.hpp"
#include "glove_driver/openxr/xr_struct.hpp"

namespace vcockpit::glove::xr {
namespace {

std::string result_text(XrResult result) {
  const char* name = xr_result_name(result);
  return name != nullptr ? name : "XrResult " + std::to_string(static_cast<int>(result));
}

std::vector<std::string> instance_extensions() {
  uint32_t count = 0;
  XrResult r = xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr);
  if (XR_FAILED(r))
    throw XrError("xrEnumerateInstanceExtensionProperties: " + result_text(r) +
                  " (no OpenXR runtime active? XR_RUNTIME_JSON names one)");
  std::vector<XrExtensionProperties> properties(count, xr_struct<XrExtensionProperties>(XR_TYPE_EXTENSION_PROPERTIES));
  r = xrEnumerateInstanceExtensionProperties(nullptr, count, &count, properties.data());
  if (XR_FAILED(r))
    throw XrError("xrEnumerateInstanceExtensionProperties: " + result_text(r));
  std::vector<std::string> names;
  for (uint32_t i = 0; i < count; ++i) names.emplace_back(properties[i].extensionName);
  return names;
}

XRAPI_ATTR XrBool32 XRAPI_CALL on_debug_message(XrDebugUtilsMessageSeverityFlagsEXT severity,
                                                XrDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                const XrDebugUtilsMessengerCallbackDataEXT* data,
                                                void* user) {
  auto& counts = *static_cast<ValidationCounts*>(user);
  const char* id = data != nullptr && data->messageId != nullptr ? data->messageId : "";
  const char* function = data != nullptr && data->functionName != nullptr ? data->functionName : "";
  const char* message = data != nullptr && data->message != nullptr ? data->message : "";
  if (severity & XR_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    ++counts.errors;
    spdlog::error("OpenXR [{}] {}: {}", id, function, message);
  } else if (severity & XR_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    ++counts.warnings;
    spdlog::warn("OpenXR [{}] {}: {}", id, function, message);
  } else {
    ++counts.others;
    spdlog::debug("OpenXR [{}] {}: {}", id, function, message);
  }
  return XR_FALSE;
}

const char* state_name(XrSessionState state) {
  switch (state) {
    case XR_SESSION_STATE_IDLE: return "idle";
    case XR_SESSION_STATE_READY: return "ready";
    case XR_SESSION_STATE_SYNCHRONIZED: return "synchronized";
    case XR_SESSION_STATE_VISIBLE: return "visible";
    case XR_SESSION_STATE_FOCUSED: return "focused";
    case XR_SESSION_STATE_STOPPING: return "stopping";
    case XR_SESSION_STATE_LOSS_PENDING: return "loss pending";
    case XR_SESSION_STATE_EXITING: return "exiting";
    default: return "unknown";
  }
}

}  // namespace

template <typename F>
F XrHandSession::proc(const char* name) const {
  PFN_xrVoidFunction f = nullptr;
  check(xrGetInstanceProcAddr(instance_, name, &f), name);
  return reinterpret_cast<F>(f);
}

void XrHandSession::check(XrResult result, const char* call) const {
  if (XR_FAILED(result)) throw XrError(std::string(call) + ": " + result_text(result));
}

XrHandSession::XrHandSession(const XrHandSessionOptions& options) {
  const std::vector<std::string> offered = instance_extensions();
  const auto offers = [&](const char* name) {
    return std::find(offered.begin(), offered.end(), name) != offered.end();
  };
  std::vector<const char*> enabled;
  for (const char* required : {XR_EXT_HAND_TRACKING_EXTENSION_NAME, XR_MND_HEADLESS_EXTENSION_NAME,
                               XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME}) {
    if (!offers(required))
      throw XrError(std::string("the OpenXR runtime offers no ") + required +
                    " (the bridge needs hand tracking, a headless session and CLOCK_MONOTONIC "
                    "times)");
    enabled.push_back(required);
  }
  const bool debug_utils = offers(XR_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (debug_utils) enabled.push_back(XR_EXT_DEBUG_UTILS_EXTENSION_NAME);

  // made once the instance is (in xrCreateInstance's chain as well, a layer would count twice)
  auto messenger_info = xr_struct<XrDebugUtilsMessengerCreateInfoEXT>(XR_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
  messenger_info.messageSeverities =
      XR_DEBUG_UTILS_MESSAGE_SEVERITY_VERBOSE_BIT_EXT | XR_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT |
      XR_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | XR_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageTypes =
      XR_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | XR_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
      XR_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT | XR_DEBUG_UTILS_MESSAGE_TYPE_CONFORMANCE_BIT_EXT;
  messenger_info.userCallback = on_debug_message;
  messenger_info.userData = &validation_;

  auto create = xr_struct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
  std::snprintf(create.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "%s",
                options.application_name.c_str());
  std::snprintf(create.applicationInfo.engineName, XR_MAX_ENGINE_NAME_SIZE, "vcockpit");
  create.applicationInfo.applicationVersion = 1;
  create.applicationInfo.engineVersion = 1;
  create.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  create.enabledExtensionCount = static_cast<uint32_t>(enabled.size());
  create.enabledExtensionNames = enabled.data();
  check(xrCreateInstance(&create, &instance_), "xrCreateInstance");

  try {
    auto instance_properties = xr_struct<XrInstanceProperties>(XR_TYPE_INSTANCE_PROPERTIES);
    check(xrGetInstanceProperties(instance_, &instance_properties), "xrGetInstanceProperties");
    runtime_name_ = instance_properties.runtimeName;
    if (debug_utils) {
      auto create_messenger = proc<PFN_xrCreateDebugUtilsMessengerEXT>("xrCreateDebugUtilsMessengerEXT");
      destroy_messenger_ = proc<PFN_xrDestroyDebugUtilsMessengerEXT>("xrDestroyDebugUtilsMessengerEXT");
      check(create_messenger(instance_, &messenger_info, &messenger_), "xrCreateDebugUtilsMessengerEXT");
    }
    create_hand_tracker_ = proc<PFN_xrCreateHandTrackerEXT>("xrCreateHandTrackerEXT");
    destroy_hand_tracker_ = proc<PFN_xrDestroyHandTrackerEXT>("xrDestroyHandTrackerEXT");
    locate_hand_joints_ = proc<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT");
    convert_timespec_ = reinterpret_cast<PFN_xrVoidFunction>(
        proc<PFN_xrConvertTimespecTimeToTimeKHR>("xrConvertTimespecTimeToTimeKHR"));

    auto system_info = xr_struct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
    system_info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    check(xrGetSystem(instance_, &system_info, &system_), "xrGetSystem");
    auto hand_tracking = xr_struct<XrSystemHandTrackingPropertiesEXT>(XR_TYPE_SYSTEM_HAND_TRACKING_PROPERTIES_EXT);
    auto system_properties = xr_struct<XrSystemProperties>(XR_TYPE_SYSTEM_PROPERTIES);
    system_properties.next = &hand_tracking;
    check(xrGetSystemProperties(instance_, system_, &system_properties), "xrGetSystemProperties");
    system_name_ = system_properties.systemName;
    if (!hand_tracking.supportsHandTracking)
      throw XrError("the OpenXR system '" + system_name_ + "' of runtime '" + runtime_name_ +
                    "' does not track hands");

    auto session_info = xr_struct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);  // no graphics binding: headless
    session_info.systemId = system_;
    check(xrCreateSession(instance_, &session_info, &session_), "xrCreateSession (headless)");

    auto space_info = xr_struct<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
    space_info.referenceSpaceType = options.space;
    space_info.poseInReferenceSpace.orientation.w = 1.0f;
    check(xrCreateReferenceSpace(session_, &space_info, &space_), "xrCreateReferenceSpace");

    for (int side = 0; side < 2; ++side) {
      auto tracker_info = xr_struct<XrHandTrackerCreateInfoEXT>(XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT);
      tracker_info.hand = side == 1 ? XR_HAND_LEFT_EXT : XR_HAND_RIGHT_EXT;
      tracker_info.handJointSet = XR_HAND_JOINT_SET_DEFAULT_EXT;
      check(create_hand_tracker_(session_, &tracker_info, &trackers_[static_cast<std::size_t>(side)]),
            "xrCreateHandTrackerEXT");
    }
  } catch (...) {
    xrDestroyInstance(instance_);  // and everything made from it
    throw;
  }
}

XrHandSession::~XrHandSession() {
  for (XrHandTrackerEXT tracker : trackers_)
    if (tracker != XR_NULL_HANDLE) destroy_hand_tracker_(tracker);
  if (space_ != XR_NULL_HANDLE) xrDestroySpace(space_);
  if (session_ != XR_NULL_HANDLE) xrDestroySession(session_);
  if (messenger_ != XR_NULL_HANDLE) destroy_messenger_(messenger_);
  xrDestroyInstance(instance_);
}

void XrHandSession::on_state(XrSessionState state) {
  spdlog::info("OpenXR session {}", state_name(state));
  state_ = state;
  switch (state) {
    case XR_SESSION_STATE_READY: {
      auto begin = xr_struct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
      begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;  // ignored: headless
      check(xrBeginSession(session_, &begin), "xrBeginSession");
      running_ = true;
      break;
    }
    case XR_SESSION_STATE_STOPPING:
      check(xrEndSession(session_), "xrEndSession");
      running_ = false;
      break;
    case XR_SESSION_STATE_LOSS_PENDING:
      lost_ = true;
      over_ = true;
      break;
    case XR_SESSION_STATE_EXITING:
      over_ = true;
      break;
    default:
      break;
  }
}

bool XrHandSession::poll() {
  while (!over_) {
    auto event = xr_struct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
    const XrResult r = xrPollEvent(instance_, &event);
    check(r, "xrPollEvent");
    if (r == XR_EVENT_UNAVAILABLE) break;
    if (event.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
      const auto& changed = reinterpret_cast<const XrEventDataSessionStateChanged&>(event);
      if (changed.session == session_) on_state(changed.state);
    } else if (event.type == XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING) {
      spdlog::warn("OpenXR instance loss pending");
      lost_ = true;
      over_ = true;
    } else if (event.type == XR_TYPE_EVENT_DATA_EVENTS_LOST) {
      spdlog::warn("OpenXR runtime lost {} events",
                   reinterpret_cast<const XrEventDataEventsLost&>(event).lostEventCount);
    }
  }
  return !over_;
}

void XrHandSession::request_exit() {
  if (running_) check(xrRequestExitSession(session_), "xrRequestExitSession");
  else over_ = true;  // not begun (or already ended): nothing to wind down
}

XrTime XrHandSession::time_at(int64_t monotonic_ns) const {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(monotonic_ns / 1'000'000'000);
  ts.tv_nsec = static_cast<long>(monotonic_ns % 1'000'000'000);
  XrTime time = 0;
  check(reinterpret_cast<PFN_xrConvertTimespecTimeToTimeKHR>(convert_timespec_)(instance_, &ts, &time),
        "xrConvertTimespecTimeToTimeKHR");
  return time;
}

bool XrHandSession::locate(bool left_hand, XrTime time, int64_t t_ns, hand::tracking::JointsFrame& out) {
  auto info = xr_struct<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
  info.baseSpace = space_;
  info.time = time;
  auto locations = xr_struct<XrHandJointLocationsEXT>(XR_TYPE_HAND_JOINT_LOCATIONS_EXT);
  locations.jointCount = XR_HAND_JOINT_COUNT_EXT;
  locations.jointLocations = locations_.data();
  check(locate_hand_joints_(trackers_[left_hand ? 1 : 0], &info, &locations), "xrLocateHandJointsEXT");
  if (!locations.isActive) return false;
  out = joints_frame(locations_.data(), left_hand, t_ns);
  return true;
}

}  // namespace vcockpit::glove::xr
