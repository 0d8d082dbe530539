// The aircraft systems (systems/): the expression language, the model's errors, and the default
// aircraft (config/aircraft.yaml on config/cockpit.yaml's controls) against closed forms: the
// gear's transit, the lags' time constants, the start sequence, within one systems step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>

#include "common/config_error.hpp"
#include "common/yaml_config.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/offline_runner.hpp"
#include "systems/config/procedure_yaml.hpp"
#include "systems/config/systems_yaml.hpp"
#include "systems/procedure_runner.hpp"
#include "systems/control_frames_file.hpp"
#include "systems/systems_checkpoint.hpp"
#include "systems/systems_run.hpp"
#include "systems/systems_session.hpp"
#include "systems/systems_engine.hpp"

namespace vcockpit::systems {
namespace {

std::string source_dir() {
  const char* dir = std::getenv("VCOCKPIT_SOURCE_DIR");
  return dir != nullptr ? dir : ".";
}

// ---- expressions -------------------------------------------------------------------------------

class MapReader final : public RefReader {
 public:
  double read(const Ref& ref) const override { return values.at(ref.index); }
  std::map<int, double> values;
};

double eval(const std::string& text, std::map<std::string, double> vars = {}) {
  Expression e = Expression::parse(text);
  MapReader reader;
  std::map<std::string, int> index;
  e.bind([&](const Name& n) {
    const std::string key = n.member.empty() ? n.name : n.name + "." + n.member;
    if (!vars.count(key)) throw ExpressionError(n.column, "no '" + key + "'");
    const int i = index.emplace(key, static_cast<int>(index.size())).first->second;
    reader.values[i] = vars[key];
    return Ref{RefKind::kElement, i, 0};
  });
  return e.evaluate(reader);
}

TEST(SystemsExpression, PrecedenceAndFunctions) {
  EXPECT_EQ(eval("1 + 2 * 3"), 7.0);
  EXPECT_EQ(eval("(1 + 2) * 3"), 9.0);
  EXPECT_EQ(eval("10 - 4 - 3"), 3.0);  // left to right
  EXPECT_EQ(eval("-2 * -3"), 6.0);
  EXPECT_EQ(eval("1 < 2 && 3 >= 3"), 1.0);
  EXPECT_EQ(eval("0 || 0"), 0.0);
  EXPECT_EQ(eval("!0 && !(2 == 3)"), 1.0);
  EXPECT_EQ(eval("1 != 1"), 0.0);
  EXPECT_EQ(eval("0 ? 5 : 1 ? 6 : 7"), 6.0);  // right-associative select
  EXPECT_EQ(eval("true ? 2 : 3"), 2.0);
  EXPECT_EQ(eval("clamp(12, 0, 10) + min(3, 4) + max(3, 4) + abs(-1)"), 18.0);
  EXPECT_EQ(eval("round(2.5) + floor(-0.5)"), 2.0);
  EXPECT_EQ(eval("mod(-10, 360)"), 350.0);
  EXPECT_EQ(eval("a.q * 2 + b", {{"a.q", 1.5}, {"b", 1.0}}), 4.0);
  EXPECT_EQ(eval("1e3 / 4"), 250.0);
}

TEST(SystemsExpression, DivisionByZeroIsZeroNotNaN) {
  EXPECT_EQ(eval("1 / 0"), 0.0);
  EXPECT_EQ(eval("mod(5, 0)"), 0.0);
  EXPECT_EQ(eval("1e300 * 1e300"), 0.0);  // an overflow is not published either
}

TEST(SystemsExpression, SyntaxErrorsNameTheCharacter) {
  const auto error = [](const std::string& text) {
    try {
      Expression::parse(text);
    } catch (const ExpressionError& e) {
      return std::string(e.what());
    }
    return std::string("parsed");
  };
  EXPECT_EQ(error("1 +"), "at character 4: expected a value");
  EXPECT_EQ(error("a && (b"), "at character 8: expected ')'");
  EXPECT_EQ(error("a b"), "at character 3: unexpected 'b'");
  EXPECT_EQ(error("1 < 2 < 3"), "at character 7: comparisons do not chain: use && between them");
  EXPECT_EQ(error("sqrt(2)"), "at character 1: no function 'sqrt' (min, max, clamp, abs, round, floor, mod)");
  EXPECT_EQ(error("min(1)"), "at character 6: expected ','");
  EXPECT_EQ(error("a = b"), "at character 3: unexpected '='");
  EXPECT_EQ(error(""), "at character 1: empty expression");
  EXPECT_EQ(error("gear."), "at character 6: expected a name after '.'");
  EXPECT_EQ(error("2x"), "at character 2: bad number");
}

// ---- the model's errors ------------------------------------------------------------------------

std::vector<ControlSpec> two_controls() {
  return {{"gear", false, {"down", "up"}}, {"throttle", true, {"cutoff", "idle", "full"}}};
}

std::string load_error(const std::string& yaml, std::vector<ControlSpec> controls = two_controls()) {
  try {
    Systems s(parse_systems_model(ConfigNode::load_string(yaml, "aircraft.yaml")), std::move(controls));
  } catch (const ConfigError& e) {
    return e.what();
  } catch (const ModelError& e) {
    return e.what();
  }
  return "loaded";
}

TEST(SystemsModelErrors, NameFileLineAndWhat) {
  EXPECT_EQ(load_error("systems:\n  - {name: a, logic: \"gear.down &&\"}\n"),
            "aircraft.yaml:2:22: systems[0].logic: at character 13: expected a value in \"gear.down &&\"");
  EXPECT_EQ(load_error("systems:\n  - {name: a, logic: \"gear.dwn\"}\n"),
            "aircraft.yaml:2:22: systems[0].logic: at character 1: control 'gear' has no position "
            "'dwn' (positions: down, up; or q, position) in \"gear.dwn\"");
  EXPECT_EQ(load_error("systems:\n  - {name: a, logic: \"flaps.up\"}\n"),
            "aircraft.yaml:2:22: systems[0].logic: at character 1: no control, failure or system "
            "named 'flaps' in \"flaps.up\"");
  EXPECT_EQ(load_error("systems:\n  - {name: a, lag: {to: 1, tau_s: 0}}\n"),
            "aircraft.yaml:2:35: systems[0].lag.tau_s: must be positive, got 0.000000");
  EXPECT_EQ(load_error("systems:\n  - {name: a, logic: 1, lag: {to: 1, tau_s: 1}}\n"),
            "aircraft.yaml:2:5: systems[0]: a system has one kind: logic, lag, rate, timer, latch or machine");
  EXPECT_EQ(load_error("systems:\n  - {name: gear, logic: 1}\n"),
            "aircraft.yaml:2:5: systems[0]: the name 'gear' is already taken (by a control, failure or system)");
  EXPECT_EQ(load_error("systems:\n  - {name: a, logic: 1, colour: red}\n"),
            "aircraft.yaml:2:25: systems[0].colour: unknown key 'colour' (allowed: name, logic, lag, "
            "rate, timer, latch, machine, unit, events)");
  EXPECT_EQ(load_error("systems:\n  - name: m\n    machine:\n      states: [a, b]\n"
                       "      transitions: [{from: a, to: c}]\n"),
            "aircraft.yaml:5:21: systems[0].machine.transitions[0]: no state 'c' (states: a, b)");
  EXPECT_EQ(load_error("systems:\n  - name: m\n    machine:\n      states: [a, b]\n"
                       "      transitions: [{from: a, to: b, clears: [fire]}]\n"),
            "aircraft.yaml:5:21: systems[0].machine.transitions[0]: no failure 'fire' to clear");
  EXPECT_EQ(load_error("systems:\n  - {name: a, logic: \"b.x\"}\n  - {name: b, lag: {to: 1, tau_s: 1}}\n"),
            "aircraft.yaml:2:22: systems[0].logic: at character 1: 'b' is a lag: it has no .x in \"b.x\"");
  EXPECT_EQ(load_error("rate_hz: 3\nsystems:\n  - {name: a, logic: 1}\n"),
            "aircraft.yaml:1:10: rate_hz: rate_hz must give a whole number of nanoseconds a step");
}

// ---- the default aircraft on the default cockpit -------------------------------------------------

class DefaultAircraft : public ::testing::Test {
 protected:
  void SetUp() override {
    const physics::Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
    std::vector<ControlSpec> controls;
    for (const physics::ControlSpec& c : scene.controls) {
      ControlSpec spec{c.name, c.joint == physics::JointKind::kRevolute, {}};
      for (const physics::ControlPosition& p : c.positions) spec.positions.push_back(p.name);
      controls.push_back(spec);
      frame_.position.push_back(0);
      frame_.q.push_back(c.q_initial);
      for (std::size_t i = 0; i < c.positions.size(); ++i)
        if (c.q_initial >= c.positions[i].enter_lo && c.q_initial <= c.positions[i].enter_hi)
          frame_.position.back() = static_cast<int32_t>(i);
      positions_[c.name] = spec.positions;
      at_[c.name] = {};
      for (const physics::ControlPosition& p : c.positions)
        at_[c.name][p.name] = p.q;
    }
    controls_ = controls;
    systems_ = std::make_unique<Systems>(load_systems_model(source_dir() + "/config/aircraft.yaml"),
                                         controls);
  }

