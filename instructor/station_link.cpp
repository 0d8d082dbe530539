#include "instructor/station_link.hpp"

#include "common/clock.hpp"

namespace vcockpit::instructor {

StationLink::StationLink(DdsParticipant& participant, StationModel& model, std::string source_name)
    : model_(model),
      source_name_(std::move(source_name)),
      status_reader_(participant.make_reader<cockpit::NodeStatus>("state")),
      hand_reader_(participant.make_reader<cockpit::HandState>("stream")),
      object_info_reader_(participant.make_reader<cockpit::ObjectInfo>("state")),
      object_reader_(participant.make_reader<cockpit::ObjectState>("state")),
      control_info_reader_(participant.make_reader<cockpit::ControlInfo>("state")),
      control_reader_(participant.make_reader<cockpit::ControlState>("state")),
      grasp_reader_(participant.make_reader<cockpit::GraspEvent>("event")),
      control_event_reader_(participant.make_reader<cockpit::ControlEvent>("event")),
      ack_reader_(participant.make_reader<cockpit::SimAck>("event")),
      preview_reader_(participant.make_reader<cockpit::PreviewFrame>("preview")),
      systems_info_reader_(participant.make_reader<cockpit::SystemsInfo>("state")),
      systems_state_reader_(participant.make_reader<cockpit::SystemsState>("state")),
      systems_event_reader_(participant.make_reader<cockpit::SystemsEvent>("event")),
      failure_ack_reader_(participant.make_reader<cockpit::FailureAck>("command")),
      score_reader_(participant.make_reader<cockpit::ProcedureScore>("state")),
      sim_writer_(participant.make_writer<cockpit::SimCommand>("command")),
      control_writer_(participant.make_writer<cockpit::ControlCommand>("command")),
      failure_writer_(participant.make_writer<cockpit::FailureCommand>("command")) {}

void StationLink::poll() {
  const int64_t now_ns = monotonic_now_ns();
  // names before the events that use them
  while (object_info_reader_.take(object_info_)) model_.on_object_info(object_info_);
  while (control_info_reader_.take(control_info_)) model_.on_control_info(control_info_);
  while (status_reader_.take(status_)) model_.on_status(status_, now_ns);
  while (hand_reader_.take(hand_)) model_.on_hand(hand_);
  while (object_reader_.take(object_)) model_.on_object_state(object_);
  while (control_reader_.take(control_)) model_.on_control_state(control_);
  while (grasp_reader_.take(grasp_)) model_.on_grasp_event(grasp_);
  while (control_event_reader_.take(control_event_)) model_.on_control_event(control_event_);
  while (ack_reader_.take(ack_)) model_.on_ack(ack_);
  while (preview_reader_.take(preview_)) model_.on_preview(preview_, now_ns);
  while (systems_info_reader_.take(systems_info_)) model_.on_systems_info(systems_info_);
  while (systems_state_reader_.take(systems_state_)) model_.on_systems_state(systems_state_);
  while (systems_event_reader_.take(systems_event_)) model_.on_systems_event(systems_event_);
  while (failure_ack_reader_.take(failure_ack_)) model_.on_failure_ack(failure_ack_);
  while (score_reader_.take(score_)) model_.on_procedure_score(score_);
}

namespace {
constexpr int64_t kMatchWaitNs = 2'000'000'000;
}  // namespace

int64_t StationLink::send_sim(cockpit::SimCommandKind kind, const std::string& checkpoint) {
  std::lock_guard<std::mutex> lock(send_mutex_);
  cockpit::SimCommand command;
  command.seq(next_seq_);
  command.kind(kind);
  command.checkpoint(checkpoint.substr(0, 64));
  command.source(source_name_);
  // the command topic is volatile: written before the physics node's reader has matched (a
  // click right after start, a slow discovery), a command would be lost without a word
  sim_writer_.wait_for_matched(1, kMatchWaitNs);
  if (!sim_writer_.write(command)) return -1;
  return static_cast<int64_t>(next_seq_++);
}

int64_t StationLink::send_control(uint32_t control_id, uint32_t position) {
  std::lock_guard<std::mutex> lock(send_mutex_);
  cockpit::ControlCommand command;
  command.seq(next_seq_);
  command.control_id(control_id);
  command.position(position);
  command.source(source_name_);
  control_writer_.wait_for_matched(1, kMatchWaitNs);
  if (!control_writer_.write(command)) return -1;
  return static_cast<int64_t>(next_seq_++);
}

int64_t StationLink::send_failure(const std::string& failure, bool inserted) {
  std::lock_guard<std::mutex> lock(send_mutex_);
  cockpit::FailureCommand command;
  command.seq(next_seq_);
  command.failure(failure.substr(0, 64));
  command.inserted(inserted);
  command.source(source_name_);
  failure_writer_.wait_for_matched(1, kMatchWaitNs);
  if (!failure_writer_.write(command)) return -1;
  return static_cast<int64_t>(next_seq_++);
}

}  // namespace vcockpit::instructor
