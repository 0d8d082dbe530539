#pragma once
// cockpit/tracked_joints: the tracker's joints each retargeted sample came from (--source joints),
// for the image generator to draw beside the fitted hand. Reliable in lockstep, as the samples
// are; a stream at the samples' pace otherwise (what a viewer misses, it misses).

#include <cstdint>

#include "dds/dds_participant.hpp"
#include "hand/tracking/joints_log.hpp"

namespace vcockpit::glove {

class TrackedJointsPublisher {
 public:
  TrackedJointsPublisher(DdsParticipant& participant, uint32_t hand_id, bool lockstep);

  // The frame's joints (in G) with the sample's time; false if the middleware refused it.
  bool publish(const hand::tracking::JointsFrame& frame_G, int64_t sample_time_ns);
  uint64_t published() const { return published_; }

 private:
  uint32_t hand_id_;
  Writer<cockpit::TrackedJoints> writer_;
  cockpit::TrackedJoints message_;
  uint64_t published_ = 0;
};

}  // namespace vcockpit::glove