  int control(const std::string& name) const {
    for (std::size_t i = 0; i < controls_.size(); ++i)
      if (controls_[i].name == name) return static_cast<int>(i);
    ADD_FAILURE() << "no control " << name;
    return 0;
  }
  // Puts a control in a named position, at its nominal coordinate.
  void set(const std::string& name, const std::string& position) {
    const int c = control(name);
    const auto& names = positions_.at(name);
    const auto it = std::find(names.begin(), names.end(), position);
    ASSERT_NE(it, names.end()) << name << " has no " << position;
    frame_.position[static_cast<std::size_t>(c)] = static_cast<int32_t>(it - names.begin());
    frame_.q[static_cast<std::size_t>(c)] = at_.at(name).at(position);
  }
  double value(const std::string& name) const {
    const int e = systems_->element_index(name);
    EXPECT_GE(e, 0) << name;
    return systems_->value(e);
  }
  std::string text(const std::string& name) const {
    const int e = systems_->element_index(name);
    return systems_->value_text(e, systems_->value(e));
  }
  void step(int n = 1) {
    for (int i = 0; i < n; ++i) {
      frame_.time_ns += systems_->period_ns();
      systems_->step(frame_, events_);
    }
  }
  // Steps until `name` reads `state` (at most `limit` steps); the steps taken, or -1.
  int steps_until(const std::string& name, const std::string& state, int limit) {
    for (int i = 1; i <= limit; ++i) {
      step();
      if (text(name) == state) return i;
    }
    return -1;
  }
  // The engine started and running, from a powered cockpit with the pump on and the throttle at
  // idle; the steps from the start switch to cranking.
  void power_up() {
    set("avionics_master", "on");
    set("fuel_pump", "on");
    set("throttle", "idle");
    step();
  }

