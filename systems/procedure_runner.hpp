#pragma once
// Scores a lesson's procedures live, step by step of the aircraft's systems (the same frames, the
// same result offline and in a rig). After every systems step, for each procedure that runs:
//   - a step not yet done is done when its condition holds (for a `rises` step: becomes true);
//     it is recorded with its time and how long after the previous step done (or the start);
//     out of order when an earlier step, outside its any-order group, is not done yet; late
//     when it came more than within_s after the previous one;
//   - a step done whose condition stops holding while the procedure runs is undone (not a
//     momentary or rises step), once, with its time;
//   - the procedure is complete when every step is done, ended incomplete at its time limit.
// finish() ends what still runs: its steps not done are missed. A procedure that never started
// (an abnormal that did not happen) counts no errors. Errors of a procedure: steps out of order,
// late, undone and missed.

#include <cstdint>
#include <string>
#include <vector>

#include "systems/procedure.hpp"
#include "systems/systems_engine.hpp"

namespace vcockpit::systems {

enum class StepStatus : uint8_t { kPending, kDone, kMissed };
enum class ProcedureState : uint8_t { kWaiting, kRunning, kComplete, kIncomplete };

struct StepScore {
  StepStatus status = StepStatus::kPending;
  bool out_of_order = false;
  bool late = false;
  bool undone = false;
  int64_t done_ns = -1;
  int64_t since_previous_ns = -1;
  int64_t undone_ns = -1;
  bool held_at_start = false;  // its condition at the procedure's start (for the record)
  bool held_last = false;      // its condition at the last step (a rises step's edge)
};

struct ProcedureScore {
  ProcedureState state = ProcedureState::kWaiting;
  int64_t started_ns = -1;
  int64_t ended_ns = -1;
  int64_t last_done_ns = -1;  // the latest step done (the next one's "previous")
  std::vector<StepScore> steps;
  int errors() const;
};

// A change of the score, for logs and topics.
struct ScoreEvent {
  int64_t time_ns = 0;
  int procedure = 0;
  int step = -1;       // -1: the procedure itself (started, complete, incomplete)
  std::string what;    // started | complete | incomplete | done | missed | undone
};

const char* state_name(ProcedureState s);
const char* status_name(StepStatus s);

class ProcedureRunner {
 public:
  // Binds every condition through `systems` (throws ModelError naming the file and line).
  ProcedureRunner(Lesson lesson, const Systems& systems);

  const Lesson& lesson() const { return lesson_; }
  // Fingerprint of the lesson's procedures and steps (a checkpoint of another lesson is refused).
  uint64_t lesson_hash() const { return lesson_hash_; }
  const std::vector<ProcedureScore>& scores() const { return scores_; }

  // After a systems step: the score as that step leaves it; changes appended to `events`.
  void after_step(const Systems& systems, std::vector<ScoreEvent>& events);
  // The run is over: what runs ends, and its steps not done are missed.
  void finish(int64_t time_ns, std::vector<ScoreEvent>& events);
  // Scoring again from nothing (an instructor's reset): every procedure waits again.
  void reset();

  // Saved and restored with the systems (checkpoints).
  void restore(const std::vector<ProcedureScore>& scores);

 private:
  void start(std::size_t p, const Systems& systems, int64_t t, std::vector<ScoreEvent>& events);
  void score_steps(std::size_t p, const Systems& systems, int64_t t, std::vector<ScoreEvent>& events);
  void end(std::size_t p, ProcedureState state, int64_t t, std::vector<ScoreEvent>& events);

  Lesson lesson_;
  uint64_t lesson_hash_ = 0;
  std::vector<ProcedureScore> scores_;
};

}  // namespace vcockpit::systems
