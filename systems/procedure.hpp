#pragma once
// Procedures a trainee flies with their hands (checklists and flows), and how a run scores them
// (procedure_runner.hpp). A procedure is an ordered list of steps; a step is a condition on the
// controls and the systems (the aircraft's expression language, system_model.hpp), e.g.
// "fuel_pump.on" or "gear_three_green". Steps follow in order, except those of an any-order group,
// which may be done in any order among themselves.
//
// A lesson is the procedures of one run, in order. A procedure starts when its starts_when holds
// (an abnormal: "gear_left.unsafe"); without one, the first starts with the run and each other
// when the one before it ends. It ends when every step is done (complete), when its time limit
// runs out, or with the run; a step not done by then is missed.

#include <string>
#include <vector>

#include "systems/system_model.hpp"

namespace vcockpit::systems {

struct ProcedureStep {
  std::string item;    // what is checked ("Fuel pump")
  std::string action;  // what it is set to ("ON")
  SourceExpression when;
  double within_s = -1.0;  // >= 0: late when done more than this after the previous step
  bool rises = false;      // done only when `when` becomes true after the procedure started
                           // (a condition already true then does not count: "recycle the gear")
  bool momentary = false;  // not expected to stay true: never "undone" (the start switch)
  int group = -1;          // >= 0: its any-order group (steps of one group are adjacent)
  Origin origin;
};

struct Procedure {
  std::string name;   // the file's stem ("before_start")
  std::string title;  // "Before start"
  SourceExpression starts_when;  // empty: see above
  double time_limit_s = -1.0;    // >= 0: ended (incomplete) this long after it started
  std::vector<ProcedureStep> steps;
  Origin origin;
};

struct Lesson {
  std::string source;  // the lesson file, for logs
  std::string title;
  std::vector<Procedure> procedures;
};

}  // namespace vcockpit::systems
