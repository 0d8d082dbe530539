#include "physics_node/config/scene_config.hpp"

#include <filesystem>
#include <sstream>
#include <vector>

#include "common/pose.hpp"
#include "hand/config/hand_yaml.hpp"
#include "model/convex_hull.hpp"
#include "model/import/model_file.hpp"
#include "physics_node/config/scene_parts.hpp"

namespace vcockpit {
namespace scene_parts {

namespace fs = std::filesystem;
using physics::GestureRule;
using physics::GraspParams;
using physics::HoldRule;
using physics::Material;
using physics::ObjectSpec;
using physics::Scene;
using physics::Shape;

constexpr double kMaxStep_s = 0.1;
constexpr int kMaxSubsteps = 1000;     // beyond this a step could not run in real time anyway
constexpr int kMaxSolverIterations = 1000;  // a sweep is microseconds; more is a typo
constexpr int kMaxPointsPerPair = 64;  // FCL reports at most a handful; more is a typo

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

Eigen::Vector3d vector3(const std::array<double, 3>& v) {
  return {v[0], v[1], v[2]};
}

// ---- checked scalars: each failure names the node (file:line:col and key) and the value -----

double require(const ConfigNode& node, double value, bool ok, const std::string& rule) {
  if (!ok) node.fail(rule + ", got " + format_number(value));
  return value;
}

double positive(const ConfigNode& node, const std::string& what) {
  const double v = node.as_double();
  return require(node, v, v > 0.0, what + " must be positive");
}

double non_negative(const ConfigNode& node) {
  const double v = node.as_double();
  return require(node, v, v >= 0.0, "must be >= 0");
}

double at_least(const ConfigNode& node, double lo) {
  const double v = node.as_double();
  return require(node, v, v >= lo, "must be >= " + format_number(lo));
}

double in_open_closed(const ConfigNode& node, double lo, double hi) {
  const double v = node.as_double();
  return require(node, v, v > lo && v <= hi,
                 "must be in (" + format_number(lo) + ", " + format_number(hi) + "]");
}

double in_open(const ConfigNode& node, double lo, double hi) {
  const double v = node.as_double();
  return require(node, v, v > lo && v < hi,
                 "must be in (" + format_number(lo) + ", " + format_number(hi) + ")");
}

int int_in_range(const ConfigNode& node, int lo, int hi) {
  const int64_t v = node.as_int();
  if (v < lo || v > hi) {
    node.fail("must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
              "], got " + std::to_string(v));
  }
  return static_cast<int>(v);
}


// ---- materials, shapes, poses, colours ------------------------------------------------------

Material parse_material(const ConfigNode& node, const Material& defaults) {
  node.expect_keys({"stiffness", "damping_ratio", "mu_s", "mu_d", "mu_roll_m", "mu_spin_m"});
  Material m = defaults;
  read_optional(node, "stiffness", m.stiffness_Npm,
                [](const ConfigNode& n) { return positive(n); });
  read_optional(node, "damping_ratio", m.damping_ratio, non_negative);
  read_optional(node, "mu_s", m.mu_s, non_negative);
  read_optional(node, "mu_d", m.mu_d, non_negative);
  read_optional(node, "mu_roll_m", m.mu_roll_m, non_negative);  // 0: no rolling resistance
  read_optional(node, "mu_spin_m", m.mu_spin_m, non_negative);  // 0: no spinning resistance
  if (m.mu_d > m.mu_s) {
    // blame the key the user wrote (mu_d if given, else the mu_s that undercut the default)
    const ConfigNode at = node.has("mu_d") ? node["mu_d"] : node["mu_s"];
    at.fail("mu_d " + format_number(m.mu_d) + " is greater than mu_s " + format_number(m.mu_s) +
            " (sliding friction cannot exceed sticking friction)");
  }
  return m;
}

// A list of N positive numbers, each checked at its own element.
template <std::size_t N>
std::array<double, N> positive_list(const ConfigNode& node,
                                    const std::array<const char*, N>& what) {
  std::array<double, N> out = node.as_doubles<N>();
  for (std::size_t i = 0; i < N; ++i)
    out[i] = positive(node.at(i), what[i]);
  return out;
}

std::array<float, 4> default_color(const Shape& shape) {
  // a model's own materials as they are; a primitive in the cockpit's grey
  return shape.kind == physics::ShapeKind::kMesh ? std::array<float, 4>{1.0f, 1.0f, 1.0f, 1.0f}
                                        : ObjectSpec{}.color_rgba;
}

// {mesh: FILE, node: NAME, scale: S, up: y|z}: the request it makes, the file relative to the
// scene's directory
model::ModelRequest mesh_request(const ConfigNode& node, const std::string& base_dir) {
  node.expect_keys({"mesh", "node", "scale", "up"});
  model::ModelRequest request;
  const std::string file = node["mesh"].as_string();
  if (file.empty()) node["mesh"].fail("the model file name must not be empty");
  fs::path path(file);
  if (path.is_relative() && !base_dir.empty()) path = fs::path(base_dir) / path;
  // absolute: the image generator reads the same file from wherever it was started
  request.path = fs::absolute(path).lexically_normal().string();
  if (request.path.size() > 255)
    node["mesh"].fail("the model file's path is longer than 255 characters (cockpit/object_info)");
  read_optional(node, "node", request.node, [](const ConfigNode& n) { return n.as_string(); });
  if (request.node.size() > 64) node["node"].fail("a node name longer than 64 characters");
  if (auto scale = node.find("scale")) request.scale = positive(*scale, "scale");
  if (auto up = node.find("up")) {
    const std::string axis = up->as_string();
    if (axis != "y" && axis != "z") up->fail("up must be y or z, not '" + axis + "'");
    request.up = axis == "z" ? model::UpAxis::kZ : model::UpAxis::kY;
  }
  return request;
}

// The model parts a scene's objects and controls name (shapes and looks), for a ModelPrefetch;
// one the YAML gets wrong is left out (its parse reports it).
std::vector<model::ModelRequest> mesh_requests(const ConfigNode& root, const std::string& base_dir) {
  std::vector<model::ModelRequest> out;
  const auto add = [&](const ConfigNode& parent, const char* key) {
    try {
      if (!parent.is_map()) return;
      const auto shape = parent.find(key);
      if (shape && shape->is_map() && shape->has("mesh")) out.push_back(mesh_request(*shape, base_dir));
    } catch (const ConfigError&) {
    }
  };
  for (const char* list : {"objects", "controls"}) {
    const auto items = root.is_map() ? root.find(list) : std::nullopt;
    if (!items || !items->is_sequence()) continue;
    for (const ConfigNode& item : items->elements()) {
      add(item, "shape");
      add(item, "look");
      for (const char* part : {"body", "light"}) {
        if (!item.is_map()) continue;
        if (const auto child = item.find(part)) add(*child, "shape");
      }
    }
  }
  return out;
}

Shape parse_mesh_shape(const ConfigNode& node, const ShapeContext& context) {
  const model::ModelRequest request = mesh_request(node, context.base_dir);
  try {
    auto mesh = std::make_shared<model::TriangleMesh>(model::load_model_mesh(request));
    std::shared_ptr<model::TriangleMesh> hull;  // a static mesh collides as its triangles
    Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();
    if (context.moving) {
      hull = std::make_shared<model::TriangleMesh>(model::convex_hull(*mesh));
      // a moving body's frame is its centroid: the solid of its hull (what it collides as)
      origin_m = -model::mass_properties(*hull).centroid_m;
      model::translate(*mesh, origin_m);
      model::translate(*hull, origin_m);
    }
    Shape shape = Shape::triangle_mesh(std::move(mesh), std::move(hull));
    shape.mesh_source = {request.path, request.node, request.scale, request.up == model::UpAxis::kZ, origin_m};
    return shape;
  } catch (const model::MeshError& e) {
    node["mesh"].fail(e.what());
  }
}

Shape parse_shape(const ConfigNode& node, const ShapeContext& context) {
  if (node.find("mesh")) return parse_mesh_shape(node, context);
  node.expect_keys({"box", "sphere", "capsule", "cylinder"});
  const std::vector<std::string> keys = node.keys();
  if (keys.size() != 1) {
    node.fail("expected exactly one of box, sphere, capsule, cylinder, mesh, found " +
              std::to_string(keys.size()));
  }
  const ConfigNode dims = node[keys[0]];
  if (keys[0] == "box") {
    return Shape::box(vector3(positive_list<3>(dims, {"size x", "size y", "size z"})));
  }
  if (keys[0] == "sphere") return Shape::sphere(positive(dims, "radius"));
  const auto radius_length = positive_list<2>(dims, {"radius", "length"});
  return keys[0] == "capsule" ? Shape::capsule(radius_length[0], radius_length[1])
                              : Shape::cylinder(radius_length[0], radius_length[1]);
}

Eigen::Isometry3d parse_pose(const ConfigNode& node) {
  node.expect_keys({"position", "rpy_deg"});
  std::array<double, 3> rpy_deg{0.0, 0.0, 0.0};
  read_optional(node, "rpy_deg", rpy_deg, [](const ConfigNode& n) { return n.as_doubles<3>(); });
  return pose_from_position_rpy_deg(node["position"].as_doubles<3>(), rpy_deg);
}

std::array<float, 4> parse_color(const ConfigNode& node) {
  if (!node.is_sequence() || (node.size() != 3 && node.size() != 4)) {
    node.fail("expected [r, g, b] or [r, g, b, a] with components in [0, 1]");
  }
  std::array<float, 4> rgba{0.0f, 0.0f, 0.0f, 1.0f};
  for (std::size_t i = 0; i < node.size(); ++i) {
    const ConfigNode c = node.at(i);
    const double v = c.as_double();
    rgba[i] = static_cast<float>(require(c, v, v >= 0.0 && v <= 1.0, "must be in [0, 1]"));
  }
  return rgba;
}

// ---- objects ----------------------------------------------------------------------------------

bool parse_kind_is_dynamic(const ConfigNode& node) {
  const std::string kind = node.as_string();
  if (kind != "static" && kind != "dynamic") {
    node.fail("unknown kind '" + kind + "' (static or dynamic)");
  }
  return kind == "dynamic";
}

std::string parse_name(const ConfigNode& node) {
  const std::string name = node.as_string();
  if (name.empty()) node.fail("the name must not be empty");
  return name;
}

// Principal moments about the centroid; any real body obeys the triangle inequality.
Eigen::Matrix3d parse_inertia(const ConfigNode& node) {
  const Eigen::Vector3d I = vector3(positive_list<3>(node, {"ixx", "iyy", "izz"}));
  const double slack = 1e-9 * I.sum();  // decimal inputs of a thin plate land on equality
  for (int i = 0; i < 3; ++i) {
    if (I[i] > I[(i + 1) % 3] + I[(i + 2) % 3] + slack) {
      node.fail("principal moments [" + format_number(I.x()) + ", " + format_number(I.y()) + ", " +
                format_number(I.z()) +
                "] break the triangle inequality (each must be <= the sum of the other two)");
    }
  }
  return I.asDiagonal();
}

// Mass from `mass` or `density` (exactly one), inertia from `inertia` or from the shape.
void parse_mass_properties(const ConfigNode& node, ObjectSpec& spec) {
  const auto mass = node.find("mass");
  const auto density = node.find("density");
  if (mass && density) density->fail("give either mass or density, not both");
  if (!mass && !density) node.fail("a dynamic object needs 'mass' or 'density'");
  if (mass) {
    spec.mass_kg = positive(*mass, "mass");
    spec.I_O = spec.mass_kg / spec.shape.volume_m3() * spec.shape.unit_density_inertia();
  } else {
    physics::mass_properties_from_density(spec.shape, positive(*density, "density"), spec.mass_kg,
                                          spec.I_O);
  }
  read_optional(node, "inertia", spec.I_O, parse_inertia);
}

void parse_velocity(const ConfigNode& node, ObjectSpec& spec) {
  node.expect_keys({"linear", "angular"});
  auto vec = [](const ConfigNode& n) { return vector3(n.as_doubles<3>()); };
  read_optional(node, "linear", spec.v_G, vec);
  read_optional(node, "angular", spec.w_G, vec);
}

// A static object never moves, so anything about its motion is a mistake worth naming.
void reject_dynamics(const ConfigNode& node) {
  for (const char* key : {"mass", "density", "inertia", "velocity"}) {
    if (auto n = node.find(key)) {
      n->fail("a static object has no " + std::string(key) + " (make it kind: dynamic)");
    }
  }
}

ObjectSpec parse_object(const ConfigNode& node, const std::string& base_dir) {
  node.expect_keys({"name", "kind", "shape", "look", "pose", "mass", "density", "inertia",
                    "velocity", "material", "color"});
  ObjectSpec spec;
  spec.name = parse_name(node["name"]);
  spec.dynamic = parse_kind_is_dynamic(node["kind"]);
  spec.shape = parse_shape(node["shape"], {base_dir, spec.dynamic});
  // the pose places the model's node; a moving mesh's frame is at its centroid
  spec.X_GO = parse_pose(node["pose"]) * Eigen::Translation3d(-spec.shape.mesh_source.origin_m);
  if (spec.dynamic) {
    parse_mass_properties(node, spec);
    if (auto v = node.find("velocity")) parse_velocity(*v, spec);
  } else {
    reject_dynamics(node);
  }
  if (auto look = node.find("look")) {
    // drawn in the box's place, so it cannot ride a centroid the box gives (a moving part)
    if (spec.dynamic) look->fail("a look is for a static object (a dynamic one is drawn as its shape)");
    spec.look = parse_mesh_shape(*look, {base_dir, false});
  }
  if (auto m = node.find("material")) spec.material = parse_material(*m, Material{});
  spec.color_rgba = default_color(spec.look ? *spec.look : spec.shape);
  read_optional(node, "color", spec.color_rgba, parse_color);
  return spec;
}

void parse_objects(const ConfigNode& list, const std::string& base_dir, Scene& scene) {
  std::vector<int> lines;  // where each object's name was written, for the duplicate message
  for (const ConfigNode& node : list.elements()) {
    ObjectSpec spec = parse_object(node, base_dir);
    const int first = scene.find_object(spec.name);
    if (first >= 0) {
      node["name"].fail("duplicate object name '" + spec.name + "' (first used on line " +
                        std::to_string(lines[static_cast<std::size_t>(first)]) + ")");
    }
    lines.push_back(node["name"].line());
    scene.objects.push_back(std::move(spec));
  }
}

// ---- hand, grasp, contact ---------------------------------------------------------------------

// A hand file's model (relative to the scene's directory); its errors name the hand file.
hand::HandModel load_hand_file(const ConfigNode& node, const std::string& base_dir) {
  const std::string name = node.as_string();
  if (name.empty()) node.fail("the hand file name must not be empty");
  fs::path path(name);
  if (path.is_relative() && !base_dir.empty()) path = fs::path(base_dir) / path;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) node.fail("cannot open hand file '" + path.string() + "'");
  return load_hand_model(path.string());
}

void parse_hand(const ConfigNode& node, const std::string& base_dir, Scene& scene) {
  scene.hands = {load_hand_file(node, base_dir)};
}

// hands: [file, {file: f, side: right|left}, ...]: a side given here overrides the file's (a
// right hand's file mirrored to the left); at most one right and one left hand.
void parse_hands(const ConfigNode& node, const std::string& base_dir, Scene& scene) {
  if (!node.is_sequence() || node.size() == 0 || node.size() > 2)
    node.fail("expected a list of one or two hands (a file, or {file, side})");
  scene.hands.clear();
  for (const ConfigNode& entry : node.elements()) {
    hand::HandModel model;
    if (entry.is_map()) {
      entry.expect_keys({"file", "side"});
      model = load_hand_file(entry["file"], base_dir);
      if (auto side = entry.find("side")) {
        const std::string text = side->as_string();
        if (text != "right" && text != "left") side->fail("expected right or left, got '" + text + "'");
        if ((text == "left") != model.left) model = hand::mirrored(model);
      }
    } else {
      model = load_hand_file(entry, base_dir);
    }
    for (const hand::HandModel& other : scene.hands)
      if (other.left == model.left)
        entry.fail(std::string("a second ") + (model.left ? "left" : "right") +
                   " hand: the hands are one right and one left");
    scene.hands.push_back(std::move(model));
  }
}

// project | paper | none; true and false, from before the paper's reading was kept, are project
// and none
GestureRule parse_gesture_rule(const ConfigNode& n) {
  const std::string v = n.as_string();
  if (v == "project" || v == "true") return GestureRule::kProject;
  if (v == "paper") return GestureRule::kPaper;
  if (v == "none" || v == "false") return GestureRule::kNone;
  n.fail("'" + v + "': expected project, paper or none");
}

HoldRule parse_hold_rule(const ConfigNode& n) {
  const std::string v = n.as_string();
  if (v == "grip") return HoldRule::kTrackedGrip;
  if (v == "test") return HoldRule::kContactTest;
  n.fail("'" + v + "': expected grip (the tracked hand's grip) or test (the contact test)");
}

GraspParams parse_grasp(const ConfigNode& node) {
  node.expect_keys({"xi_N", "eta_Nm", "alpha0_deg", "min_contacts", "exit_min_contacts", "exit_scale",
                    "exit_alpha_margin_deg", "min_hold_s", "release_delay_s", "regrab_cooldown_s",
                    "velocity_window_s", "settle_speed_mps", "settle_window_s",
                    "release_opening_share", "release_opening_deg", "release_gap_m",
                    "palm_opposition", "gesture_rule", "hold_rule"});
  GraspParams g;
  auto pos = [](const ConfigNode& n) { return positive(n); };
  read_optional(node, "xi_N", g.xi_N, pos);
  read_optional(node, "eta_Nm", g.eta_Nm, pos);
  read_optional(node, "alpha0_deg", g.alpha0_deg,
                [](const ConfigNode& n) { return in_open(n, 0.0, 180.0); });
  read_optional(node, "min_contacts", g.min_contacts,
                [](const ConfigNode& n) { return int_in_range(n, 1, hand::kLinkCount); });
  read_optional(node, "exit_min_contacts", g.exit_min_contacts,
                [](const ConfigNode& n) { return int_in_range(n, 1, hand::kLinkCount); });
  if (!node.has("exit_min_contacts")) g.exit_min_contacts = std::min(g.exit_min_contacts, g.min_contacts);
  if (g.exit_min_contacts > g.min_contacts) {
    node["exit_min_contacts"].fail("exit_min_contacts " + std::to_string(g.exit_min_contacts) +
            " must not exceed min_contacts " + std::to_string(g.min_contacts) +
            " (a held object would need more links than a grasp: chatter, not hysteresis)");
  }
  // below 1 the exit thresholds would be tighter than the entry ones: chatter, not hysteresis
  read_optional(node, "exit_scale", g.exit_scale,
                [](const ConfigNode& n) { return at_least(n, 1.0); });
  read_optional(node, "exit_alpha_margin_deg", g.exit_alpha_margin_deg, non_negative);
  read_optional(node, "min_hold_s", g.min_hold_s, non_negative);
  read_optional(node, "release_delay_s", g.release_delay_s, non_negative);
  read_optional(node, "regrab_cooldown_s", g.regrab_cooldown_s, non_negative);
  read_optional(node, "velocity_window_s", g.velocity_window_s, pos);
  read_optional(node, "settle_speed_mps", g.settle_speed_mps, non_negative);
  read_optional(node, "settle_window_s", g.settle_window_s, pos);
  read_optional(node, "release_opening_share", g.release_opening_share,
                [](const ConfigNode& n) {
                  const double v = n.as_double();
                  return require(n, v, v >= 0.0 && v < 1.0, "must be in [0, 1) (0: off)");
                });
  read_optional(node, "release_opening_deg", g.release_opening_deg, non_negative);
  read_optional(node, "release_gap_m", g.release_gap_m, pos);
  g.palm_opposition = node.get_bool("palm_opposition", g.palm_opposition);
  if (node.has("gesture_rule")) g.gesture_rule = parse_gesture_rule(node["gesture_rule"]);
  if (node.has("hold_rule")) g.hold_rule = parse_hold_rule(node["hold_rule"]);
  if (g.exit_alpha_margin_deg >= g.alpha0_deg) {
    const ConfigNode at =
        node.has("exit_alpha_margin_deg") ? node["exit_alpha_margin_deg"] : node["alpha0_deg"];
    at.fail("exit_alpha_margin_deg " + format_number(g.exit_alpha_margin_deg) +
            " must be below alpha0_deg " + format_number(g.alpha0_deg));
  }
  return g;
}

physics::ContactParams parse_contact(const ConfigNode& node) {
  node.expect_keys({"slip_speed_mps", "substep_safety", "max_substeps", "max_points_per_pair",
                    "solver", "iterations", "relax_iterations", "restitution_threshold_mps"});
  physics::ContactParams c;
  read_optional(node, "slip_speed_mps", c.slip_speed_mps,
                [](const ConfigNode& n) { return positive(n); });
  // The explicit penalty path and its substeps are gone: the contacts are soft constraints, one
  // solve a step. Scenes written for it still load; their substep settings are read (a bad value
  // is still an error) and have nothing left to set. Asking for the penalty path is an error.
  if (const auto k = node.find("substep_safety")) (void)in_open_closed(*k, 0.0, 1.0);
  if (const auto k = node.find("max_substeps")) (void)int_in_range(*k, 1, kMaxSubsteps);
  if (const auto k = node.find("solver"); k && k->as_string() != "soft")
    k->fail("'" + k->as_string() + "': the contacts are soft constraints, one solve a step "
            "(the explicit penalty path and its substeps were removed); the only value is soft");
  read_optional(node, "max_points_per_pair", c.max_points_per_pair,
                [](const ConfigNode& n) { return int_in_range(n, 1, kMaxPointsPerPair); });
  read_optional(node, "iterations", c.iterations,
                [](const ConfigNode& n) { return int_in_range(n, 1, kMaxSolverIterations); });
  read_optional(node, "relax_iterations", c.relax_iterations,
                [](const ConfigNode& n) { return int_in_range(n, 0, kMaxSolverIterations); });
  // (0 would bounce every resting contact: its approach speed each step is g h)
  read_optional(node, "restitution_threshold_mps", c.restitution_threshold_mps,
                [](const ConfigNode& n) { return positive(n); });
  return c;
}

physics::ProxyParams parse_proxy(const ConfigNode& node) {
  node.expect_keys({"enabled", "max_speed_mps", "max_spin_radps", "push_speed_mps",
                    "grip_force_N", "grip_weight_ratio", "static_depth_m", "finger_pull_ratio",
                    "pass_through_depth_m"});
  physics::ProxyParams p;
  auto pos = [](const ConfigNode& n) { return positive(n); };
  if (auto e = node.find("enabled")) p.enabled = e->as_bool();
  read_optional(node, "max_speed_mps", p.max_speed_mps, pos);
  read_optional(node, "max_spin_radps", p.max_spin_radps, pos);
  read_optional(node, "push_speed_mps", p.push_speed_mps, pos);
  read_optional(node, "grip_force_N", p.grip_force_N, pos);
  read_optional(node, "grip_weight_ratio", p.grip_weight_ratio, pos);
  read_optional(node, "finger_pull_ratio", p.finger_pull_ratio,
                [](const ConfigNode& n) {
                  const double v = n.as_double();
                  return require(n, v, v >= 0.0 && v <= 100.0, "must be in [0, 100]");
                });
  // the promise is "never more than 1 mm inside a static object"
  read_optional(node, "static_depth_m", p.static_depth_m,
                [](const ConfigNode& n) { return in_open_closed(n, 0.0, 1.0e-3); });
  read_optional(node, "pass_through_depth_m", p.pass_through_depth_m,
                non_negative);  // 0: until no link is in the object
  if (p.push_speed_mps > p.max_speed_mps) {
    const ConfigNode at =
        node.has("push_speed_mps") ? node["push_speed_mps"] : node["max_speed_mps"];
    at.fail("push_speed_mps " + format_number(p.push_speed_mps) +
                                " must not exceed max_speed_mps " +
                                format_number(p.max_speed_mps));
  }
  return p;
}

physics::SleepParams parse_sleep(const ConfigNode& node) {
  node.expect_keys({"enabled", "speed_mps", "time_s"});
  physics::SleepParams p;
  auto pos = [](const ConfigNode& n) { return positive(n); };
  if (auto e = node.find("enabled")) p.enabled = e->as_bool();
  read_optional(node, "speed_mps", p.speed_mps, pos);
  read_optional(node, "time_s", p.time_s, pos);
  return p;
}

}  // namespace scene_parts

