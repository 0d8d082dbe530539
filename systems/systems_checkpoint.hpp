#pragma once
// The systems' state in a file, to survive kill -9: written whole or not at all (AtomicFile),
// the model's fingerprint first so that another model's state is refused. Doubles are written
// as hexadecimal floats: a resumed run goes on with the very bits it stopped with.
//
//   # vcockpit systems checkpoint, version 1
//   model_hash <16 hex digits>
//   step <n>
//   time_ns <t>
//   value <%a> ...        one per system
//   since_step <n> ...    one per system
//   last_input <%a> ...   one per system
//   failure <0|1> ...     one per failure (the line is "failure" alone when there are none)
//   procedures <n> <h>    the lesson's scores (0 without a lesson) and its fingerprint, then per
//                         procedure
//   procedure <state> <started_ns> <ended_ns> <last_done_ns> <steps>, and per step
//   step <status> <out_of_order> <late> <undone> <done_ns> <since_previous_ns> <undone_ns>
//        <held_at_start> <held_last>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "systems/procedure_runner.hpp"
#include "systems/systems_engine.hpp"

namespace vcockpit::systems {

class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SystemsCheckpoint {
  SystemsState state;
  std::vector<ProcedureScore> scores;  // empty without a lesson
};

// The systems and, when there is a lesson, its scores. Throws FileError when it cannot be written.
void write_systems_checkpoint(const std::string& path, const Systems& systems,
                              const ProcedureRunner* procedures = nullptr);
// What was saved for `systems`' model (and `procedures`' lesson: the same procedures and steps);
// throws CheckpointError "path:line: ..." on a damaged file or another model's or lesson's,
// FileError when unreadable.
SystemsCheckpoint read_systems_checkpoint(const std::string& path, const Systems& systems,
                                          const ProcedureRunner* procedures = nullptr);

}  // namespace vcockpit::systems
