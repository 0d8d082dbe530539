#pragma once
// One run of the aircraft systems, whatever feeds it: the systems, their frame rule (SystemsRun),
// the failures scheduled at simulated times (--failure-at), and with an output folder the
// recorder's files and systems_summary.json. systems_node --offline feeds it control_frames.csv;
// on DDS it is fed cockpit/control_frame and publishes what it hands back, so both write the same
// files for the same frames.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "systems/procedure_runner.hpp"
#include "common/atomic_file.hpp"
#include "systems/systems_engine.hpp"
#include "systems/systems_recorder.hpp"
#include "systems/systems_run.hpp"

namespace vcockpit::systems {

// A failure inserted at a time of the simulation ("12.5:gear_unsafe_left").
struct ScheduledFailure {
  int64_t time_ns = 0;
  std::string failure;
};
// Parses "SECONDS:NAME"; throws std::invalid_argument naming the text.
ScheduledFailure parse_scheduled_failure(const std::string& text);

struct SessionOptions {
  std::string aircraft_path;  // for the summary
  std::string out_dir;        // empty: no files
  std::vector<ScheduledFailure> failures;
  std::optional<Lesson> lesson;  // procedures to score (procedure_runner.hpp)
};

// One step's outcome, for the DDS side: its systems events and the score's changes.
struct StepOutcome {
  std::vector<SystemsEvent> events;
  std::vector<ScoreEvent> score_events;
};

// The score as JSON text (procedures.json; the report reads it); one change of it as a JSON line.
std::string score_json_text(const ProcedureRunner& runner);
std::string score_event_json(const ProcedureRunner& runner, const ScoreEvent& event);

class SystemsSession {
 public:
  // Throws ModelError (binding) and std::invalid_argument (a scheduled failure of no name).
  SystemsSession(SystemsModel model, std::vector<ControlSpec> controls, SessionOptions options);

  Systems& systems() { return systems_; }
  const Systems& systems() const { return systems_; }
  using Sink = std::function<void(const Systems&, const StepOutcome&)>;
  // The steps for a frame; each step's events (scheduled failures first) and the score's
  // changes go to the files and to `sink`. Returns the steps taken.
  int take(const ControlFrame& frame, const Sink& sink = {});
  // An instructor's failure now: its event (recorded), or nothing when it already was so.
  std::optional<SystemsEvent> set_failure(int failure, bool inserted);
  // Continues from a saved state (after kill -9); the failures scheduled at or before its time
  // are not inserted again (a cleared one stays cleared).
  void restore(const SystemsState& state);
  // An instructor's reset to the start: the systems as they start (their changes recorded and
  // given to `sink`) and the scoring from nothing (a "reset" line in procedure_events.jsonl); the
  // time goes on.
  void reset_to_start(const Sink& sink = {});
  // The lesson's scoring; null without a lesson.
  ProcedureRunner* procedures() { return procedures_.get(); }
  const ProcedureRunner* procedures() const { return procedures_.get(); }

  const FrameCounts& counts() const { return run_.counts(); }
  bool run_started() const { return run_.started(); }
  uint64_t events() const { return events_; }
  // Ends the scoring (what runs is incomplete, its open steps missed: `sink` gets those changes),
  // then writes systems_summary.json and procedures.json and commits the files (with an output
  // folder).
  void finish(const Sink& sink = {});

 private:
  void record(const SystemsEvent& event);
  void record_scores();

  Systems systems_;
  SystemsRun run_;
  SessionOptions options_;
  std::vector<std::pair<int64_t, int>> schedule_;  // (time, failure), in time order
  std::size_t next_scheduled_ = 0;
  std::unique_ptr<SystemsRecorder> recorder_;
  uint64_t events_ = 0;
  std::unique_ptr<ProcedureRunner> procedures_;
  std::unique_ptr<AtomicFile> score_log_;  // procedure_events.jsonl
  StepOutcome outcome_;
};

}  // namespace vcockpit::systems
