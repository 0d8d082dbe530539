// The joints-log replay runtime: an OpenXR runtime that the Khronos loader loads like any other
// (its manifest, selected with XR_RUNTIME_JSON, names this library) and that serves a hand-joints
// log (hand/tracking/joints_log.hpp) as a headset's hand tracking would. It is what
// openxr_hand_bridge is tested against and what a user can try the bridge with, no headset needed.
//
// Set by the environment:
//   VCOCKPIT_XR_REPLAY_LOG    the hand-joints log (space xr), required
//   VCOCKPIT_XR_REPLAY_RATE   log seconds per second (default 1)
//   VCOCKPIT_XR_REPLAY_LOOP   1: start over at the end; else the session stops at the log's end
//
// What it offers: XR_EXT_hand_tracking (both hands, the default joint set), XR_MND_headless (a
// session without graphics; the only kind it makes) and XR_KHR_convert_timespec_time (XrTime is
// CLOCK_MONOTONIC in ns). One system, a head-mounted display. Reference spaces VIEW, LOCAL and
// STAGE are all the log's frame (no head, no floor). A headless session goes IDLE -> READY at
// once, SYNCHRONIZED -> VISIBLE -> FOCUSED when begun, and at the log's end (not looping) or on
// xrRequestExitSession back down to STOPPING; xrEndSession then gives IDLE and EXITING.
// The frame loop (xrWaitFrame at 90 Hz, xrBeginFrame, xrEndFrame with no layers) and
// xrLocateSpace work too; it has no views (no view configuration), and the other core functions
// (swapchains, actions, paths) return XR_ERROR_FUNCTION_UNSUPPORTED.
// Errors that are the caller's give the result the specification names; a log that cannot be
// read fails xrCreateInstance with XR_ERROR_RUNTIME_FAILURE, and the reason on stderr.

#define XR_USE_TIMESPEC
#include <time.h>

#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>

#include "glove_driver/openxr/loader_interface.hpp"
#include "glove_driver/openxr/xr_names.hpp"
#include "glove_driver/openxr/xr_struct.hpp"
#include "glove_driver/openxr/replay_runtime/joints_timeline.hpp"
#include "hand/tracking/joints_log.hpp"

