#pragma once
// The physics node's DDS outputs: the world as topics. Messages are preallocated and fixed-size,
// so publishing in the loop neither allocates nor throws.
//   cockpit/object_info   every object's geometry and colour, once (state: transient local)
//   cockpit/hand_info     each simulated hand's capsules and palm box, once (state, keyed by
//                         hand_id), so the image generator draws these hands and not its own
//   cockpit/hand_state    each active hand's 16 link poses and the sample they came from (stream)
//   cockpit/object_state  every dynamic object's pose and velocities (state)
//   cockpit/grasp_event   every GRASP and RELEASE with its reason (event)
//   cockpit/control_info  every control's kind, joint and named positions, once (state)
//   cockpit/control_state a control's coordinate, position and light when they change (state;
//                         at rest, again now and then: History span below)
//   cockpit/control_event every change of a control's position with its cause (event)
//   cockpit/node_status   rates, stage timings, counters, glove liveliness (state)
//
// History span: on every periodic heartbeat Fast DDS 2.9 walks each hole in a reliable writer's
// history one sequence number at a time, in the writer (GAPs) and in every reader
// (StatefulReader::processGapMsg). With keep last 1 per instance, an instance written once (a
// static object, a control at rest) keeps its old sequence number while the others go on, so
// the hole, and the readers' CPU, grew with run time. On object_state and control_state an
// instance whose last sample is history_span_samples writes behind the newest is written again,
// unchanged (HistorySpan).
//
// No NaN or infinity is published (physics_io::NonFiniteGuard: counted, named once in the log):
// an object or hand sample with one is not sent (the last good one stands); an object_info with
// one is not sent; a grasp event is sent with a residual that is not finite replaced by -1 (the
// residuals are magnitudes: negative means "not available"); a node_status with a rate or stage
// time that is not finite is sent with -1 in its place.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dds/dds_participant.hpp"
#include "physics_node/io/non_finite_guard.hpp"
#include "physics_node/physics/world.hpp"

namespace vcockpit::physics_node {

// Where a hand's current input came from, for hand_state.
struct InputStamps {
  int64_t sample_time_ns = 0;
  int64_t source_stamp_ns = 0;
};

// One hand's input as hand_state reports it.
struct HandInputState {
  InputStamps stamps;
  bool tracking = false;
};

// The most writes an instance's kept sample may lag behind its keep-last-1 writer's newest
// (see "History span" above): at least 1024, and 8 per instance so that the rewrites stay
// within an eighth of the writes.
constexpr uint64_t history_span_samples(std::size_t instances) {
  return std::max<uint64_t>(1024, 8 * static_cast<uint64_t>(instances));
}

// Counts one keyed writer's samples and which of them each instance's last one was: an
// instance is due when its last sample lies history_span_samples behind the newest.
class HistorySpan {
 public:
  explicit HistorySpan(std::size_t instances)
      : last_(instances, 0), span_samples_(history_span_samples(instances)) {}
  void wrote(std::size_t instance) { last_[instance] = ++written_; }
  // written at least once, and that long ago
  bool due(std::size_t instance) const {
    return last_[instance] != 0 && written_ - last_[instance] >= span_samples_;
  }

 private:
  uint64_t written_ = 0;
  std::vector<uint64_t> last_;  // per instance: written_ just after its last sample, 0 never
  uint64_t span_samples_;
};

class StatePublisher {
 public:
  StatePublisher(DdsParticipant& participant, const physics::World& world);

  void publish_object_info(const physics::World& world);
  void publish_control_info(const physics::World& world);
  // Each hand's geometry (nothing when the scene has no hand).
  void publish_hand_info(const physics::World& world);
  // The objects, the controls, and each active hand (`hands`: per world hand; a hand beyond its
  // size is published with no stamps and tracking).
  void publish_state(const physics::World& world, const std::vector<HandInputState>& hands);
  void publish_events(const physics::World& world);
  void publish_status(const cockpit::NodeStatus& status);
  // cockpit/control_state of each control that changed since its last sample (publish_state
  // calls it; a node that publishes no hand state can call it alone)
  void publish_controls(const physics::World& world);
  // Waits (bounded) until reliable readers have the last state and events, before shutdown.
  void flush(int64_t timeout_ns);

  // Samples not sent and values replaced because they were not finite, over all topics.
  uint64_t non_finite_refused() const {
    return info_guard_.refused() + object_guard_.refused() + hand_guard_.refused() +
           event_guard_.refused() + status_guard_.refused() + control_guard_.refused();
  }

 private:
  void publish_hand(const physics::World& world, int hand, const HandInputState& input);
  void write_object(const cockpit::ObjectState& msg);
  void write_control(const cockpit::ControlState& msg);
  // Writes again, unchanged, each instance whose last sample is due (HistorySpan).
  void rewrite_due_objects();
  void rewrite_due_controls();

  Writer<cockpit::ObjectInfo> info_writer_;
  Writer<cockpit::HandInfo> hand_info_writer_;
  Writer<cockpit::HandState> hand_writer_;
  Writer<cockpit::ObjectState> object_writer_;
  Writer<cockpit::GraspEvent> event_writer_;
  Writer<cockpit::NodeStatus> status_writer_;
  Writer<cockpit::ControlInfo> control_info_writer_;
  Writer<cockpit::ControlState> control_writer_;
  Writer<cockpit::ControlEvent> control_event_writer_;
  cockpit::ControlState control_msg_;
  cockpit::ControlEvent control_event_msg_;
  uint64_t control_event_seq_ = 0;
  // per control, what its last control_state said (a control at rest is not re-sent)
  struct SentControl {
    bool valid = false;
    double q = 0.0;
    double qd = 0.0;
    int position = 0;
    int held_by = physics::kNotHeld;
  };
  std::vector<SentControl> control_sent_;
  // per object and per control, the last sample written, and when (History span)
  std::vector<cockpit::ObjectState> object_last_;
  std::vector<cockpit::ControlState> control_last_;
  HistorySpan object_span_;
  HistorySpan control_span_;
  cockpit::HandState hand_msg_;
  cockpit::ObjectState object_msg_;
  cockpit::GraspEvent event_msg_;
  std::vector<uint64_t> hand_seq_;  // per hand
  uint64_t event_seq_ = 0;
  physics_io::NonFiniteGuard info_guard_{"cockpit/object_info"};
  physics_io::NonFiniteGuard object_guard_{"cockpit/object_state"};
  physics_io::NonFiniteGuard hand_guard_{"cockpit/hand_state"};
  physics_io::NonFiniteGuard event_guard_{"cockpit/grasp_event"};
  physics_io::NonFiniteGuard status_guard_{"cockpit/node_status"};
  physics_io::NonFiniteGuard control_guard_{"cockpit/control_state"};
};

}  // namespace vcockpit::physics_node
