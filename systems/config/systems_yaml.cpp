#include "systems/config/systems_yaml.hpp"

#include <array>
#include <cmath>
#include <cctype>
#include <set>

#include "common/yaml_config.hpp"

namespace vcockpit {
namespace {

using systems::ElementKind;

systems::Origin origin_of(const ConfigNode& node) {
  return node.file() + ":" + std::to_string(node.line()) + ":" + std::to_string(node.column()) +
         ": " + (node.key_path().empty() ? std::string("(top level)") : node.key_path());
}

// [A-Za-z_][A-Za-z0-9_]*, as the expressions' names are
bool is_name(const std::string& s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

std::string name_of(const ConfigNode& node) {
  const std::string name = node.as_string();
  if (!is_name(name))
    node.fail("'" + name + "' is not a name (letters, digits and _, not starting with a digit)");
  return name;
}

systems::SourceExpression expression_of(const ConfigNode& node) {
  std::string text;
  if (node.is_scalar()) text = node.as_string();
  else node.fail("expected an expression (a string)");
  try {
    return {systems::Expression::parse(text), origin_of(node)};
  } catch (const systems::ExpressionError& e) {
    node.fail(std::string(e.what()) + " in \"" + text + "\"");
  }
}

double positive(const ConfigNode& node, const char* key) {
  const ConfigNode v = node[key];
  const double x = v.as_double();
  if (!(x > 0.0)) v.fail("must be positive, got " + std::to_string(x));
  return x;
}

std::vector<std::string> names_of(const ConfigNode& node) {
  std::vector<std::string> out;
  if (node.is_scalar()) {
    out.push_back(name_of(node));
  } else {
    for (const ConfigNode& n : node.elements()) out.push_back(name_of(n));
  }
  return out;
}

systems::Transition transition_of(const ConfigNode& node) {
  node.expect_keys({"from", "to", "when", "after_s", "clears"});
  systems::Transition t;
  t.origin = origin_of(node);
  if (auto from = node.find("from")) {
    if (!(from->is_scalar() && from->as_string() == "any")) t.from = names_of(*from);
  } else {
    node.fail("missing required key 'from' (a state, a list of states, or any)");
  }
  t.to = name_of(node["to"]);
  if (auto when = node.find("when")) t.when = expression_of(*when);
  if (auto after = node.find("after_s")) {
    t.after_s = after->as_double();
    if (t.after_s < 0.0) after->fail("must be >= 0");
  }
  if (auto clears = node.find("clears")) t.clears = names_of(*clears);
  return t;
}

void machine_of(const ConfigNode& node, systems::Element& e) {
  node.expect_keys({"states", "initial", "transitions"});
  e.states = names_of(node["states"]);
  std::set<std::string> unique;
  for (const std::string& s : e.states) {
    if (s == "time_s") node["states"].fail("'time_s' cannot name a state (it is the time in one)");
    if (!unique.insert(s).second) node["states"].fail("state '" + s + "' is named twice");
  }
  if (auto initial = node.find("initial")) {
    e.initial_state = name_of(*initial);
    if (!unique.count(e.initial_state)) initial->fail("not one of the states");
  }
  if (auto transitions = node.find("transitions"))
    for (const ConfigNode& t : transitions->elements()) e.transitions.push_back(transition_of(t));
}

systems::Element element_of(const ConfigNode& node) {
  node.expect_keys({"name", "logic", "lag", "rate", "timer", "latch", "machine", "unit", "events"});
  systems::Element e;
  e.name = name_of(node["name"]);
  e.origin = origin_of(node);
  e.unit = node.get_string("unit", "");
  static constexpr std::array<std::pair<const char*, ElementKind>, 6> kKinds = {{
      {"logic", ElementKind::kLogic}, {"lag", ElementKind::kLag}, {"rate", ElementKind::kRate},
      {"timer", ElementKind::kTimer}, {"latch", ElementKind::kLatch},
      {"machine", ElementKind::kMachine}}};
  int kinds = 0;
  for (const auto& [key, kind] : kKinds) {
    const auto part = node.find(key);
    if (!part) continue;
    ++kinds;
    e.kind = kind;
    switch (kind) {
      case ElementKind::kLogic:
      case ElementKind::kTimer: e.input = expression_of(*part); break;
      case ElementKind::kLag:
        part->expect_keys({"to", "tau_s", "initial"});
        e.input = expression_of((*part)["to"]);
        e.tau_s = positive(*part, "tau_s");
        e.initial = part->get_double("initial", 0.0);
        break;
      case ElementKind::kRate:
        part->expect_keys({"to", "per_s", "initial"});
        e.input = expression_of((*part)["to"]);
        e.per_s = positive(*part, "per_s");
        e.initial = part->get_double("initial", 0.0);
        break;
      case ElementKind::kLatch:
        part->expect_keys({"rises", "reset"});
        e.input = expression_of((*part)["rises"]);
        e.reset = expression_of((*part)["reset"]);
        break;
      case ElementKind::kMachine: machine_of(*part, e); break;
    }
  }
  if (kinds != 1)
    node.fail(kinds == 0 ? "a system needs one of logic, lag, rate, timer, latch, machine"
                         : "a system has one kind: logic, lag, rate, timer, latch or machine");
  if (auto events = node.find("events")) {
    if (e.kind != ElementKind::kLogic) events->fail("only a logic system takes 'events' (machines and latches always report)");
    e.events = events->as_bool();
  }
  return e;
}

}  // namespace

systems::SystemsModel parse_systems_model(const ConfigNode& root) {
  root.expect_keys({"rate_hz", "failures", "systems"});
  systems::SystemsModel model;
  model.source = root.file();
  if (auto rate = root.find("rate_hz")) {
    model.rate_hz = rate->as_double();
    model.rate_origin = origin_of(*rate);
  } else {
    model.rate_origin = origin_of(root);
  }
  if (auto failures = root.find("failures")) {
    for (const ConfigNode& f : failures->elements()) {
      f.expect_keys({"name", "text"});
      model.failures.push_back({name_of(f["name"]), f.get_string("text", ""), origin_of(f)});
    }
  }
  for (const ConfigNode& s : root["systems"].elements()) model.elements.push_back(element_of(s));
  if (model.elements.empty()) root["systems"].fail("no systems");
  return model;
}

systems::SystemsModel load_systems_model(const std::string& path) {
  return parse_systems_model(ConfigNode::load_file(path));
}

}  // namespace vcockpit
