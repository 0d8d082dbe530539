#pragma once
// What the instructor station knows of the rig, as the DDS side hears it and the web page reads
// it: every node's newest status, the world's sim time and whether it is frozen, the hands, the
// controls, the newest preview of the pilot's view, and a numbered log of grasp, control and
// sim events. Thread-safe: the DDS loop writes, the HTTP server's threads read (JSON).

#include <nlohmann/json.hpp>

#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "dds/dds_participant.hpp"
#include "idl/topics/systems_topics.hpp"

namespace vcockpit::instructor {

class StationModel {
 public:
  static constexpr std::size_t kMaxEvents = 1000;   // kept for late pages
  static constexpr std::size_t kEventsPerReply = 200;
  static constexpr int64_t kStaleAfter_ns = 3'000'000'000;  // a node silent longer: stale

  // DDS side (stamps: the station's monotonic clock when the sample was taken)
  void on_status(const cockpit::NodeStatus& status, int64_t now_ns);
  void on_hand(const cockpit::HandState& hand);
  void on_object_info(const cockpit::ObjectInfo& info);
  void on_object_state(const cockpit::ObjectState& state);
  void on_control_info(const cockpit::ControlInfo& info);
  void on_control_state(const cockpit::ControlState& state);
  void on_grasp_event(const cockpit::GraspEvent& event);
  void on_control_event(const cockpit::ControlEvent& event);
  void on_ack(const cockpit::SimAck& ack);
  void on_preview(const cockpit::PreviewFrame& frame, int64_t now_ns);
  // a command this station sent (logged as an event, so the page shows what was asked)
  void on_command_sent(const std::string& text);
  // the aircraft's systems (systems_node): names once, values every step, changes, failures
  // and the lesson's scores
  void on_systems_info(const cockpit::SystemsInfo& info);
  void on_systems_state(const cockpit::SystemsState& state);
  void on_systems_event(const cockpit::SystemsEvent& event);
  void on_failure_ack(const cockpit::FailureAck& ack);
  void on_procedure_score(const cockpit::ProcedureScore& score);

  // HTTP side
  nlohmann::json state_json(int64_t now_ns) const;
  // Events after seq `after` (-1: the newest kEventsPerReply), oldest first, and the next seq.
  nlohmann::json events_json(int64_t after) const;
  bool view_png(std::string& out) const;  // false: no preview yet
  // A control and position the rig has (for refusing bad commands before they go out).
  bool has_control_position(uint32_t control_id, uint32_t position) const;
  // Whether the systems node has said which failures it has, and whether it has this one.
  bool knows_failures() const;
  bool has_failure(const std::string& name) const;

 private:
  struct Node {
    cockpit::NodeStatus status;
    int64_t taken_ns = 0;
  };
  struct Control {
    std::string name;
    std::string kind;
    std::vector<std::string> positions;
    bool have_state = false;
    uint32_t position = 0;
    double coordinate = 0.0;
    bool lit = false;
    int32_t held_by = -1;
  };
  struct Hand {
    bool tracking = false;
    int32_t holding = -1;
  };
  struct System {
    std::string name;
    std::string unit;
    std::vector<std::string> states;  // a machine's
  };
  struct FailureEntry {
    std::string name;
    std::string text;
    bool inserted = false;
  };
  // What an event names by id, named when the event is read rather than when it arrives: the
  // topics are independent, and an event that comes before its object's or control's info
  // would keep a bare number for good.
  struct Naming {
    enum class Of : uint8_t { kNothing, kObject, kControl } of = Of::kNothing;
    uint32_t id = 0;
    uint32_t from = 0, to = 0;  // a control's positions
  };
  struct Event {
    int64_t seq = 0;
    std::string kind;  // grasp, release, control, sim, system, failure
    double sim_time_s = 0.0;
    std::string text;  // with a naming: what comes before the name ...
    std::string tail;  // ... and after it (and a control's positions)
    Naming naming;
  };

  void add_event(std::string kind, int64_t sim_time_ns, std::string text);  // mutex held
  void add_named_event(std::string kind, int64_t sim_time_ns, std::string text, Naming naming,
                       std::string tail);  // mutex held
  std::string event_text(const Event& e) const;                // mutex held
  std::string object_name(uint32_t id) const;                  // mutex held
  void note_sim_time(int64_t sim_time_ns);                                     // mutex held

  mutable std::mutex mutex_;
  std::map<std::string, Node> nodes_;
  std::map<uint32_t, std::string> object_names_;
  std::map<uint32_t, Control> controls_;
  std::map<uint32_t, Hand> hands_;
  bool have_sim_time_ = false;
  int64_t sim_time_ns_ = 0;
  bool frozen_ = false;
  std::vector<std::string> checkpoints_;
  nlohmann::json last_ack_;  // null until one
  std::vector<System> systems_;
  std::vector<double> system_values_;
  int64_t systems_time_ns_ = -1;
  std::vector<FailureEntry> failures_;
  bool failures_known_ = false;
  std::string lesson_;
  std::map<uint32_t, nlohmann::json> procedures_;  // by index, as the page shows them
  std::deque<Event> events_;
  int64_t next_event_seq_ = 0;
  // the newest preview
  std::string png_;
  uint64_t frame_seq_ = 0;
  int64_t frame_sim_time_ns_ = 0;
  uint32_t frame_width_px_ = 0;
  uint32_t frame_height_px_ = 0;
  int64_t frame_taken_ns_ = 0;
};

const char* sim_command_word(cockpit::SimCommandKind kind);  // freeze, reset_start, ...

}  // namespace vcockpit::instructor
