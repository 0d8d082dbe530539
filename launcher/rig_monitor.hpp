#pragma once
// The launcher's view of the running rig over DDS: node statuses, grasp and control events, the
// controls' last positions, and the
// glove-to-frame latency of every hand sample the image generator drew (render end minus the
// glove driver's stamp, first frame that drew it; both monotonic on this machine).

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "dds/dds_participant.hpp"
#include "idl/topics/systems_topics.hpp"
#include "common/latency_histogram.hpp"

namespace vcockpit::rig {

struct SeenEvent {
  double t_s = 0;
  bool grasp = true;
  int hand_id = 0;  // 0 right, 1 left
  std::string object;
  std::string reason;
};

// A change of a cockpit control's position (cockpit/control_event), named.
struct SeenControlEvent {
  double t_s = 0;
  std::string control;
  std::string from;
  std::string to;
  std::string cause;  // pushed, grasped, commanded, mechanism, object
  std::string link;   // the hand link that pushed it; empty when none
};

// A change of the aircraft's systems (cockpit/systems_event): a system's value or a failure.
struct SeenSystemsEvent {
  double t_s = 0;
  std::string kind;  // changed, failure_inserted, failure_cleared
  std::string name;  // the system or the failure
  std::string from;
  std::string to;
};

// One procedure of the lesson, as its last cockpit/procedure_score had it.
struct SeenProcedure {
  struct Step {
    std::string item, action, status;  // status: pending | done | missed
    bool out_of_order = false, late = false, undone = false;
    double done_s = -1, since_previous_s = -1;  // -1: not done
  };
  std::string lesson, name, title, state;  // state: waiting | running | complete | incomplete
  double started_s = -1, ended_s = -1;
  uint32_t errors = 0;
  std::vector<Step> steps;
};

class RigMonitor {
 public:
  explicit RigMonitor(DdsParticipant& participant);

  void poll();  // takes everything pending
  std::string status_line(double elapsed_s) const;

  const std::map<std::string, cockpit::NodeStatus>& statuses() const { return statuses_; }
  const std::vector<SeenEvent>& events() const { return events_; }
  // Named when read, not when taken: a control's state or event can come before its
  // cockpit/control_info (the topics are independent), and named then, it stayed "control 9"
  // beside the "nav_mode" of later samples. A control whose info never came keeps its number.
  std::vector<SeenControlEvent> control_events() const;
  // each control's last position name (cockpit/control_state), by control name
  std::map<std::string, std::string> control_positions() const;
  const std::vector<SeenSystemsEvent>& systems_events() const { return systems_events_; }
  // the lesson's procedures in order (cockpit/procedure_score); empty without a lesson
  std::vector<SeenProcedure> procedures() const;
  // each system's last value as words (a machine's state name), by name (systems_state with
  // systems_info); empty without a systems node
  std::map<std::string, std::string> systems_values() const;
  // Histograms (fixed memory, however long the rig runs: an hour at 90 frames a second kept as a
  // list grew the launcher by megabytes and sorted it four times a second for the status line)
  const LatencyHistogram& latency() const { return latency_; }
  // for the same frames: the sample's age at render start, and the render time
  const LatencyHistogram& age_at_render() const { return age_at_render_; }
  const LatencyHistogram& render() const { return render_; }
  uint64_t frames_seen() const { return frames_seen_; }
  // mean physics step rate over the statuses while the glove was alive, and the last late count
  double mean_step_rate_hz() const;
  uint64_t late_steps() const;
  // Whether the physics node has taken every sample the named input nodes published, by the last
  // statuses seen: each of them has reported STOPPING (its own status, or each of its
  // "<name>/..." ones: openxr_hand_bridge's hands), and the physics node's accepted and rejected
  // samples add up to what they published. False while any of those is unknown.
  bool input_consumed(const std::vector<std::string>& input_nodes) const;
  // Whether a node_status name is the node's: its own, or one of its "<node>/..." (a node that
  // reports each of its inputs, openxr_hand_bridge/right and /left).
  static bool is_status_of(const std::string& status_name, const std::string& node_name) {
    return status_name == node_name || status_name.rfind(node_name + "/", 0) == 0;
  }
  std::string object_name(uint32_t id) const;
  // the last state of every dynamic object, by name
  const std::map<std::string, cockpit::ObjectState>& final_states() const { return final_; }

 private:
  Reader<cockpit::NodeStatus> status_reader_;
  Reader<cockpit::GraspEvent> event_reader_;
  Reader<cockpit::FrameInfo> frame_reader_;
  Reader<cockpit::ObjectInfo> info_reader_;
  Reader<cockpit::ObjectState> state_reader_;
  Reader<cockpit::ControlInfo> control_info_reader_;
  Reader<cockpit::ControlState> control_state_reader_;
  Reader<cockpit::ControlEvent> control_event_reader_;
  Reader<cockpit::SystemsInfo> systems_info_reader_;
  Reader<cockpit::SystemsState> systems_state_reader_;
  Reader<cockpit::SystemsEvent> systems_event_reader_;
  Reader<cockpit::ProcedureScore> score_reader_;
  std::map<uint32_t, SeenProcedure> procedures_;
  uint32_t procedure_count_ = 0;
  std::vector<SeenSystemsEvent> systems_events_;
  struct SystemNames {
    std::string name;
    std::vector<std::string> states;  // a machine's
  };
  std::vector<SystemNames> systems_;
  std::vector<double> systems_values_;
  struct ControlNames {
    std::string name;
    std::vector<std::string> positions;
  };
  std::map<uint32_t, ControlNames> controls_;
  std::string control_name(uint32_t control) const;
  std::string position_name(uint32_t control, uint32_t position) const;
  struct RawControlEvent {  // as taken: ids and position indices
    double t_s = 0;
    uint32_t control = 0;
    uint32_t from = 0;
    uint32_t to = 0;
    std::string cause;
    std::string link;
  };
  std::vector<RawControlEvent> control_events_;
  std::map<uint32_t, uint32_t> control_positions_;  // control id -> its last position index
  std::map<uint32_t, bool> dynamic_;
  std::map<std::string, cockpit::ObjectState> final_;
  std::map<std::string, cockpit::NodeStatus> statuses_;
  uint64_t step_rates_ = 0;       // physics statuses while the glove was alive
  double step_rates_sum_hz_ = 0;  // of them but the first (a partial second)
  double first_step_rate_hz_ = 0;
  std::map<uint32_t, std::string> names_;
  std::vector<SeenEvent> events_;
  // 50 us bins up to 20 s (800 KB each): a sanitized rig's seconds of latency still fit
  static constexpr int64_t kBin_ns = 50'000;
  static constexpr int64_t kRange_ns = 20'000'000'000;
  LatencyHistogram latency_{kBin_ns, kRange_ns};
  LatencyHistogram age_at_render_{kBin_ns, kRange_ns};
  LatencyHistogram render_{kBin_ns, kRange_ns};
  int64_t last_source_stamp_ns_ = 0;
  uint64_t frames_seen_ = 0;
  std::string held_;
};


}  // namespace vcockpit::rig
