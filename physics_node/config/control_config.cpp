// `controls:` of a scene file (schema at the top of config/cockpit.yaml): each control's joint,
// mechanism and positions, and its moving part as a dynamic object of the scene.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "physics_node/config/scene_parts.hpp"

namespace vcockpit::scene_parts {
namespace {

using physics::ControlKind;
using physics::ControlSpec;
using physics::JointKind;

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

ControlKind parse_control_kind(const ConfigNode& node) {
  const std::string kind = node.as_string();
  if (kind == "push_button") return ControlKind::kPushButton;
  if (kind == "toggle") return ControlKind::kToggle;
  if (kind == "rotary") return ControlKind::kRotary;
  if (kind == "lever") return ControlKind::kLever;
  if (kind == "guard") return ControlKind::kGuard;
  node.fail("unknown kind '" + kind + "' (push_button, toggle, rotary, lever or guard)");
}

JointKind parse_joint(const ConfigNode& node, ControlKind kind) {
  const std::string joint = node.as_string();
  if (joint != "prismatic" && joint != "revolute") {
    node.fail("unknown joint '" + joint + "' (prismatic or revolute)");
  }
  const JointKind j = joint == "prismatic" ? JointKind::kPrismatic : JointKind::kRevolute;
  if (kind == ControlKind::kPushButton && j != JointKind::kPrismatic) {
    node.fail("a push_button moves along its axis: joint prismatic");
  }
  if ((kind == ControlKind::kToggle || kind == ControlKind::kRotary || kind == ControlKind::kGuard) &&
      j != JointKind::kRevolute) {
    node.fail("a " + std::string(physics::control_kind_name(kind)) +
              " turns about its axis: joint revolute");
  }
  return j;
}

// Coordinates are metres on a prismatic joint and degrees (stored as radians) on a revolute one;
// stiffness, damping, friction and strengths are SI per metre or per radian (N/m, N m/rad, ...).
struct Units {
  double scale = 1.0;
  const char* name = "m";
  double coordinate(const ConfigNode& n) const { return n.as_double() * scale; }
  std::string text(double q) const { return format_number(q / scale) + " " + name; }
};

void parse_body(const ConfigNode& node, const std::string& base_dir, physics::ObjectSpec& body) {
  node.expect_keys({"shape", "mass", "density", "inertia", "offset", "material", "color"});
  body.shape = parse_shape(node["shape"], {base_dir, /*moving=*/true});
  parse_mass_properties(node, body);
  if (auto m = node.find("material")) body.material = parse_material(*m, physics::Material{});
  body.color_rgba = default_color(body.shape);
  read_optional(node, "color", body.color_rgba, parse_color);
}

void check_in_travel(const ConfigNode& at, const ControlSpec& c, const Units& u, double q,
                     const std::string& what) {
  if (!c.limited) return;
  if (q < c.q_min || q > c.q_max) {
    at.fail(what + " " + u.text(q) + " is outside the travel [" + u.text(c.q_min) + ", " +
            u.text(c.q_max) + "]");
  }
}

void parse_positions(const ConfigNode& list, ControlSpec& c, const Units& u) {
  for (const ConfigNode& node : list.elements()) {
    node.expect_keys({"name", "at", "enter"});
    physics::ControlPosition p;
    p.name = parse_name(node["name"]);
    if (p.name.size() > 31) node["name"].fail("a position name has at most 31 characters");
    for (const auto& other : c.positions)
      if (other.name == p.name) node["name"].fail("duplicate position name '" + p.name + "'");
    p.q = u.coordinate(node["at"]);
    check_in_travel(node["at"], c, u, p.q, "position");
    const ConfigNode enter = node["enter"];
    const auto lo_hi = enter.as_doubles<2>();
    p.enter_lo = lo_hi[0] * u.scale;
    p.enter_hi = lo_hi[1] * u.scale;
    if (!(p.enter_lo < p.enter_hi)) enter.fail("enter [lo, hi] needs lo < hi");
    if (p.q < p.enter_lo || p.q > p.enter_hi) {
      enter.fail("the interval [" + u.text(p.enter_lo) + ", " + u.text(p.enter_hi) +
                 "] must contain the position's own coordinate " + u.text(p.q));
    }
    if (!c.positions.empty()) {
      const physics::ControlPosition& prev = c.positions.back();
      if (p.q <= prev.q) node["at"].fail("positions must be in increasing order of 'at'");
      if (p.enter_lo <= prev.enter_hi) {
        enter.fail("overlaps position '" + prev.name + "' (its interval ends at " +
                   u.text(prev.enter_hi) + "): the gap between them is the hysteresis");
      }
    }
    c.positions.push_back(std::move(p));
  }
  if (c.positions.size() > static_cast<std::size_t>(physics::kMaxControlPositions)) {
    list.fail("a control has at most " + std::to_string(physics::kMaxControlPositions) +
              " positions, got " + std::to_string(c.positions.size()));
  }
  if (c.positions.size() < 2) {
    list.fail("a control needs at least 2 positions (a momentary one springs back from its "
              "second), got " + std::to_string(c.positions.size()));
  }
}

void parse_mechanism(const ConfigNode& node, ControlSpec& c, const Units& u) {
  if (auto spring = node.find("spring")) {
    spring->expect_keys({"stiffness", "rest"});
    c.stiffness = non_negative((*spring)["stiffness"]);
    c.q_rest = u.coordinate((*spring)["rest"]);
  }
  read_optional(node, "damping", c.damping, non_negative);
  read_optional(node, "friction", c.friction, non_negative);
  if (auto snap = node.find("snap")) {
    snap->expect_keys({"strength", "centre"});
    c.snap = positive((*snap)["strength"], "snap strength");
    c.snap_centre = u.coordinate((*snap)["centre"]);
    check_in_travel((*snap)["centre"], c, u, c.snap_centre, "snap centre");
  }
  if (auto detents = node.find("detents")) {
    for (const ConfigNode& d : detents->elements()) {
      d.expect_keys({"at", "strength", "half_width"});
      physics::Detent detent;
      detent.q = u.coordinate(d["at"]);
      check_in_travel(d["at"], c, u, detent.q, "detent");
      detent.strength = positive(d["strength"], "detent strength");
      detent.half_width = positive(d["half_width"], "half_width") * u.scale;
      c.detents.push_back(detent);
    }
  }
  if (auto every = node.find("detent_every")) {
    if (c.limited) every->fail("detent_every is for a continuous rotary (continuous: true)");
    if (c.detents.size() != 1) every->fail("detent_every repeats exactly one detent (detents: [...])");
    c.detent_period = positive(*every, "detent_every") * u.scale;
  }
  if (auto gates = node.find("gates")) {
    for (const ConfigNode& g : gates->elements()) {
      g.expect_keys({"at", "lift"});
      physics::Gate gate;
      gate.q = u.coordinate(g["at"]);
      check_in_travel(g["at"], c, u, gate.q, "gate");
      gate.lift_m = positive(g["lift"], "lift");
      const bool on_detent = std::any_of(c.detents.begin(), c.detents.end(), [&](const auto& d) {
        return std::abs(gate.q - d.q) < d.half_width;
      });
      if (!on_detent) g["at"].fail("a gate is a detent the hand lifts the lever over: no detent at " + u.text(gate.q));
      c.gates.push_back(gate);
    }
  }
}

// An annunciator: a static object that lights with the control (lit_when).
physics::ObjectSpec parse_light(const ConfigNode& node, const std::string& control_name,
                                const std::string& base_dir) {
  node.expect_keys({"shape", "pose", "color"});
  physics::ObjectSpec light;
  light.name = control_name + "_light";
  light.dynamic = false;
  light.shape = parse_shape(node["shape"], {base_dir, /*moving=*/false});
  light.color_rgba = default_color(light.shape);
  light.X_GO = parse_pose(node["pose"]);
  read_optional(node, "color", light.color_rgba, parse_color);
  return light;
}

ControlSpec parse_control(const ConfigNode& node, int body_index, const std::string& base_dir,
                          physics::ObjectSpec& body) {
  node.expect_keys({"name", "kind", "joint", "pose", "body", "travel", "continuous", "initial",
                    "spring", "damping", "friction", "snap", "detents", "detent_every", "gates",
                    "positions", "latch_at", "lit_when", "light"});
  ControlSpec c;
  c.name = parse_name(node["name"]);
  c.kind = parse_control_kind(node["kind"]);
  c.joint = parse_joint(node["joint"], c.kind);
  c.body = body_index;
  const Units u = c.joint == JointKind::kRevolute ? Units{kDegToRad, "deg"} : Units{};
  c.X_GJ = parse_pose(node["pose"]);
  c.limited = !node.get_bool("continuous", false);
  if (!c.limited && c.kind != ControlKind::kRotary) {
    node["continuous"].fail("only a rotary turns without end");
  }
  if (c.limited) {
    const ConfigNode travel = node["travel"];
    const auto lo_hi = travel.as_doubles<2>();
    c.q_min = lo_hi[0] * u.scale;
    c.q_max = lo_hi[1] * u.scale;
    if (!(c.q_min < c.q_max)) travel.fail("travel [lo, hi] needs lo < hi");
  } else if (auto t = node.find("travel")) {
    t->fail("a continuous rotary has no travel");
  }
  parse_positions(node["positions"], c, u);
  parse_mechanism(node, c, u);
  c.q_initial = c.positions.front().q;
  if (auto initial = node.find("initial")) {
    c.q_initial = u.coordinate(*initial);
    check_in_travel(*initial, c, u, c.q_initial, "initial");
  }
  if (auto latch = node.find("latch_at")) {
    if (c.kind != ControlKind::kPushButton) latch->fail("only a push_button latches");
    if (c.positions.size() != 2) latch->fail("a latching button has 2 positions: off and on");
    c.latching = true;
    c.latch_q = u.coordinate(*latch);
    check_in_travel(*latch, c, u, c.latch_q, "latch_at");
    const auto& off = c.positions.front();
    if (c.latch_q < off.enter_lo || c.latch_q > off.enter_hi) {
      latch->fail("the latch must rest inside the first position's interval (there the button "
                  "re-arms for the press that releases it)");
    }
  }
  if (auto lit = node.find("lit_when")) {
    const std::string name = lit->as_string();
    for (std::size_t i = 0; i < c.positions.size(); ++i)
      if (c.positions[i].name == name) c.lit_when = static_cast<int>(i);
    if (c.lit_when < 0) lit->fail("no position named '" + name + "'");
  }
  const ConfigNode body_node = node["body"];
  body.name = c.name;
  body.dynamic = true;
  parse_body(body_node, base_dir, body);
  if (auto offset = body_node.find("offset")) c.X_JO = parse_pose(*offset);
  // the offset places a model's node; a moving mesh's frame is at its centroid
  c.X_JO = c.X_JO * Eigen::Translation3d(-body.shape.mesh_source.origin_m);
  body.X_GO = physics::control_body_pose(c, c.q_initial);
  return c;
}

}  // namespace

void parse_controls(const ConfigNode& list, const std::string& base_dir, physics::Scene& scene) {
  for (const ConfigNode& node : list.elements()) {
    physics::ObjectSpec body;
    const int body_index = static_cast<int>(scene.objects.size());
    ControlSpec c = parse_control(node, body_index, base_dir, body);
    if (scene.find_object(c.name) >= 0 || scene.find_control(c.name) >= 0) {
      node["name"].fail("duplicate name '" + c.name + "' (objects and controls share names)");
    }
    body.control = static_cast<int>(scene.controls.size());
    scene.objects.push_back(std::move(body));
    if (auto light = node.find("light")) {
      if (c.lit_when < 0) light->fail("a light needs lit_when (the position it is lit in)");
      physics::ObjectSpec spec = parse_light(*light, c.name, base_dir);
      if (scene.find_object(spec.name) >= 0) light->fail("duplicate name '" + spec.name + "'");
      c.light_object = static_cast<int>(scene.objects.size());
      scene.objects.push_back(std::move(spec));
    }
    scene.controls.push_back(std::move(c));
  }
}

}  // namespace vcockpit::scene_parts