  std::vector<ControlSpec> controls_;
  std::map<std::string, std::vector<std::string>> positions_;
  std::map<std::string, std::map<std::string, double>> at_;
  ControlFrame frame_;
  std::unique_ptr<Systems> systems_;
  std::vector<SystemsEvent> events_;
};

TEST_F(DefaultAircraft, StartsAsTheCockpitIs) {
  EXPECT_EQ(systems_->period_ns(), 10'000'000);
  step();
  EXPECT_EQ(text("engine"), "stopped");
  EXPECT_EQ(value("bus"), 0.0);  // the avionics master starts off
  EXPECT_EQ(text("gear_left"), "down");
  EXPECT_EQ(value("gear_three_green"), 1.0);
  EXPECT_EQ(value("gear_green_left"), 0.0);  // no power, no lights
  EXPECT_EQ(value("egt"), 15.0);
}

TEST_F(DefaultAircraft, GearTransitTimesPerLeg) {
  set("avionics_master", "on");
  step();
  set("gear", "up");
  step();  // the lever's step: every leg starts retracting
  EXPECT_EQ(text("gear_nose"), "retracting");
  EXPECT_EQ(value("gear_red_left"), 1.0);
  EXPECT_EQ(value("gear_three_green"), 0.0);
  // 6.5, 7 and 7.5 s at 100 Hz, exactly
  EXPECT_EQ(steps_until("gear_nose", "up", 2000), 650);
  EXPECT_EQ(steps_until("gear_left", "up", 2000), 50);
  EXPECT_EQ(steps_until("gear_right", "up", 2000), 50);
  EXPECT_EQ(value("gear_red_right"), 0.0);
  set("gear", "down");
  step();
  EXPECT_EQ(text("gear_right"), "extending");
  EXPECT_EQ(steps_until("gear_three_green", "1", 2000), 750);
  EXPECT_EQ(value("gear_green_nose") + value("gear_green_left") + value("gear_green_right"), 3.0);
}

TEST_F(DefaultAircraft, GearDoesNotMoveWithoutPower) {
  set("gear", "up");
  step(100);
  EXPECT_EQ(text("gear_nose"), "down");
  set("avionics_master", "on");
  step();
  EXPECT_EQ(text("gear_nose"), "retracting");
}

TEST_F(DefaultAircraft, StartSequenceTimingAndLags) {
  power_up();
  set("engine_start_guard", "open");
  set("engine_start", "start");
  step();
  EXPECT_EQ(text("engine"), "cranking");
  set("engine_start", "off");  // momentary: the start runs on by itself
  // light-off 2 s after cranking began
  EXPECT_EQ(steps_until("engine", "light_off", 1000), 200);
  // 2 s of the starter's 22 % (the exact discrete lag: e^(-t/tau) at every step), then the
  // light-off step's first step toward idle's 60 %
  const double a = 1.0 - std::exp(-0.01 / 1.2);
  const double rpm_cranked = 22.0 * (1.0 - std::exp(-2.0 / 1.2));
  EXPECT_NEAR(value("rpm"), rpm_cranked + (60.0 - rpm_cranked) * a, 1e-9);
  // running when rpm reaches 58 of its 60 %: t = tau ln((60 - r0) / (60 - 58)) after light-off;
  // the machine reads rpm as the last step left it (it is above rpm in the file)
  const double t_s = 1.2 * std::log((60.0 - rpm_cranked) / 2.0);
  const int steps = steps_until("engine", "running", 2000);
  EXPECT_GE(steps, static_cast<int>(std::floor(t_s * 100.0)));
  EXPECT_LE(steps, static_cast<int>(std::ceil(t_s * 100.0)) + 1);
}

TEST_F(DefaultAircraft, LagTimeConstantIsExact) {
  power_up();
  set("engine_start", "start");
  step();
  set("engine_start", "off");
  ASSERT_EQ(steps_until("engine", "light_off", 1000), 200);
  // from light-off EGT heads for 420 C (throttle at idle) from where cranking left it (15 C)
  const double egt0 = value("egt");
  EXPECT_NEAR(egt0, 15.0 + (420.0 - 15.0) * (1.0 - std::exp(-0.01 / 2.5)), 1e-9);
  step(249);  // tau = 2.5 s after the light-off step
  EXPECT_NEAR(value("egt"), 420.0 - (420.0 - 15.0) * std::exp(-1.0), 1e-9);
  // throttle to full: RPM heads for 100 % with its 1.2 s constant
  ASSERT_EQ(steps_until("engine", "running", 1000) > 0, true);
  step(1000);  // settled at idle
  EXPECT_NEAR(value("rpm"), 60.0, 1e-3);
  set("throttle", "full");
  const double r0 = value("rpm");
  step(120);
  EXPECT_NEAR(value("rpm"), 100.0 - (100.0 - r0) * std::exp(-1.0), 1e-9);
  EXPECT_NEAR(value("fuel_flow"), 60.0, 60.0 * std::exp(-1.2 / 0.5) + 1e-9);
}

TEST_F(DefaultAircraft, WrongConditionsFailTheStart) {
  set("avionics_master", "on");
  set("throttle", "idle");  // the fuel pump stays off
  step();
  set("engine_start", "start");
  step();
  set("engine_start", "off");
  EXPECT_EQ(steps_until("engine", "start_failed", 1000), 200);
  EXPECT_EQ(value("ann_start_failed"), 1.0);
  EXPECT_EQ(value("master_caution_light"), 1.0);
  // the master caution button puts the light out; the annunciator stays
  set("master_caution", "pressed");
  step();
  EXPECT_EQ(value("master_caution_light"), 0.0);
  EXPECT_EQ(value("ann_start_failed"), 1.0);
  set("master_caution", "out");
  step();
  EXPECT_EQ(value("master_caution_light"), 0.0);
  // the start switch released, the engine is stopped again after 5 s
  EXPECT_EQ(steps_until("engine", "stopped", 1000), 498);

  // with the throttle open instead, the start fails the same way
  set("fuel_pump", "on");
  set("throttle", "full");
  set("engine_start", "start");
  step();
  set("engine_start", "off");
  EXPECT_EQ(steps_until("engine", "start_failed", 1000), 200);
}

TEST_F(DefaultAircraft, GearUnsafeIsFixedByRecyclingTheGear) {
  set("avionics_master", "on");
  step();
  events_.clear();
  const int failure = systems_->failure_index("gear_unsafe_left");
  ASSERT_GE(failure, 0);
  ASSERT_TRUE(systems_->set_failure(failure, true).has_value());
  EXPECT_FALSE(systems_->set_failure(failure, true).has_value());  // already in
  step();
  EXPECT_EQ(text("gear_left"), "unsafe");
  EXPECT_EQ(value("gear_red_left"), 1.0);
  EXPECT_EQ(value("ann_gear_unsafe"), 1.0);
  EXPECT_EQ(value("master_caution_light"), 1.0);
  EXPECT_EQ(value("gear_three_green"), 0.0);
  // recycling: up clears the failure, and down locks all three again
  set("gear", "up");
  step();
  EXPECT_EQ(text("gear_left"), "retracting");
  EXPECT_EQ(systems_->state().failure[static_cast<std::size_t>(failure)], 0);
  bool cleared = false;
  for (const SystemsEvent& e : events_)
    cleared |= e.kind == SystemsEventKind::kFailureCleared && e.index == failure;
  EXPECT_TRUE(cleared);
  ASSERT_GT(steps_until("gear_right", "up", 2000), 0);
  set("gear", "down");
  ASSERT_GT(steps_until("gear_three_green", "1", 2000), 0);
  EXPECT_EQ(text("gear_left"), "down");
  EXPECT_EQ(value("ann_gear_unsafe"), 0.0);
}

TEST_F(DefaultAircraft, GearHornAndFlapMotor) {
  set("avionics_master", "on");
  set("throttle", "idle");
  set("flaps", "landing");
  step();
  EXPECT_EQ(value("gear_horn"), 0.0);  // gear down and locked
  EXPECT_NEAR(value("flap_deg"), 0.04, 1e-12);
  step(499);
  EXPECT_NEAR(value("flap_deg"), 20.0, 1e-9);  // 4 deg/s
  step(500);
  EXPECT_NEAR(value("flap_deg"), 40.0, 1e-9);
  step(10);
  EXPECT_NEAR(value("flap_deg"), 40.0, 1e-12);
  set("gear", "up");
  step();
  EXPECT_EQ(value("gear_horn"), 1.0);
  set("throttle", "full");
  step();
  EXPECT_EQ(value("gear_horn"), 0.0);
}

TEST_F(DefaultAircraft, AResetToTheStartReportsWhatItChanged) {
  set("avionics_master", "on");
  set("engine_start", "start");
  step();
  ASSERT_TRUE(systems_->set_failure(systems_->failure_index("engine_fire"), true));
  step();
  events_.clear();
  systems_->reset_to_start(events_);
  EXPECT_EQ(text("engine"), "stopped");
  EXPECT_EQ(value("bus"), 0.0);
  EXPECT_EQ(systems_->state().failure[static_cast<std::size_t>(systems_->failure_index("engine_fire"))], 0);
  bool engine = false, fire = false, caution = false;
  for (const SystemsEvent& e : events_) {
    if (e.kind == SystemsEventKind::kChange && e.index == systems_->element_index("engine"))
      engine = systems_->value_text(e.index, e.from) == "cranking" && systems_->value_text(e.index, e.to) == "stopped";
    fire |= e.kind == SystemsEventKind::kFailureCleared && e.index == systems_->failure_index("engine_fire");
    caution |= e.kind == SystemsEventKind::kChange && e.index == systems_->element_index("master_caution_light");
    EXPECT_EQ(e.time_ns, systems_->state().time_ns);
  }
  EXPECT_TRUE(engine);
  EXPECT_TRUE(fire);
  EXPECT_TRUE(caution);
  const int64_t step_before = systems_->state().step;
  step();  // time goes on from where it was
  EXPECT_EQ(systems_->state().step, step_before + 1);
}

// A failure scheduled at a time and since cleared by the crew stays cleared after a resume.
TEST_F(DefaultAircraft, AResumedSessionDoesNotInsertPastScheduledFailuresAgain) {
  SessionOptions options;
  options.failures.push_back(parse_scheduled_failure("0.05:gear_unsafe_left"));
  const auto model = [&] { return load_systems_model(source_dir() + "/config/aircraft.yaml"); };
  SystemsSession first(model(), controls_, options);
  const int failure = first.systems().failure_index("gear_unsafe_left");
  set("avionics_master", "on");
  const auto fly = [&](SystemsSession& s, int steps) {
    for (int i = 0; i < steps; ++i) {
      frame_.time_ns += 10'000'000;
      s.take(frame_);
    }
  };
  fly(first, 10);
  ASSERT_EQ(first.systems().value_text(first.systems().element_index("gear_left"),
                                       first.systems().value(first.systems().element_index("gear_left"))),
            "unsafe");
  set("gear", "up");  // the recycle clears it
  fly(first, 10);
  ASSERT_EQ(first.systems().state().failure[static_cast<std::size_t>(failure)], 0);
  SystemsSession second(model(), controls_, options);
  second.restore(first.systems().state());
  set("gear", "down");
  fly(second, 800);
  EXPECT_EQ(second.systems().state().failure[static_cast<std::size_t>(failure)], 0);
  const int left = second.systems().element_index("gear_left");
  EXPECT_EQ(second.systems().value_text(left, second.systems().value(left)), "down");
}

TEST_F(DefaultAircraft, RestoredStateGoesOnIdentically) {
  power_up();
  set("engine_start", "start");
  set("gear", "up");
  step(150);
  const SystemsState saved = systems_->state();
  const ControlFrame frame_then = frame_;
  set("engine_start", "off");
  step(400);
  const std::vector<double> values_a = systems_->state().value;
  const std::size_t events_a = events_.size();

  Systems other(load_systems_model(source_dir() + "/config/aircraft.yaml"), controls_);
  other.restore(saved);
  EXPECT_EQ(other.model_hash(), systems_->model_hash());
  ControlFrame f = frame_then;
  f.position[static_cast<std::size_t>(control("engine_start"))] = 0;
  f.q[static_cast<std::size_t>(control("engine_start"))] = at_["engine_start"]["off"];
  std::vector<SystemsEvent> events_b;
  for (int i = 0; i < 400; ++i) {
    f.time_ns += other.period_ns();
    other.step(f, events_b);
  }
  EXPECT_EQ(other.state().value, values_a);  // bit for bit
  EXPECT_GT(events_b.size(), 0u);
  EXPECT_LE(events_b.size(), events_a);

  SystemsState bad = saved;
  bad.value.pop_back();
  EXPECT_THROW(other.restore(bad), std::invalid_argument);
}

// ---- procedures: the default lesson scored on synthetic frames ----------------------------------

class DefaultLesson : public DefaultAircraft {
 protected:
  void SetUp() override {
    DefaultAircraft::SetUp();
    runner_ = std::make_unique<ProcedureRunner>(load_lesson(source_dir() + "/config/lessons/default.yaml"),
                                                *systems_);
  }
  void fly(int steps = 1) {
    for (int i = 0; i < steps; ++i) {
      step();
      runner_->after_step(*systems_, score_events_);
    }
  }
  const ProcedureScore& score(const std::string& name) const {
    for (std::size_t p = 0; p < runner_->lesson().procedures.size(); ++p)
      if (runner_->lesson().procedures[p].name == name) return runner_->scores()[p];
    throw std::out_of_range(name);
  }
  // A pushed control: in position for `hold` steps, then back.
  void press(const std::string& control, const std::string& on, const std::string& off, int hold = 5) {
    set(control, on);
    fly(hold);
    set(control, off);
    fly();
  }
  // The flow done right up to the gear raised "after take-off".
  void start_engine_and_take_off() {
    fly();  // before start begins; its checks hold
    set("avionics_master", "on");
    fly(50);
    set("fuel_pump", "on");
    fly(50);
    set("engine_start_guard", "open");
    fly(20);
    press("engine_start", "start", "off", 30);
    fly(700);  // running after about 5.5 s
    set("engine_start_guard", "closed");
    fly(50);
    set("gear", "up");
    fly(800);  // the legs up
  }

