#pragma once
// The aircraft's systems stepped at their fixed rate (system_model.hpp says what each element
// does). Deterministic: the same frames and failures give the same values and events, bit for
// bit; no clock, no randomness. The state is plain data, saved and restored whole (checkpoints).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "systems/system_model.hpp"

namespace vcockpit::systems {

// The controls at one instant of the physics' time: per control of the engine's ControlSpec
// list, its position index and its coordinate in SI units (m, or rad for a revolute joint, as
// cockpit/control_state has it; expressions read a revolute one's in deg).
struct ControlFrame {
  int64_t time_ns = 0;
  std::vector<int32_t> position;
  std::vector<double> q;
};

enum class SystemsEventKind : uint8_t { kChange, kFailureInserted, kFailureCleared };

// A discrete change: a machine's state, a latch, a logic element with events: true (kChange:
// `index` the element, from and to its values); a failure inserted or cleared (`index` the
// failure; cleared by a transition or by the instructor).
struct SystemsEvent {
  int64_t time_ns = 0;
  SystemsEventKind kind = SystemsEventKind::kChange;
  int index = 0;
  double from = 0.0;
  double to = 0.0;
};

struct SystemsState {
  int64_t step = 0;      // steps taken; 0: the initial values
  int64_t time_ns = 0;   // the last step's frame time
  std::vector<double> value;        // per element
  std::vector<int64_t> since_step;  // machine: the step it entered its state; timer: the step
                                    // its condition began to hold (-1: not holding)
  std::vector<double> last_input;   // latch: its input at the last step
  std::vector<uint8_t> failure;     // per failure: 1 inserted
};

class Systems {
 public:
  // Binds the model to the scene's controls; throws ModelError naming the place in the file.
  Systems(SystemsModel model, std::vector<ControlSpec> controls);

  const SystemsModel& model() const { return model_; }
  const std::vector<ControlSpec>& controls() const { return controls_; }
  int64_t period_ns() const { return period_ns_; }
  double period_s() const { return period_s_; }

  // One step, at the frame's time, with the controls as the frame has them (one entry per
  // control; a frame of another size throws std::invalid_argument). Appends its events.
  void step(const ControlFrame& frame, std::vector<SystemsEvent>& events);

  // Inserts or clears a failure now (for the next step); its event, stamped `time_ns` (default:
  // the last step's time), or nothing when it already was so.
  std::optional<SystemsEvent> set_failure(int failure, bool inserted, int64_t time_ns = -1);

  int element_index(const std::string& name) const;  // -1 when none
  int failure_index(const std::string& name) const;  // -1 when none
  double value(int element) const { return state_.value[static_cast<std::size_t>(element)]; }
  // A value as words: a machine's state name; a number otherwise ("%.6g").
  std::string value_text(int element, double value) const;

  const SystemsState& state() const { return state_; }
  // The controls the last step took (all in their first position before any step).
  const ControlFrame& frame() const { return frame_; }

  // Other expressions on the same names (a procedure's steps): resolved as the model's are,
  // throwing ModelError at the expression's origin; evaluated on the state the last step left.
  void bind_expression(SourceExpression& e) const;
  double evaluate(const Expression& e) const;
  // Puts back a saved state (std::invalid_argument if it does not fit this model).
  void restore(const SystemsState& saved);
  // An instructor's reset to the start: every system as it starts, no failure inserted; the step
  // count and time go on (machines enter their initial states now). The changes that reports
  // (machines, latches, logic with events, failures cleared) are appended to `events`.
  void reset_to_start(std::vector<SystemsEvent>& events);
  // Fingerprint of the model and the control list (a checkpoint of another model is refused).
  uint64_t model_hash() const { return model_hash_; }

 private:
  class Reader;
  void bind();
  void step_element(std::size_t e, const class Reader& reader, std::vector<SystemsEvent>& events);

  SystemsModel model_;
  std::vector<ControlSpec> controls_;
  int64_t period_ns_ = 0;
  double period_s_ = 0.0;
  uint64_t model_hash_ = 0;
  // per element: lag factor 1 - exp(-dt/tau); machine: per transition, bound
  struct BoundTransition {
    std::vector<uint8_t> from;  // per state: 1 if it starts here (all when `from` is empty)
    int to = 0;
    int64_t after_steps = 0;
    std::vector<int> clears;
  };
  std::vector<double> lag_factor_;
  std::vector<std::vector<BoundTransition>> transitions_;
  SystemsState state_;
  SystemsState initial_;  // as bound, before any step
  Ref resolve(const Name& name) const;
  ControlFrame frame_;                   // the last step's
  std::vector<int> cleared_;             // during a step: failures a transition cleared
};

}  // namespace vcockpit::systems
