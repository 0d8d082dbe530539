#pragma once
// The instructor station's DDS side: reads what the page shows into the StationModel (node
// status, the world's hands, objects and controls, grasp, control and sim events, the preview of
// the pilot's view) and sends the page's commands on cockpit/sim_command and
// cockpit/control_command; the aircraft's systems, failures and the lesson's score
// (systems_node), and failures sent on cockpit/failure_command. poll() runs on one thread; the
// send calls may come from any.

#include <cstdint>
#include <mutex>
#include <string>

#include "dds/dds_participant.hpp"
#include "instructor/station_model.hpp"

namespace vcockpit::instructor {

class StationLink {
 public:
  StationLink(DdsParticipant& participant, StationModel& model, std::string source_name);

  // Takes everything that arrived into the model.
  void poll();

  // Each returns the command's sequence number (per station), or -1 if it could not be written.
  int64_t send_sim(cockpit::SimCommandKind kind, const std::string& checkpoint);
  int64_t send_control(uint32_t control_id, uint32_t position);
  int64_t send_failure(const std::string& failure, bool inserted);

 private:
  StationModel& model_;
  std::string source_name_;
  Reader<cockpit::NodeStatus> status_reader_;
  Reader<cockpit::HandState> hand_reader_;
  Reader<cockpit::ObjectInfo> object_info_reader_;
  Reader<cockpit::ObjectState> object_reader_;
  Reader<cockpit::ControlInfo> control_info_reader_;
  Reader<cockpit::ControlState> control_reader_;
  Reader<cockpit::GraspEvent> grasp_reader_;
  Reader<cockpit::ControlEvent> control_event_reader_;
  Reader<cockpit::SimAck> ack_reader_;
  Reader<cockpit::PreviewFrame> preview_reader_;
  Reader<cockpit::SystemsInfo> systems_info_reader_;
  Reader<cockpit::SystemsState> systems_state_reader_;
  Reader<cockpit::SystemsEvent> systems_event_reader_;
  Reader<cockpit::FailureAck> failure_ack_reader_;
  Reader<cockpit::ProcedureScore> score_reader_;
  std::mutex send_mutex_;
  Writer<cockpit::SimCommand> sim_writer_;
  Writer<cockpit::ControlCommand> control_writer_;
  Writer<cockpit::FailureCommand> failure_writer_;
  uint64_t next_seq_ = 0;
  // poll()'s buffers
  cockpit::NodeStatus status_;
  cockpit::HandState hand_;
  cockpit::ObjectInfo object_info_;
  cockpit::ObjectState object_;
  cockpit::ControlInfo control_info_;
  cockpit::ControlState control_;
  cockpit::GraspEvent grasp_;
  cockpit::ControlEvent control_event_;
  cockpit::SimAck ack_;
  cockpit::PreviewFrame preview_;
  cockpit::SystemsInfo systems_info_;
  cockpit::SystemsState systems_state_;
  cockpit::SystemsEvent systems_event_;
  cockpit::FailureAck failure_ack_;
  cockpit::ProcedureScore score_;
};

}  // namespace vcockpit::instructor
