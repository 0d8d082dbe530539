#pragma once
// What a systems run writes (systems_node --out, offline or on DDS, byte for byte the same for the
// same frames and failures); each file appears whole on commit() (AtomicFile):
//   systems_events.jsonl  one JSON object a line: t_ns, t_s, event (change | failure_inserted |
//                         failure_cleared), system or failure, from and to (a machine's state
//                         names, else numbers)
//   systems.csv           t_ns and every system's value ("%.9g") after each step
// The summary (systems_summary.json) is the caller's: it knows the run's counts.

#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "systems/systems_engine.hpp"

namespace vcockpit::systems {

// One event as words: its JSON line without the newline.
std::string event_json(const Systems& systems, const SystemsEvent& event);

class SystemsRecorder {
 public:
  SystemsRecorder(const std::string& out_dir, const Systems& systems);
  void after_step(const Systems& systems);             // a systems.csv row
  void write(const Systems& systems, const SystemsEvent& event);  // a systems_events.jsonl line
  void commit();
  uint64_t events() const { return events_written_; }

 private:
  AtomicFile events_;
  AtomicFile values_;
  uint64_t events_written_ = 0;
};

}  // namespace vcockpit::systems