namespace vcockpit::glove::xr_replay {
namespace {

using hand::tracking::JointsFrame;
using xr::xr_struct;

static_assert(XR_HAND_JOINT_COUNT_EXT == hand::tracking::kXrJointCount);
static_assert(XR_HAND_JOINT_LITTLE_TIP_EXT == static_cast<int>(hand::tracking::XrJoint::kLittleTip));
static_assert(XR_HAND_JOINT_THUMB_TIP_EXT == static_cast<int>(hand::tracking::XrJoint::kThumbTip));

constexpr XrSystemId kSystemId = 1;
constexpr double kMaxRate = 1000.0;  // log seconds per second
constexpr int64_t kFramePeriod_ns = 11'111'111;  // 90 Hz
constexpr float kDefaultJointRadius_m = 0.008f;  // when the log has none

int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

void copy_name(char* out, std::size_t size, const char* name) {
  std::snprintf(out, size, "%s", name);
}

struct Instance;

struct Session {
  Instance* instance = nullptr;
  XrSessionState delivered = XR_SESSION_STATE_UNKNOWN;  // the last state the application was told
  XrSessionState queued = XR_SESSION_STATE_UNKNOWN;     // the last state an event was queued for
  bool running = false;           // between xrBeginSession and xrEndSession
  bool exit_requested = false;
  int64_t begin_ns = 0;           // xrBeginSession: the log's start
  int64_t frames_waited = 0;
  bool frame_waited = false;      // xrWaitFrame since the last xrBeginFrame
  bool frame_begun = false;
};

struct Space {
  Session* session = nullptr;
  XrPosef pose_in_log{};  // the space's origin in the log's frame
};

struct HandTracker {
  Session* session = nullptr;
  bool left = false;
};

struct Instance {
  bool hand_tracking = false;
  bool headless = false;
  bool timespec = false;
  std::unique_ptr<JointsTimeline> timeline;
  std::deque<XrEventDataSessionStateChanged> events;
};

// Every live handle, so that a stale or foreign one is XR_ERROR_HANDLE_INVALID, not a crash.
struct Registry {
  std::mutex mutex;
  std::set<std::unique_ptr<Instance>> instances_owned;
  std::set<Instance*> instances;
  std::set<Session*> sessions;
  std::set<Space*> spaces;
  std::set<HandTracker*> trackers;
};
Registry& registry() {
  static Registry r;
  return r;
}

template <typename T>
T* as(const std::set<T*>& live, const void* handle) {
  T* p = static_cast<T*>(const_cast<void*>(handle));
  return live.count(p) > 0 ? p : nullptr;
}
Instance* instance_of(XrInstance h) { return as(registry().instances, h); }
Session* session_of(XrSession h) { return as(registry().sessions, h); }
Space* space_of(XrSpace h) { return as(registry().spaces, h); }
HandTracker* tracker_of(XrHandTrackerEXT h) { return as(registry().trackers, h); }

void queue_state(Session& s, XrSessionState state) {
  auto e = xr_struct<XrEventDataSessionStateChanged>(XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED);
  e.session = reinterpret_cast<XrSession>(&s);
  e.state = state;
  e.time = monotonic_ns();
  s.queued = state;
  try {
    s.instance->events.push_back(e);
  } catch (const std::bad_alloc&) {  // out of memory: the event is lost, as the spec allows
    std::fprintf(stderr, "vcockpit replay runtime: out of memory: a session state event is lost\n");
  }
}

// Adds a new object to its registry set: false (and nothing kept) when out of memory.
template <typename T>
bool register_new(std::set<T*>& live, std::unique_ptr<T>& object) {
  try {
    live.insert(object.get());
  } catch (const std::bad_alloc&) {
    return false;
  }
  object.release();
  return true;
}

// A running session whose log ended (or whose exit was asked for) goes down to STOPPING.
void stop_if_due(Session& s) {
  if (!s.running || s.queued == XR_SESSION_STATE_STOPPING) return;
  const bool ended = s.instance->timeline->ended(monotonic_ns() - s.begin_ns);
  if (!ended && !s.exit_requested) return;
  if (s.queued == XR_SESSION_STATE_FOCUSED) queue_state(s, XR_SESSION_STATE_VISIBLE);
  if (s.queued == XR_SESSION_STATE_VISIBLE) queue_state(s, XR_SESSION_STATE_SYNCHRONIZED);
  queue_state(s, XR_SESSION_STATE_STOPPING);
}

const XrBaseInStructure* find_in_chain(const void* next, XrStructureType type) {
  for (auto* p = static_cast<const XrBaseInStructure*>(next); p != nullptr; p = p->next)
    if (p->type == type) return p;
  return nullptr;
}

std::string env_or(const char* name, const char* fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? v : fallback;
}

// ---- extensions, instance, system -------------------------------------------------------------

struct Extension {
  const char* name;
  uint32_t version;
};
constexpr Extension kExtensions[] = {
    {XR_EXT_HAND_TRACKING_EXTENSION_NAME, XR_EXT_hand_tracking_SPEC_VERSION},
    {XR_MND_HEADLESS_EXTENSION_NAME, XR_MND_headless_SPEC_VERSION},
    {XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME, XR_KHR_convert_timespec_time_SPEC_VERSION},
};

XRAPI_ATTR XrResult XRAPI_CALL EnumerateInstanceExtensionProperties(
    const char* layer_name, uint32_t capacity, uint32_t* count, XrExtensionProperties* properties) {
  if (layer_name != nullptr && *layer_name != '\0') return XR_ERROR_API_LAYER_NOT_PRESENT;
  if (count == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  constexpr uint32_t n = sizeof(kExtensions) / sizeof(kExtensions[0]);
  *count = n;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < n) return XR_ERROR_SIZE_INSUFFICIENT;
  if (properties == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  for (uint32_t i = 0; i < n; ++i) {
    if (properties[i].type != XR_TYPE_EXTENSION_PROPERTIES) return XR_ERROR_VALIDATION_FAILURE;
    copy_name(properties[i].extensionName, XR_MAX_EXTENSION_NAME_SIZE, kExtensions[i].name);
    properties[i].extensionVersion = kExtensions[i].version;
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL CreateInstance(const XrInstanceCreateInfo* info, XrInstance* out) {
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_INSTANCE_CREATE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (XR_VERSION_MAJOR(info->applicationInfo.apiVersion) != 1) return XR_ERROR_API_VERSION_UNSUPPORTED;
  auto instance = std::make_unique<Instance>();
  if (info->enabledExtensionCount > 0 && info->enabledExtensionNames == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  for (uint32_t i = 0; i < info->enabledExtensionCount; ++i) {
    if (info->enabledExtensionNames[i] == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    const std::string name = info->enabledExtensionNames[i];
    if (name == XR_EXT_HAND_TRACKING_EXTENSION_NAME) instance->hand_tracking = true;
    else if (name == XR_MND_HEADLESS_EXTENSION_NAME) instance->headless = true;
    else if (name == XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME) instance->timespec = true;
    else if (name == XR_EXT_DEBUG_UTILS_EXTENSION_NAME) continue;  // the loader's own
    else return XR_ERROR_EXTENSION_NOT_PRESENT;
  }
  const std::string path = env_or("VCOCKPIT_XR_REPLAY_LOG", "");
  try {
    if (path.empty()) throw std::invalid_argument("VCOCKPIT_XR_REPLAY_LOG names no hand-joints log");
    const hand::tracking::JointsLog log = hand::tracking::read_joints_log(path);
    if (log.space != hand::tracking::JointsSpace::kXr)
      throw std::invalid_argument(path + ": space " + hand::tracking::joints_space_name(log.space) +
                                  ": the replay runtime serves a tracker's own frame, space xr");
    const std::string rate_text = env_or("VCOCKPIT_XR_REPLAY_RATE", "1");
    char* end = nullptr;
    const double rate = std::strtod(rate_text.c_str(), &end);
    if (end == rate_text.c_str() || *end != '\0' || !(rate > 0.0) || !(rate <= kMaxRate))
      throw std::invalid_argument("VCOCKPIT_XR_REPLAY_RATE '" + rate_text + "' is not a number in (0, 1000]");
    instance->timeline = std::make_unique<JointsTimeline>(
        log.frames, rate, env_or("VCOCKPIT_XR_REPLAY_LOOP", "0") == "1");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vcockpit replay runtime: %s\n", e.what());
    return XR_ERROR_RUNTIME_FAILURE;
  }
  std::lock_guard<std::mutex> lock(registry().mutex);
  Instance* handle = instance.get();
  try {
    registry().instances_owned.insert(std::move(instance));
    registry().instances.insert(handle);
  } catch (const std::bad_alloc&) {
    registry().instances.erase(handle);
    for (auto it = registry().instances_owned.begin(); it != registry().instances_owned.end(); ++it)
      if (it->get() == handle) { registry().instances_owned.erase(it); break; }
    return XR_ERROR_OUT_OF_MEMORY;
  }
  *out = reinterpret_cast<XrInstance>(handle);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL DestroyInstance(XrInstance handle) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Instance* instance = instance_of(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  Registry& r = registry();
  for (auto it = r.trackers.begin(); it != r.trackers.end();) {
    if ((*it)->session->instance == instance) { delete *it; it = r.trackers.erase(it); } else { ++it; }
  }
  for (auto it = r.spaces.begin(); it != r.spaces.end();) {
    if ((*it)->session->instance == instance) { delete *it; it = r.spaces.erase(it); } else { ++it; }
  }
  for (auto it = r.sessions.begin(); it != r.sessions.end();) {
    if ((*it)->instance == instance) { delete *it; it = r.sessions.erase(it); } else { ++it; }
  }
  r.instances.erase(instance);
  for (auto it = r.instances_owned.begin(); it != r.instances_owned.end(); ++it) {
    if (it->get() == instance) { r.instances_owned.erase(it); break; }
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL GetInstanceProperties(XrInstance handle, XrInstanceProperties* p) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  if (instance_of(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (p == nullptr || p->type != XR_TYPE_INSTANCE_PROPERTIES) return XR_ERROR_VALIDATION_FAILURE;
  p->runtimeVersion = XR_MAKE_VERSION(1, 0, 0);
  copy_name(p->runtimeName, XR_MAX_RUNTIME_NAME_SIZE, "vcockpit joints-log replay");
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL ResultToString(XrInstance handle, XrResult value, char* buffer) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  if (instance_of(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  if (const char* name = xr::xr_result_name(value)) {
    copy_name(buffer, XR_MAX_RESULT_STRING_SIZE, name);
  } else {
    std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "XR_%s_%d", value < 0 ? "UNKNOWN_FAILURE" : "UNKNOWN_SUCCESS",
                  static_cast<int>(value));
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL StructureTypeToString(XrInstance handle, XrStructureType value, char* buffer) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  if (instance_of(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  if (const char* name = xr::xr_structure_type_name(value))
    copy_name(buffer, XR_MAX_STRUCTURE_NAME_SIZE, name);
  else
    std::snprintf(buffer, XR_MAX_STRUCTURE_NAME_SIZE, "XR_UNKNOWN_STRUCTURE_TYPE_%d", static_cast<int>(value));
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL GetSystem(XrInstance handle, const XrSystemGetInfo* info, XrSystemId* id) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  if (instance_of(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || id == nullptr || info->type != XR_TYPE_SYSTEM_GET_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (info->formFactor != XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY) return XR_ERROR_FORM_FACTOR_UNSUPPORTED;
  *id = kSystemId;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL GetSystemProperties(XrInstance handle, XrSystemId id, XrSystemProperties* p) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  if (instance_of(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (id != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  if (p == nullptr || p->type != XR_TYPE_SYSTEM_PROPERTIES) return XR_ERROR_VALIDATION_FAILURE;
  p->systemId = kSystemId;
  p->vendorId = 0;
  copy_name(p->systemName, XR_MAX_SYSTEM_NAME_SIZE, "vcockpit hand-joints log");
  p->graphicsProperties = {0, 0, 0};
  p->trackingProperties = {XR_TRUE, XR_TRUE};
  for (auto* q = static_cast<XrBaseOutStructure*>(p->next); q != nullptr; q = q->next) {
    if (q->type == XR_TYPE_SYSTEM_HAND_TRACKING_PROPERTIES_EXT)
      reinterpret_cast<XrSystemHandTrackingPropertiesEXT*>(q)->supportsHandTracking = XR_TRUE;
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL PollEvent(XrInstance handle, XrEventDataBuffer* buffer) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Instance* instance = instance_of(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (buffer == nullptr || buffer->type != XR_TYPE_EVENT_DATA_BUFFER) return XR_ERROR_VALIDATION_FAILURE;
  for (Session* s : registry().sessions)
    if (s->instance == instance) stop_if_due(*s);
  if (instance->events.empty()) return XR_EVENT_UNAVAILABLE;
  const XrEventDataSessionStateChanged e = instance->events.front();
  instance->events.pop_front();
  if (Session* s = session_of(e.session)) s->delivered = e.state;
  static_assert(sizeof(e) <= sizeof(XrEventDataBuffer));
  std::memcpy(buffer, &e, sizeof(e));
  return XR_SUCCESS;
}

// ---- time ---------------------------------------------------------------------------------------

XRAPI_ATTR XrResult XRAPI_CALL ConvertTimespecTimeToTimeKHR(XrInstance handle, const timespec* t, XrTime* out) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Instance* instance = instance_of(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!instance->timespec) return XR_ERROR_FUNCTION_UNSUPPORTED;
  if (t == nullptr || out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  constexpr int64_t kMaxSeconds = (INT64_MAX - 999'999'999) / 1'000'000'000;
  if (t->tv_nsec < 0 || t->tv_nsec >= 1'000'000'000 || t->tv_sec < 0 || t->tv_sec > kMaxSeconds)
    return XR_ERROR_TIME_INVALID;
  const int64_t ns = static_cast<int64_t>(t->tv_sec) * 1'000'000'000 + t->tv_nsec;
  if (ns <= 0) return XR_ERROR_TIME_INVALID;
  *out = ns;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL ConvertTimeToTimespecTimeKHR(XrInstance handle, XrTime time, timespec* out) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Instance* instance = instance_of(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!instance->timespec) return XR_ERROR_FUNCTION_UNSUPPORTED;
  if (out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  if (time <= 0) return XR_ERROR_TIME_INVALID;
  out->tv_sec = static_cast<time_t>(time / 1'000'000'000);
  out->tv_nsec = static_cast<long>(time % 1'000'000'000);
  return XR_SUCCESS;
}

// ---- session --------------------------------------------------------------------------------------

XRAPI_ATTR XrResult XRAPI_CALL CreateSession(XrInstance handle, const XrSessionCreateInfo* info, XrSession* out) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Instance* instance = instance_of(handle);
  if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_SESSION_CREATE_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (info->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  // no graphics here: only a headless session, without a graphics binding in the chain
  if (!instance->headless) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
  for (const XrStructureType binding :
       {XR_TYPE_GRAPHICS_BINDING_OPENGL_WIN32_KHR, XR_TYPE_GRAPHICS_BINDING_OPENGL_XLIB_KHR,
        XR_TYPE_GRAPHICS_BINDING_OPENGL_XCB_KHR, XR_TYPE_GRAPHICS_BINDING_OPENGL_WAYLAND_KHR,
        XR_TYPE_GRAPHICS_BINDING_OPENGL_ES_ANDROID_KHR, XR_TYPE_GRAPHICS_BINDING_VULKAN_KHR,
        XR_TYPE_GRAPHICS_BINDING_D3D11_KHR, XR_TYPE_GRAPHICS_BINDING_D3D12_KHR,
        XR_TYPE_GRAPHICS_BINDING_EGL_MNDX})
    if (find_in_chain(info->next, binding) != nullptr) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
  auto owned = std::make_unique<Session>();
  owned->instance = instance;
  Session* session = owned.get();
  if (!register_new(registry().sessions, owned)) return XR_ERROR_OUT_OF_MEMORY;
  queue_state(*session, XR_SESSION_STATE_IDLE);
  queue_state(*session, XR_SESSION_STATE_READY);
  *out = reinterpret_cast<XrSession>(session);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL DestroySession(XrSession handle) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Session* session = session_of(handle);
  if (session == nullptr) return XR_ERROR_HANDLE_INVALID;
  Registry& r = registry();
  for (auto it = r.trackers.begin(); it != r.trackers.end();) {
    if ((*it)->session == session) { delete *it; it = r.trackers.erase(it); } else { ++it; }
  }
  for (auto it = r.spaces.begin(); it != r.spaces.end();) {
    if ((*it)->session == session) { delete *it; it = r.spaces.erase(it); } else { ++it; }
  }
  auto& events = session->instance->events;
  events.erase(std::remove_if(events.begin(), events.end(),
                              [&](const XrEventDataSessionStateChanged& e) {
                                return e.session == handle;
                              }),
               events.end());
  r.sessions.erase(session);
  delete session;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL BeginSession(XrSession handle, const XrSessionBeginInfo* info) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || info->type != XR_TYPE_SESSION_BEGIN_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (s->running) return XR_ERROR_SESSION_RUNNING;
  if (s->delivered != XR_SESSION_STATE_READY) return XR_ERROR_SESSION_NOT_READY;
  s->running = true;
  s->begin_ns = monotonic_ns();
  queue_state(*s, XR_SESSION_STATE_SYNCHRONIZED);
  queue_state(*s, XR_SESSION_STATE_VISIBLE);
  queue_state(*s, XR_SESSION_STATE_FOCUSED);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL EndSession(XrSession handle) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (s->delivered != XR_SESSION_STATE_STOPPING) return XR_ERROR_SESSION_NOT_STOPPING;
  s->running = false;
  queue_state(*s, XR_SESSION_STATE_IDLE);
  queue_state(*s, XR_SESSION_STATE_EXITING);  // a replay is not begun twice
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL RequestExitSession(XrSession handle) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  s->exit_requested = true;
  stop_if_due(*s);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL WaitFrame(XrSession handle, const XrFrameWaitInfo* info, XrFrameState* state) {
  int64_t display_ns = 0;
  {
    std::lock_guard<std::mutex> lock(registry().mutex);
    Session* s = session_of(handle);
    if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
    if ((info != nullptr && info->type != XR_TYPE_FRAME_WAIT_INFO) || state == nullptr ||
        state->type != XR_TYPE_FRAME_STATE)
      return XR_ERROR_VALIDATION_FAILURE;
    if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
    ++s->frames_waited;
    s->frame_waited = true;
    display_ns = s->begin_ns + s->frames_waited * kFramePeriod_ns;
    const int64_t now_ns = monotonic_ns();
    if (display_ns < now_ns) {  // the application fell behind: the next display period
      s->frames_waited += (now_ns - display_ns) / kFramePeriod_ns + 1;
      display_ns = s->begin_ns + s->frames_waited * kFramePeriod_ns;
    }
    state->predictedDisplayTime = display_ns;
    state->predictedDisplayPeriod = kFramePeriod_ns;
    state->shouldRender = s->delivered == XR_SESSION_STATE_VISIBLE || s->delivered == XR_SESSION_STATE_FOCUSED;
  }
  // blocks until a period before its display, as a compositor's frame pacing does
  const int64_t wake_ns = display_ns - kFramePeriod_ns;
  const int64_t wait_ns = wake_ns - monotonic_ns();
  if (wait_ns > 0) std::this_thread::sleep_for(std::chrono::nanoseconds(wait_ns));
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL BeginFrame(XrSession handle, const XrFrameBeginInfo* info) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info != nullptr && info->type != XR_TYPE_FRAME_BEGIN_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (!s->frame_waited) return XR_ERROR_CALL_ORDER_INVALID;
  s->frame_waited = false;
  const bool discarded = s->frame_begun;  // begun twice: the first frame is discarded
  s->frame_begun = true;
  return discarded ? XR_FRAME_DISCARDED : XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL EndFrame(XrSession handle, const XrFrameEndInfo* info) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || info->type != XR_TYPE_FRAME_END_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (!s->running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (!s->frame_begun) return XR_ERROR_CALL_ORDER_INVALID;
  if (info->displayTime <= 0) return XR_ERROR_TIME_INVALID;
  if (info->environmentBlendMode != XR_ENVIRONMENT_BLEND_MODE_OPAQUE)
    return XR_ERROR_ENVIRONMENT_BLEND_MODE_UNSUPPORTED;
  if (info->layerCount > 0) return XR_ERROR_LAYER_INVALID;  // headless: nothing to show
  s->frame_begun = false;
  return XR_SUCCESS;
}

// ---- spaces -------------------------------------------------------------------------------------

constexpr XrReferenceSpaceType kSpaces[] = {XR_REFERENCE_SPACE_TYPE_VIEW, XR_REFERENCE_SPACE_TYPE_LOCAL,
                                            XR_REFERENCE_SPACE_TYPE_STAGE};

XRAPI_ATTR XrResult XRAPI_CALL EnumerateReferenceSpaces(XrSession handle, uint32_t capacity, uint32_t* count,
                                                        XrReferenceSpaceType* spaces) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  if (session_of(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (count == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  constexpr uint32_t n = sizeof(kSpaces) / sizeof(kSpaces[0]);
  *count = n;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < n) return XR_ERROR_SIZE_INSUFFICIENT;
  if (spaces == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  std::copy(std::begin(kSpaces), std::end(kSpaces), spaces);
  return XR_SUCCESS;
}

bool valid_pose(const XrPosef& p) {
  const double n = std::sqrt(double(p.orientation.w) * p.orientation.w + double(p.orientation.x) * p.orientation.x +
                             double(p.orientation.y) * p.orientation.y + double(p.orientation.z) * p.orientation.z);
  return std::isfinite(n) && std::abs(n - 1.0) < 1e-3 && std::isfinite(p.position.x) &&
         std::isfinite(p.position.y) && std::isfinite(p.position.z);
}

XRAPI_ATTR XrResult XRAPI_CALL CreateReferenceSpace(XrSession handle, const XrReferenceSpaceCreateInfo* info,
                                                    XrSpace* out) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_REFERENCE_SPACE_CREATE_INFO)
    return XR_ERROR_VALIDATION_FAILURE;
  if (std::find(std::begin(kSpaces), std::end(kSpaces), info->referenceSpaceType) == std::end(kSpaces))
    return XR_ERROR_REFERENCE_SPACE_UNSUPPORTED;
  if (!valid_pose(info->poseInReferenceSpace)) return XR_ERROR_POSE_INVALID;
  auto owned = std::make_unique<Space>(Space{s, info->poseInReferenceSpace});
  Space* space = owned.get();
  if (!register_new(registry().spaces, owned)) return XR_ERROR_OUT_OF_MEMORY;
  *out = reinterpret_cast<XrSpace>(space);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL DestroySpace(XrSpace handle) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Space* space = space_of(handle);
  if (space == nullptr) return XR_ERROR_HANDLE_INVALID;
  registry().spaces.erase(space);
  delete space;
  return XR_SUCCESS;
}

// ---- hand tracking ------------------------------------------------------------------------------

XRAPI_ATTR XrResult XRAPI_CALL CreateHandTrackerEXT(XrSession handle, const XrHandTrackerCreateInfoEXT* info,
                                                    XrHandTrackerEXT* out) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  Session* s = session_of(handle);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!s->instance->hand_tracking) return XR_ERROR_FUNCTION_UNSUPPORTED;
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT)
    return XR_ERROR_VALIDATION_FAILURE;
  if (info->hand != XR_HAND_LEFT_EXT && info->hand != XR_HAND_RIGHT_EXT) return XR_ERROR_VALIDATION_FAILURE;
  if (info->handJointSet != XR_HAND_JOINT_SET_DEFAULT_EXT) return XR_ERROR_VALIDATION_FAILURE;
  auto owned = std::make_unique<HandTracker>(HandTracker{s, info->hand == XR_HAND_LEFT_EXT});
  HandTracker* tracker = owned.get();
  if (!register_new(registry().trackers, owned)) return XR_ERROR_OUT_OF_MEMORY;
  *out = reinterpret_cast<XrHandTrackerEXT>(tracker);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL DestroyHandTrackerEXT(XrHandTrackerEXT handle) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  HandTracker* tracker = tracker_of(handle);
  if (tracker == nullptr) return XR_ERROR_HANDLE_INVALID;
  registry().trackers.erase(tracker);
  delete tracker;
  return XR_SUCCESS;
}

// X_SL: the log's frame seen from the space (the inverse of the space's origin in the log).
Eigen::Isometry3d X_space_log(const XrPosef& pose_in_log) {
  const auto& q = pose_in_log.orientation;
  const auto& p = pose_in_log.position;
  Eigen::Isometry3d X_LS = Eigen::Isometry3d::Identity();
  X_LS.linear() = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
  X_LS.translation() = Eigen::Vector3d(p.x, p.y, p.z);
  return X_LS.inverse();
}

XRAPI_ATTR XrResult XRAPI_CALL LocateHandJointsEXT(XrHandTrackerEXT handle, const XrHandJointsLocateInfoEXT* info,
                                                   XrHandJointLocationsEXT* locations) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  HandTracker* tracker = tracker_of(handle);
  if (tracker == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || locations == nullptr || info->type != XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT ||
      locations->type != XR_TYPE_HAND_JOINT_LOCATIONS_EXT || locations->jointLocations == nullptr)
    return XR_ERROR_VALIDATION_FAILURE;
  if (locations->jointCount != XR_HAND_JOINT_COUNT_EXT) return XR_ERROR_VALIDATION_FAILURE;
  const Space* base = space_of(info->baseSpace);
  if (base == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (base->session != tracker->session) return XR_ERROR_VALIDATION_FAILURE;  // another session's
  if (info->time <= 0) return XR_ERROR_TIME_INVALID;
  auto* velocities = const_cast<XrHandJointVelocitiesEXT*>(reinterpret_cast<const XrHandJointVelocitiesEXT*>(
      find_in_chain(locations->next, XR_TYPE_HAND_JOINT_VELOCITIES_EXT)));
  if (velocities != nullptr && (velocities->jointCount != XR_HAND_JOINT_COUNT_EXT || velocities->jointVelocities == nullptr))
    return XR_ERROR_VALIDATION_FAILURE;

  const Session& s = *tracker->session;
  const JointsFrame* frame = nullptr;
  if (s.running && s.delivered == XR_SESSION_STATE_FOCUSED)
    frame = s.instance->timeline->at(tracker->left, info->time - s.begin_ns);
  locations->isActive = frame != nullptr ? XR_TRUE : XR_FALSE;
  const Eigen::Isometry3d X_SL = X_space_log(base->pose_in_log);
  const Eigen::Quaterniond q_SL(X_SL.linear());
  for (uint32_t j = 0; j < XR_HAND_JOINT_COUNT_EXT; ++j) {
    XrHandJointLocationEXT& out = locations->jointLocations[j];
    if (velocities != nullptr) velocities->jointVelocities[j] = {0, {0, 0, 0}, {0, 0, 0}};
    if (frame == nullptr) {
      out = XrHandJointLocationEXT{0, {{0, 0, 0, 1}, {0, 0, 0}}, 0.0f};
      continue;
    }
    const hand::tracking::TrackedJoint& joint = frame->joints[j];
    // an active hand has every joint's pose valid; a joint the tracker lost is not tracked
    out.locationFlags = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
    if (joint.valid) out.locationFlags |= XR_SPACE_LOCATION_POSITION_TRACKED_BIT;
    if (joint.valid && joint.has_orientation) out.locationFlags |= XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;
    const Eigen::Vector3d p = X_SL * joint.p_m;
    const Eigen::Quaterniond q = (q_SL * (joint.has_orientation ? joint.q : Eigen::Quaterniond::Identity())).normalized();
    out.pose.position = {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
    out.pose.orientation = {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()),
                            static_cast<float>(q.w())};
    out.radius = joint.has_radius ? static_cast<float>(joint.radius_m) : kDefaultJointRadius_m;
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL LocateSpace(XrSpace space_handle, XrSpace base_handle, XrTime time,
                                           XrSpaceLocation* location) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  const Space* space = space_of(space_handle);
  const Space* base = space_of(base_handle);
  if (space == nullptr || base == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (location == nullptr || location->type != XR_TYPE_SPACE_LOCATION) return XR_ERROR_VALIDATION_FAILURE;
  if (space->session->instance != base->session->instance) return XR_ERROR_VALIDATION_FAILURE;
  if (time <= 0) return XR_ERROR_TIME_INVALID;
  // every space is fixed in the log's frame: the space's origin seen from the base
  const Eigen::Isometry3d X_BS = X_space_log(base->pose_in_log) * X_space_log(space->pose_in_log).inverse();
  const Eigen::Quaterniond q(X_BS.linear());
  const Eigen::Vector3d p = X_BS.translation();
  location->locationFlags = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT |
                            XR_SPACE_LOCATION_POSITION_TRACKED_BIT | XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;
  location->pose.position = {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
  location->pose.orientation = {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()),
                                static_cast<float>(q.w())};
  for (auto* q_next = static_cast<XrBaseOutStructure*>(location->next); q_next != nullptr; q_next = q_next->next) {
    if (q_next->type == XR_TYPE_SPACE_VELOCITY) {  // nothing moves: zero, and said to be valid
      auto* v = reinterpret_cast<XrSpaceVelocity*>(q_next);
      v->velocityFlags = XR_SPACE_VELOCITY_LINEAR_VALID_BIT | XR_SPACE_VELOCITY_ANGULAR_VALID_BIT;
      v->linearVelocity = {0, 0, 0};
      v->angularVelocity = {0, 0, 0};
    }
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL GetReferenceSpaceBoundsRect(XrSession handle, XrReferenceSpaceType type,
                                                           XrExtent2Df* bounds) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  if (session_of(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (bounds == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  if (std::find(std::begin(kSpaces), std::end(kSpaces), type) == std::end(kSpaces))
    return XR_ERROR_REFERENCE_SPACE_UNSUPPORTED;
  *bounds = {0.0f, 0.0f};
  return XR_SPACE_BOUNDS_UNAVAILABLE;  // a recording has no play area
}

// No display: no view configuration, and so no blend mode of one.
XRAPI_ATTR XrResult XRAPI_CALL EnumerateViewConfigurations(XrInstance handle, XrSystemId id, uint32_t,
                                                           uint32_t* count, XrViewConfigurationType*) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  if (instance_of(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (id != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  if (count == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *count = 0;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL EnumerateEnvironmentBlendModes(XrInstance handle, XrSystemId id,
                                                              XrViewConfigurationType, uint32_t, uint32_t*,
                                                              XrEnvironmentBlendMode*) {
  std::lock_guard<std::mutex> lock(registry().mutex);
  if (instance_of(handle) == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (id != kSystemId) return XR_ERROR_SYSTEM_INVALID;
  return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
}

// A core function this runtime does not serve (swapchains, views, actions, paths), with its own
// signature, so that an application calling it gets a result and not a jump to nothing.
template <typename F>
struct Unsupported;
template <typename... Args>
struct Unsupported<XrResult(XRAPI_PTR*)(Args...)> {
  static XRAPI_ATTR XrResult XRAPI_CALL call(Args...) { return XR_ERROR_FUNCTION_UNSUPPORTED; }
};

// ---- dispatch -----------------------------------------------------------------------------------

XRAPI_ATTR XrResult XRAPI_CALL GetInstanceProcAddr(XrInstance instance, const char* name, PFN_xrVoidFunction* function);

enum class Needs { kNothing, kHandTracking, kTimespec };  // the extension a function belongs to
struct Entry {
  const char* name;
  PFN_xrVoidFunction function;
  bool without_instance;  // callable with XR_NULL_HANDLE
  Needs needs = Needs::kNothing;
};
#define VCOCKPIT_XR_ENTRY(name, fn, global) \
  Entry { name, reinterpret_cast<PFN_xrVoidFunction>(fn), global }
#define VCOCKPIT_XR_EXT_ENTRY(name, fn, needs) \
  Entry { name, reinterpret_cast<PFN_xrVoidFunction>(fn), false, needs }
#define VCOCKPIT_XR_UNSUPPORTED(name) \
  Entry { #name, reinterpret_cast<PFN_xrVoidFunction>(&Unsupported<PFN_##name>::call), false }
const Entry kEntries[] = {
    VCOCKPIT_XR_ENTRY("xrGetInstanceProcAddr", GetInstanceProcAddr, true),
    VCOCKPIT_XR_ENTRY("xrEnumerateInstanceExtensionProperties", EnumerateInstanceExtensionProperties, true),
    VCOCKPIT_XR_ENTRY("xrCreateInstance", CreateInstance, true),
    VCOCKPIT_XR_ENTRY("xrDestroyInstance", DestroyInstance, false),
    VCOCKPIT_XR_ENTRY("xrGetInstanceProperties", GetInstanceProperties, false),
    VCOCKPIT_XR_ENTRY("xrResultToString", ResultToString, false),
    VCOCKPIT_XR_ENTRY("xrStructureTypeToString", StructureTypeToString, false),
    VCOCKPIT_XR_ENTRY("xrGetSystem", GetSystem, false),
    VCOCKPIT_XR_ENTRY("xrGetSystemProperties", GetSystemProperties, false),
    VCOCKPIT_XR_ENTRY("xrPollEvent", PollEvent, false),
    VCOCKPIT_XR_EXT_ENTRY("xrConvertTimespecTimeToTimeKHR", ConvertTimespecTimeToTimeKHR, Needs::kTimespec),
    VCOCKPIT_XR_EXT_ENTRY("xrConvertTimeToTimespecTimeKHR", ConvertTimeToTimespecTimeKHR, Needs::kTimespec),
    VCOCKPIT_XR_ENTRY("xrCreateSession", CreateSession, false),
    VCOCKPIT_XR_ENTRY("xrDestroySession", DestroySession, false),
    VCOCKPIT_XR_ENTRY("xrBeginSession", BeginSession, false),
    VCOCKPIT_XR_ENTRY("xrEndSession", EndSession, false),
    VCOCKPIT_XR_ENTRY("xrRequestExitSession", RequestExitSession, false),
    VCOCKPIT_XR_ENTRY("xrWaitFrame", WaitFrame, false),
    VCOCKPIT_XR_ENTRY("xrBeginFrame", BeginFrame, false),
    VCOCKPIT_XR_ENTRY("xrEndFrame", EndFrame, false),
    VCOCKPIT_XR_ENTRY("xrEnumerateReferenceSpaces", EnumerateReferenceSpaces, false),
    VCOCKPIT_XR_ENTRY("xrCreateReferenceSpace", CreateReferenceSpace, false),
    VCOCKPIT_XR_ENTRY("xrDestroySpace", DestroySpace, false),
    VCOCKPIT_XR_ENTRY("xrLocateSpace", LocateSpace, false),
    VCOCKPIT_XR_ENTRY("xrGetReferenceSpaceBoundsRect", GetReferenceSpaceBoundsRect, false),
    VCOCKPIT_XR_ENTRY("xrEnumerateViewConfigurations", EnumerateViewConfigurations, false),
    VCOCKPIT_XR_ENTRY("xrEnumerateEnvironmentBlendModes", EnumerateEnvironmentBlendModes, false),
    VCOCKPIT_XR_EXT_ENTRY("xrCreateHandTrackerEXT", CreateHandTrackerEXT, Needs::kHandTracking),
    VCOCKPIT_XR_EXT_ENTRY("xrDestroyHandTrackerEXT", DestroyHandTrackerEXT, Needs::kHandTracking),
    VCOCKPIT_XR_EXT_ENTRY("xrLocateHandJointsEXT", LocateHandJointsEXT, Needs::kHandTracking),
    VCOCKPIT_XR_UNSUPPORTED(xrCreateActionSpace),
    VCOCKPIT_XR_UNSUPPORTED(xrGetViewConfigurationProperties),
    VCOCKPIT_XR_UNSUPPORTED(xrEnumerateViewConfigurationViews),
    VCOCKPIT_XR_UNSUPPORTED(xrEnumerateSwapchainFormats),
    VCOCKPIT_XR_UNSUPPORTED(xrCreateSwapchain),
    VCOCKPIT_XR_UNSUPPORTED(xrDestroySwapchain),
    VCOCKPIT_XR_UNSUPPORTED(xrEnumerateSwapchainImages),
    VCOCKPIT_XR_UNSUPPORTED(xrAcquireSwapchainImage),
    VCOCKPIT_XR_UNSUPPORTED(xrWaitSwapchainImage),
    VCOCKPIT_XR_UNSUPPORTED(xrReleaseSwapchainImage),
    VCOCKPIT_XR_UNSUPPORTED(xrLocateViews),
    VCOCKPIT_XR_UNSUPPORTED(xrStringToPath),
    VCOCKPIT_XR_UNSUPPORTED(xrPathToString),
    VCOCKPIT_XR_UNSUPPORTED(xrCreateActionSet),
    VCOCKPIT_XR_UNSUPPORTED(xrDestroyActionSet),
    VCOCKPIT_XR_UNSUPPORTED(xrCreateAction),
    VCOCKPIT_XR_UNSUPPORTED(xrDestroyAction),
    VCOCKPIT_XR_UNSUPPORTED(xrSuggestInteractionProfileBindings),
    VCOCKPIT_XR_UNSUPPORTED(xrAttachSessionActionSets),
    VCOCKPIT_XR_UNSUPPORTED(xrGetCurrentInteractionProfile),
    VCOCKPIT_XR_UNSUPPORTED(xrGetActionStateBoolean),
    VCOCKPIT_XR_UNSUPPORTED(xrGetActionStateFloat),
    VCOCKPIT_XR_UNSUPPORTED(xrGetActionStateVector2f),
    VCOCKPIT_XR_UNSUPPORTED(xrGetActionStatePose),
    VCOCKPIT_XR_UNSUPPORTED(xrSyncActions),
    VCOCKPIT_XR_UNSUPPORTED(xrEnumerateBoundSourcesForAction),
    VCOCKPIT_XR_UNSUPPORTED(xrGetInputSourceLocalizedName),
    VCOCKPIT_XR_UNSUPPORTED(xrApplyHapticFeedback),
    VCOCKPIT_XR_UNSUPPORTED(xrStopHapticFeedback),
};
#undef VCOCKPIT_XR_UNSUPPORTED
#undef VCOCKPIT_XR_EXT_ENTRY
#undef VCOCKPIT_XR_ENTRY

XRAPI_ATTR XrResult XRAPI_CALL GetInstanceProcAddr(XrInstance instance, const char* name, PFN_xrVoidFunction* function) {
  if (name == nullptr || function == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *function = nullptr;
  bool hand_tracking = false, timespec = false;
  if (instance != XR_NULL_HANDLE) {
    std::lock_guard<std::mutex> lock(registry().mutex);
    const Instance* i = instance_of(instance);
    if (i == nullptr) return XR_ERROR_HANDLE_INVALID;
    hand_tracking = i->hand_tracking;
    timespec = i->timespec;
  }
  for (const Entry& e : kEntries) {
    if (std::strcmp(e.name, name) != 0) continue;
    if (instance == XR_NULL_HANDLE && !e.without_instance) return XR_ERROR_HANDLE_INVALID;
    // an extension's functions only for an instance that enabled it
    if ((e.needs == Needs::kHandTracking && !hand_tracking) || (e.needs == Needs::kTimespec && !timespec))
      return XR_ERROR_FUNCTION_UNSUPPORTED;
    *function = e.function;
    return XR_SUCCESS;
  }
  return XR_ERROR_FUNCTION_UNSUPPORTED;
}

}  // namespace
}  // namespace vcockpit::glove::xr_replay

// The one symbol the loader looks up in a runtime library.
extern "C" __attribute__((visibility("default"))) XrResult XRAPI_CALL xrNegotiateLoaderRuntimeInterface(
    const vcockpit::glove::xr::XrNegotiateLoaderInfo* loader_info,
    vcockpit::glove::xr::XrNegotiateRuntimeRequest* request) {
  using namespace vcockpit::glove::xr;
  if (loader_info == nullptr || request == nullptr ||
      loader_info->structType != XR_LOADER_INTERFACE_STRUCT_LOADER_INFO ||
      loader_info->structVersion != XR_LOADER_INFO_STRUCT_VERSION ||
      loader_info->structSize != sizeof(XrNegotiateLoaderInfo) ||
      request->structType != XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST ||
      request->structVersion != XR_RUNTIME_INFO_STRUCT_VERSION ||
      request->structSize != sizeof(XrNegotiateRuntimeRequest))
    return XR_ERROR_INITIALIZATION_FAILED;
  if (loader_info->minInterfaceVersion > kLoaderRuntimeVersion ||
      loader_info->maxInterfaceVersion < kLoaderRuntimeVersion ||
      XR_VERSION_MAJOR(loader_info->minApiVersion) > 1 || XR_VERSION_MAJOR(loader_info->maxApiVersion) < 1)
    return XR_ERROR_INITIALIZATION_FAILED;
  request->runtimeInterfaceVersion = kLoaderRuntimeVersion;
  request->runtimeApiVersion = XR_CURRENT_API_VERSION;
  request->getInstanceProcAddr = vcockpit::glove::xr_replay::GetInstanceProcAddr;
  return XR_SUCCESS;
}