  std::unique_ptr<ProcedureRunner> runner_;
  std::vector<ScoreEvent> score_events_;
};

TEST_F(DefaultLesson, TheFlowDoneRightScoresEveryProcedureComplete) {
  start_engine_and_take_off();
  set("gear", "down");
  fly(800);
  set("flaps", "landing");
  fly(50);
  set("landing_lights", "on");
  fly(50);
  runner_->finish(systems_->state().time_ns, score_events_);
  for (const char* name : {"before_start", "engine_start", "before_landing"}) {
    SCOPED_TRACE(name);
    EXPECT_EQ(score(name).state, ProcedureState::kComplete);
    EXPECT_EQ(score(name).errors(), 0);
  }
  EXPECT_EQ(score("gear_unsafe").state, ProcedureState::kWaiting);  // never happened: no error
  EXPECT_EQ(score("gear_unsafe").errors(), 0);
  // the checks that held at the start are done at its first step; then the avionics 50 steps on
  const ProcedureScore& before = score("before_start");
  EXPECT_EQ(before.started_ns, 10'000'000);
  EXPECT_EQ(before.steps[0].done_ns, 10'000'000);
  EXPECT_EQ(before.steps[4].done_ns, 20'000'000);  // avionics master, set before the 2nd step
  EXPECT_EQ(before.steps[4].since_previous_ns, 10'000'000);
  // three green 7.5 s after the lever went down (the right leg's transit), within its 10 s
  const ProcedureScore& landing = score("before_landing");
  EXPECT_EQ(landing.steps[1].since_previous_ns, 7'500'000'000);
  EXPECT_FALSE(landing.steps[1].late);
}

TEST_F(DefaultLesson, OutOfOrderMissedAndUndoneStepsAreScoredAsSuch) {
  start_engine_and_take_off();
  set("flaps", "landing");  // before the gear: out of order
  fly(50);
  set("gear", "down");
  fly(800);
  set("fuel_pump", "off");  // before start is complete already: not its concern
  fly(10);
  runner_->finish(systems_->state().time_ns, score_events_);  // landing lights never on
  const ProcedureScore& landing = score("before_landing");
  EXPECT_EQ(landing.state, ProcedureState::kIncomplete);
  EXPECT_TRUE(landing.steps[2].out_of_order);       // flaps
  EXPECT_EQ(landing.steps[3].status, StepStatus::kMissed);  // landing lights
  EXPECT_EQ(landing.errors(), 2);
  EXPECT_EQ(score("before_start").errors(), 0);

  // undone: the avionics master switched off again before the procedure was complete
  runner_->reset();
  systems_ = std::make_unique<Systems>(load_systems_model(source_dir() + "/config/aircraft.yaml"), controls_);
  frame_.time_ns = 0;
  set("avionics_master", "off");
  set("fuel_pump", "off");
  set("gear", "down");
  set("flaps", "up");
  set("landing_lights", "off");
  fly();
  set("avionics_master", "on");
  fly(10);
  set("avionics_master", "off");
  fly(10);
  set("fuel_pump", "on");
  fly(10);
  const ProcedureScore& before = score("before_start");
  EXPECT_EQ(before.state, ProcedureState::kComplete);
  EXPECT_TRUE(before.steps[4].undone);
  EXPECT_EQ(before.steps[4].undone_ns, before.steps[4].done_ns + 100'000'000);
  EXPECT_EQ(before.errors(), 1);
}

TEST_F(DefaultLesson, GearUnsafeAbnormalStartsWithTheFailureAndIsScored) {
  start_engine_and_take_off();
  set("gear", "down");
  fly(800);
  ASSERT_TRUE(systems_->set_failure(systems_->failure_index("gear_unsafe_left"), true));
  fly(10);
  EXPECT_EQ(score("gear_unsafe").state, ProcedureState::kRunning);
  press("master_caution", "pressed", "out");
  fly(50);
  set("gear", "up");
  fly(800);
  set("gear", "down");
  fly(800);
  const ProcedureScore& abnormal = score("gear_unsafe");
  EXPECT_EQ(abnormal.state, ProcedureState::kComplete);
  EXPECT_EQ(abnormal.errors(), 0);
  EXPECT_EQ(abnormal.steps[3].since_previous_ns, 7'500'000'000);
}

// ---- frames, runs and checkpoints ---------------------------------------------------------------

std::string temp_path(const std::string& name) {
  const char* dir = std::getenv("VCOCKPIT_TEST_TMP");
  const std::string base = dir != nullptr && *dir != '\0' ? dir : "/tmp";
  return base + "/systems_test_" + name;
}

TEST(ControlFramesFile, WritesAndReadsTheSameBits) {
  const std::string path = temp_path("frames.csv");
  const std::vector<ControlSpec> controls = two_controls();
  {
    ControlFramesWriter w(path, controls);
    w.write({10'000'000, {0, 1}, {0.1, -0.3490658503988659}});
    w.write({20'000'000, {1, 2}, {1.0 / 3.0, 0.5235987755982988}});
    w.commit();
  }
  const ControlFrames read = read_control_frames(path);
  ASSERT_EQ(read.controls.size(), 2u);
  EXPECT_EQ(read.controls[1].name, "throttle");
  EXPECT_TRUE(read.controls[1].revolute);
  EXPECT_EQ(read.controls[1].positions, (std::vector<std::string>{"cutoff", "idle", "full"}));
  ASSERT_EQ(read.frames.size(), 2u);
  EXPECT_EQ(read.frames[1].time_ns, 20'000'000);
  EXPECT_EQ(read.frames[1].position, (std::vector<int32_t>{1, 2}));
  EXPECT_EQ(read.frames[1].q[0], 1.0 / 3.0);  // every bit
  EXPECT_EQ(read.frames[0].q[1], -0.3490658503988659);
}

TEST(ControlFramesFile, ErrorsNameTheLineAndField) {
  const auto error = [](const std::string& text) {
    const std::string path = temp_path("bad_frames.csv");
    std::ofstream(path) << text;
    try {
      read_control_frames(path);
    } catch (const ControlFramesError& e) {
      return std::string(e.what()).substr(path.size());
    }
    return std::string("read");
  };
  const std::string head = "# vcockpit control frames, version 1\n# control: gear prismatic down|up\n";
  EXPECT_EQ(error("t_ns\n"), ":1: not a control frames file (its first line must be \"# vcockpit control frames, version 1\")");
  EXPECT_EQ(error(head + "t_ns,gear.q\n"), ":3: header row: expected t_ns,gear.position,gear.q");
  EXPECT_EQ(error(head + "t_ns,gear.position,gear.q\n10,0,0\n10,0,0\n"), ":5: t_ns: 10 does not come after the last row's 10");
  EXPECT_EQ(error(head + "t_ns,gear.position,gear.q\n10,0,nan\n"), ":4: gear.q: 'nan' is not a finite number");
  EXPECT_EQ(error(head + "t_ns,gear.position,gear.q\n10,0\n"), ":4: 2 fields, expected 3");
  EXPECT_EQ(error("# vcockpit control frames, version 1\n# control: gear sliding down|up\n"), ":2: control gear: joint 'sliding' (prismatic or revolute)");
  EXPECT_EQ(error(head), ":2: no header row (t_ns,...)");
}

TEST(SystemsRunFrames, MissedStaleAndOffGridFramesAreCountedNotLost) {
  SystemsModel model = parse_systems_model(ConfigNode::load_string(
      "systems:\n  - {name: t, timer: \"gear.up\"}\n", "a.yaml"));
  Systems systems(std::move(model), two_controls());
  SystemsRun run(systems);
  int steps = 0;
  const auto count = [&](const Systems&, const std::vector<SystemsEvent>&) { ++steps; };
  ControlFrame f{10'000'000, {1, 0}, {0.04, 0.0}};
  EXPECT_EQ(run.take(f, {}, count), 1);
  f.time_ns = 50'000'000;  // three periods without a frame
  EXPECT_EQ(run.take(f, {}, count), 4);
  EXPECT_EQ(steps, 5);
  EXPECT_NEAR(systems.value(0), 0.04, 1e-12);  // the timer counted every period
  f.time_ns = 40'000'000;
  EXPECT_EQ(run.take(f, {}, count), 0);  // stale
  f.time_ns = 55'000'000;
  EXPECT_EQ(run.take(f, {}, count), 0);  // off the grid
  EXPECT_EQ(run.counts().taken, 2u);
  EXPECT_EQ(run.counts().missed, 3u);
  EXPECT_EQ(run.counts().stale, 1u);
  EXPECT_EQ(run.counts().off_grid, 1u);
}

TEST(SystemsCheckpoint, RoundTripsEveryBitAndRefusesAnotherModel) {
  const std::string aircraft = source_dir() + "/config/aircraft.yaml";
  const std::vector<ControlSpec> controls = {
      {"avionics_master", false, {"off", "on"}}, {"fuel_pump", true, {"off", "on"}},
      {"engine_start", true, {"off", "start"}}, {"throttle", true, {"cutoff", "idle", "full"}},
      {"gear", false, {"down", "up"}}, {"flaps", true, {"up", "approach", "landing"}},
      {"landing_lights", true, {"off", "taxi", "on"}}, {"nav_mode", true, {"off", "vor", "gps", "loc", "app"}},
      {"heading_bug", true, {"click", "between"}}, {"master_caution", false, {"out", "pressed"}}};
  Systems a(load_systems_model(aircraft), controls);
  ControlFrame f{0, {1, 1, 1, 1, 1, 2, 2, 1, 0, 0}, {0.004, 0.3, 0.3, -0.349, 0.04, 0.7, 0.3, 0.5, 1.3, 0}};
  std::vector<SystemsEvent> events;
  for (int i = 0; i < 333; ++i) {
    f.time_ns += a.period_ns();
    a.step(f, events);
  }
  ASSERT_TRUE(a.set_failure(a.failure_index("engine_fire"), true));
  const std::string path = temp_path("systems.ckpt");
  write_systems_checkpoint(path, a);
  Systems b(load_systems_model(aircraft), controls);
  b.restore(read_systems_checkpoint(path, b).state);
  EXPECT_EQ(b.state().value, a.state().value);
  EXPECT_EQ(b.state().since_step, a.state().since_step);
  EXPECT_EQ(b.state().failure, a.state().failure);
  EXPECT_EQ(b.state().time_ns, a.state().time_ns);

  std::vector<ControlSpec> other = controls;  // a scene with one more control
  other.push_back({"parking_brake", false, {"off", "set"}});
  Systems c(load_systems_model(aircraft), other);
  // ... and the same aircraft with one time constant edited
  SystemsModel edited = load_systems_model(aircraft);
  for (Element& e : edited.elements)
    if (e.name == "rpm") e.tau_s = 1.3;
  Systems d(std::move(edited), controls);
  for (const Systems* s : {&c, &d}) {
    try {
      read_systems_checkpoint(path, *s);
      ADD_FAILURE() << "another model's checkpoint was read";
    } catch (const CheckpointError& e) {
      EXPECT_NE(std::string(e.what()).find(":2: saved for another aircraft model or scene"), std::string::npos) << e.what();
    }
  }
}

// control_frames.csv follows the frame rate (100 Hz), not the trajectories' --output-hz.
TEST(ControlFramesFile, TheOfflineRunnerWritesFramesEveryTenMillisecondsWhateverTheOutputRate) {
  physics_io::OfflineOptions options;
  options.scene_path = source_dir() + "/config/cockpit.yaml";
  options.duration_s = 0.1;
  options.output_hz = 50.0;
  options.out_dir = temp_path("offline_50hz");
  physics_io::run_offline(load_scene(options.scene_path), options);
  const ControlFrames frames = read_control_frames(options.out_dir + "/control_frames.csv");
  ASSERT_EQ(frames.frames.size(), 10u);
  for (std::size_t i = 0; i < frames.frames.size(); ++i)
    EXPECT_EQ(frames.frames[i].time_ns, static_cast<int64_t>(i + 1) * 10'000'000);
  EXPECT_EQ(frames.controls.size(), 11u);
}

TEST(SystemsExpression, DeepNestingIsAnErrorNotACrash) {
  EXPECT_THROW(Expression::parse(std::string(5000, '(') + "1" + std::string(5000, ')')), ExpressionError);
  EXPECT_THROW(Expression::parse(std::string(5000, '!') + "1"), ExpressionError);
  EXPECT_NO_THROW(Expression::parse("((((1)))) + !!!!0"));
}

}  // namespace
}  // namespace vcockpit::systems
