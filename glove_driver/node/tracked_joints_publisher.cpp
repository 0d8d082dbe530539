#include "glove_driver/node/tracked_joints_publisher.hpp"

#include "idl/topics/pose_convert.hpp"

namespace vcockpit::glove {

TrackedJointsPublisher::TrackedJointsPublisher(DdsParticipant& participant, uint32_t hand_id,
                                               bool lockstep)
    : hand_id_(hand_id),
      writer_(participant.make_writer<cockpit::TrackedJoints>(lockstep ? "reliable" : "hand_stream")) {}

bool TrackedJointsPublisher::publish(const hand::tracking::JointsFrame& frame_G,
                                     int64_t sample_time_ns) {
  message_.hand_id(hand_id_);
  message_.seq(published_);
  message_.sample_time_ns(sample_time_ns);
  for (int j = 0; j < hand::tracking::kXrJointCount; ++j) {
    const hand::tracking::TrackedJoint& joint = frame_G.joints[static_cast<std::size_t>(j)];
    message_.valid()[static_cast<std::size_t>(j)] = joint.valid;
    message_.p_G_m()[static_cast<std::size_t>(j)] =
        to_idl(joint.valid ? joint.p_m : Eigen::Vector3d::Zero());
  }
  if (!writer_.write(message_)) return false;
  ++published_;
  return true;
}

}  // namespace vcockpit::glove
