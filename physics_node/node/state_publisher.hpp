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
//   cockpit/control_state a control's coordinate, position and light when they change (state)
//   cockpit/control_event every change of a control's position with its cause (event)
//   cockpit/node_status   rates, stage timings, counters, glove liveliness (state)
//
// No NaN or infinity is published (physics_io::NonFiniteGuard: counted, named once in the log):
// an object or hand sample with one is not sent (the last good one stands); an object_info with
// one is not sent; a grasp event is sent with a residual that is not finite replaced by -1 (the
// residuals are magnitudes: negative means "not available"); a node_status with a rate or stage
// time that is not finite is sent with -1 in its place.

#include <cstdint>
#include <vector>

#include "common/dds_participant.hpp"
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
