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

#include <cstdint>
#include <stdexcept>
#include <string>

#include "systems/systems_engine.hpp"

namespace vcockpit::systems {

class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws FileError when it cannot be written.
void write_systems_checkpoint(const std::string& path, const Systems& systems);
// The saved state for `systems`' model; throws CheckpointError "path:line: ..." on a damaged file
// or another model's, FileError when unreadable.
SystemsState read_systems_checkpoint(const std::string& path, const Systems& systems);

}  // namespace vcockpit::systems
