#pragma once
// The OpenXR side of openxr_hand_bridge: an instance with XR_EXT_hand_tracking, a headless
// session (XR_MND_headless: no graphics, the hands only), a reference space and a hand tracker
// per hand, driven through whatever runtime the Khronos loader picks (the active runtime, or
// XR_RUNTIME_JSON). The session's life follows the runtime's events: READY begins it, STOPPING
// ends it, EXITING or LOSS_PENDING is its end. Times are XrTime from CLOCK_MONOTONIC through
// XR_KHR_convert_timespec_time (a headless session need not run the frame loop).
//
// When the loader offers XR_EXT_debug_utils, every message an API layer sends (the core
// validation layer's) is logged and counted. Failures throw XrError naming the call and result.

#include <openxr/openxr.h>

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "hand/tracking/joints_log.hpp"

namespace vcockpit::glove::xr {

class XrError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct XrHandSessionOptions {
  XrReferenceSpaceType space = XR_REFERENCE_SPACE_TYPE_LOCAL;
  std::string application_name = "openxr_hand_bridge";
};

struct ValidationCounts {
  int errors = 0;
  int warnings = 0;
  int others = 0;  // info and verbose
};

class XrHandSession {
 public:
  explicit XrHandSession(const XrHandSessionOptions& options);
  ~XrHandSession();
  XrHandSession(const XrHandSession&) = delete;
  XrHandSession& operator=(const XrHandSession&) = delete;

  // Takes the runtime's events: begins the session at READY, ends it at STOPPING. False once
  // the session is over (EXITING, LOSS_PENDING, the instance lost).
  bool poll();
  // Begun and focused: the runtime gives the hands now.
  bool focused() const { return state_ == XR_SESSION_STATE_FOCUSED; }
  // The runtime is losing the session (the device went away): not a normal end.
  bool lost() const { return lost_; }
  // Asks the runtime to end the session (Ctrl-C): poll() goes on until it is over.
  void request_exit();

  XrTime time_at(int64_t monotonic_ns) const;
  // The hand's joints at `time` in the reference space (the joints log's space xr, `t_ns` as
  // given); false when the runtime does not track the hand then.
  bool locate(bool left_hand, XrTime time, int64_t t_ns, hand::tracking::JointsFrame& out);

  const std::string& runtime_name() const { return runtime_name_; }
  const std::string& system_name() const { return system_name_; }
  const ValidationCounts& validation() const { return validation_; }

 private:
  template <typename F>
  F proc(const char* name) const;
  void check(XrResult result, const char* call) const;
  void on_state(XrSessionState state);

  XrInstance instance_ = XR_NULL_HANDLE;
  XrDebugUtilsMessengerEXT messenger_ = XR_NULL_HANDLE;
  XrSystemId system_ = XR_NULL_SYSTEM_ID;
  XrSession session_ = XR_NULL_HANDLE;
  XrSpace space_ = XR_NULL_HANDLE;
  std::array<XrHandTrackerEXT, 2> trackers_{XR_NULL_HANDLE, XR_NULL_HANDLE};  // right, left
  XrSessionState state_ = XR_SESSION_STATE_UNKNOWN;
  bool running_ = false;
  bool over_ = false;
  bool lost_ = false;
  std::string runtime_name_;
  std::string system_name_;
  ValidationCounts validation_;
  std::array<XrHandJointLocationEXT, XR_HAND_JOINT_COUNT_EXT> locations_{};

  PFN_xrCreateHandTrackerEXT create_hand_tracker_ = nullptr;
  PFN_xrDestroyHandTrackerEXT destroy_hand_tracker_ = nullptr;
  PFN_xrLocateHandJointsEXT locate_hand_joints_ = nullptr;
  PFN_xrVoidFunction convert_timespec_ = nullptr;
  PFN_xrDestroyDebugUtilsMessengerEXT destroy_messenger_ = nullptr;
};

}  // namespace vcockpit::glove::xr
