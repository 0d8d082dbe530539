#pragma once
// An aircraft's systems as data (docs/systems.md): failures the instructor inserts, and systems
// ("elements") evaluated in file order every step of a fixed rate. Each element has one value:
//   logic    an expression, every step
//   lag      a first-order lag toward an expression, time constant tau_s: the exact discrete
//            step v += (u - v) (1 - exp(-dt / tau)), so a step input reaches 1 - 1/e at tau
//   rate     moves toward an expression at most per_s a second (a motor)
//   timer    seconds its condition has held, 0 while it does not
//   latch    1 from a step where its input rises (grows) until its reset holds; set wins
//   machine  a state machine: its value is the state's index; transitions are tried in order,
//            the first whose `from` has the state, whose time in the state has reached after_s
//            and whose `when` holds is taken (one a step); it may clear failures
// An element reads the values of the elements above it as this step left them and those below
// it (and its own) as the last step did. Names of the expressions:
//   <element>                 its value
//   <machine>.<state>         1 while in that state;  <machine>.time_s: seconds in its state
//   <control>.<position>      1 while the control is in that position (the scene's names)
//   <control>.q               its coordinate (m; deg for a revolute joint)
//   <control>.position        its position's index
//   <failure>                 1 while inserted
//   time_s                    seconds since the systems started
// The model is pure data; bind_model (systems_engine.hpp) resolves it against the scene's controls.

#include <string>
#include <vector>

#include "systems/expression.hpp"

namespace vcockpit::systems {

// Where a part of the model came from, for errors: "file:line:col: key.path".
using Origin = std::string;

// A model error: "<origin>: <message>".
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An expression with the place it was written.
struct SourceExpression {
  Expression expression;
  Origin origin;
};

struct Failure {
  std::string name;
  std::string text;  // what the instructor sees ("Gear leg unsafe, left main")
  Origin origin;
};

struct Transition {
  std::vector<std::string> from;  // state names; empty: from any state
  std::string to;
  SourceExpression when;          // empty: always
  double after_s = 0.0;           // the time in the state it needs
  std::vector<std::string> clears;  // failures it clears (the crew's action fixed the fault)
  Origin origin;
};

enum class ElementKind { kLogic, kLag, kRate, kTimer, kLatch, kMachine };

struct Element {
  std::string name;
  ElementKind kind = ElementKind::kLogic;
  Origin origin;
  SourceExpression input;   // logic, lag, rate: the value or target; timer: while; latch: rises
  SourceExpression reset;   // latch
  double tau_s = 0.0;       // lag
  double per_s = 0.0;       // rate
  double initial = 0.0;     // lag, rate: the value at the start
  std::string unit;         // for displays and logs ("%", "degC"); "" none
  bool events = false;      // logic: an event on every change (machines and latches always)
  // machine
  std::vector<std::string> states;
  std::string initial_state;  // default the first
  std::vector<Transition> transitions;
};

struct SystemsModel {
  std::string source;  // the file, for logs
  double rate_hz = 100.0;
  Origin rate_origin;
  std::vector<Failure> failures;
  std::vector<Element> elements;
};

// A control of the scene as the systems see it: its name, whether its coordinate is an angle
// (its q is then in deg) and its position names in order.
struct ControlSpec {
  std::string name;
  bool revolute = false;
  std::vector<std::string> positions;
};

const char* element_kind_name(ElementKind kind);

}  // namespace vcockpit::systems