physics::Scene parse_scene(const ConfigNode& root, const std::string& base_dir) {
  using namespace scene_parts;
  root.expect_keys({"gravity", "step_s", "hand", "hands", "hand_material", "objects", "controls",
                    "grasp", "contact", "proxy", "sleep"});
  Scene scene;
  scene.gravity_mps2 = vector3(root["gravity"].as_doubles<3>());
  scene.step_s = in_open_closed(root["step_s"], 0.0, kMaxStep_s);
  if (auto hand = root.find("hand")) parse_hand(*hand, base_dir, scene);
  if (auto hands = root.find("hands")) {
    if (root.has("hand")) hands->fail("give either hand or hands, not both");
    parse_hands(*hands, base_dir, scene);
  }
  if (auto m = root.find("hand_material"))
    scene.hand_material = parse_material(*m, scene.hand_material);
  {
    // every part of one model file read in one go (a cockpit's parts are often one file's nodes)
    const model::ModelPrefetch models(mesh_requests(root, base_dir));
    parse_objects(root["objects"], base_dir, scene);
    if (auto controls = root.find("controls")) parse_controls(*controls, base_dir, scene);
  }
  read_optional(root, "grasp", scene.grasp, parse_grasp);
  read_optional(root, "contact", scene.contact, parse_contact);
  read_optional(root, "proxy", scene.proxy, parse_proxy);
  read_optional(root, "sleep", scene.sleep, parse_sleep);
  return scene;
}

physics::Scene load_scene(const std::string& path) {
  return parse_scene(ConfigNode::load_file(path),
                     std::filesystem::path(path).parent_path().string());
}

}  // namespace vcockpit
