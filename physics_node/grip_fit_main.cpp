// grip_fit: from a glove recording, a scene where the recorded hand grasps an object and holds
// it. It tries moments across the first closed stretch of the log (fit/steady_moment.hpp),
// earliest first, places the object inside the recorded grip at each (fit/grip_fit.hpp), lays out
// a pedestal under it, replays the log on each candidate scene in memory and takes the first that
// the hand grasps and holds (fit/grip_choice.hpp, fit/hold_check.hpp); then writes that scene
// (config/grip_scene_yaml.hpp), which physics_node --offline replays the log on.
//
// Exit codes: 0 scene written; 1 no placement (the best one's figures are printed) or none that
// holds when replayed (each candidate's line says why); nothing written; 2 bad flags or files
// (the loaders' file:line errors).

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "common/cli_finite.hpp"
#include "hand/glove_log.hpp"
#include "hand/config/hand_yaml.hpp"
#include "physics_node/config/grip_scene_yaml.hpp"
#include "physics_node/fit/grip_choice.hpp"
#include "physics_node/fit/grip_fit.hpp"
#include "physics_node/fit/hand_approach.hpp"
#include "physics_node/fit/steady_moment.hpp"

namespace vcockpit {
namespace {

constexpr int kNoPlacement = 1;
constexpr int kBadInput = 2;

struct Flags {
  std::string log_path;
  std::string hand_path = std::string(VCOCKPIT_CONFIG_DIR) + "/hand.yaml";
  std::string shape;
  std::vector<double> size_m;
  std::string out_path;
  double mass_kg = 0.06;
  std::optional<double> at_s;
  bool no_verify = false;
  std::string cockpit_path = std::string(VCOCKPIT_CONFIG_DIR) + "/cockpit.yaml";
  std::string material_of = "cup";
  std::string name = "object";
};

// A bad flag value the parser cannot check alone: exit 2.
struct BadFlag : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void add_flags(CLI::App& app, Flags& f) {
  app.add_option("--log", f.log_path, "glove log CSV (the project's format, hand/glove_log.hpp)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--hand", f.hand_path, "hand model YAML (the log's '# hand:' side is used)")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  app.add_option("--shape", f.shape,
                 "object shape: box, sphere, cylinder or capsule (axis along "
                 "the object's z, as in the scene YAML)")
      ->required()
      ->check(CLI::IsMember({"box", "sphere", "cylinder", "capsule"}));
  app.add_option(
         "--size", f.size_m,
         "sizes in m, comma-separated: box X,Y,Z (full extents); sphere R; cylinder R,LENGTH; "
         "capsule R,LENGTH (length without the caps)")
      ->required()
      ->delimiter(',')
      ->check(CLI::PositiveNumber & kFinite);
  app.add_option("--out", f.out_path, "scene YAML to write (atomically; its folder must exist)")
      ->required();
  app.add_option("--mass", f.mass_kg, "the object's mass (kg)")
      ->check(CLI::PositiveNumber & kFinite)
      ->capture_default_str();
  app.add_option("--at", f.at_s,
                 "try only the sample nearest this t_s (s), not moments across the first closed "
                 "stretch")
      ->check(kFinite);
  app.add_flag("--no-verify", f.no_verify,
               "do not replay the log on the candidates: take the first placement (the earliest "
               "moment's best) unchecked");
  app.add_option("--cockpit", f.cockpit_path,
                 "scene whose gravity, step_s, hand_material, grasp, contact and proxy settings "
                 "are copied, and whose --material-of object lends its material")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  app.add_option("--material-of", f.material_of,
                 "the cockpit object whose material the object takes")
      ->capture_default_str();
  app.add_option("--name", f.name, "the object's name in the scene")->capture_default_str();
}

physics::Shape shape_from(const Flags& f) {
  const std::size_t want = f.shape == "box" ? 3 : f.shape == "sphere" ? 1 : 2;
  if (f.size_m.size() != want) {
    throw BadFlag("--size: a " + f.shape + " takes " + std::to_string(want) + " number" +
                  (want > 1 ? "s" : "") + " (" +
                  (f.shape == "box"      ? "X,Y,Z"
                   : f.shape == "sphere" ? "R"
                                         : "R,LENGTH") +
                  "), got " + std::to_string(f.size_m.size()));
  }
  if (f.shape == "box") return physics::Shape::box({f.size_m[0], f.size_m[1], f.size_m[2]});
  if (f.shape == "sphere") return physics::Shape::sphere(f.size_m[0]);
  if (f.shape == "cylinder") return physics::Shape::cylinder(f.size_m[0], f.size_m[1]);
  return physics::Shape::capsule(f.size_m[0], f.size_m[1]);
}

std::string shape_text(const physics::Shape& s) {
  char text[128];
  switch (s.kind) {
    case physics::ShapeKind::kBox:
      std::snprintf(text, sizeof text, "box %.1f x %.1f x %.1f mm", s.box_size_m.x() * 1e3,
                    s.box_size_m.y() * 1e3, s.box_size_m.z() * 1e3);
      break;
    case physics::ShapeKind::kSphere:
      std::snprintf(text, sizeof text, "sphere r %.1f mm", s.radius_m * 1e3);
      break;
    default:
      std::snprintf(text, sizeof text, "%s r %.1f mm, length %.1f mm",
                    s.kind == physics::ShapeKind::kCylinder ? "cylinder" : "capsule",
                    s.radius_m * 1e3, s.length_m * 1e3);
  }
  return text;
}

std::string name_of(hand::Link link) {
  return std::string(hand::link_name(link));
}

void print_figures(const fit::Placement& p, const fit::FitLimits& limits) {
  std::printf(
      "surface distance (a finger within %.1f mm touches; < 0: inside) and the angle of the "
      "surface normal there from the thumb's (over %.0f deg: opposes it):\n",
      limits.contact_m * 1e3, limits.opposition_deg);
  for (int f = 0; f < hand::kFingerCount; ++f) {
    const auto k = static_cast<std::size_t>(f);
    const bool touches = p.finger_distance_m[k] <= limits.contact_m;
    const bool opposes = f > 0 && p.finger_opposition_deg[k] > limits.opposition_deg;
    char angle[32] = "";
    if (f > 0) std::snprintf(angle, sizeof angle, "%5.0f deg", p.finger_opposition_deg[k]);
    std::printf("  %-7s %7.2f mm  %-15s %9s%s\n",
                std::string(hand::finger_name(static_cast<hand::Finger>(f))).c_str(),
                p.finger_distance_m[k] * 1e3, name_of(p.finger_link[k]).c_str(), angle,
                !touches  ? ""
                : f == 0  ? "  touches"
                : opposes ? "  grips"
                          : "  touches, not opposed");
  }
  std::printf("  %-7s %7.2f mm\n", "palm", p.link_distance_m[0] * 1e3);
  if (p.deepest_m > 0.0) {
    std::printf("deepest link: %s, %.2f mm inside (limit %.1f mm)\n",
                name_of(p.deepest_link).c_str(), p.deepest_m * 1e3, limits.max_depth_m * 1e3);
  } else {
    std::printf("deepest link: none inside; nearest %s, %.2f mm away\n",
                name_of(p.deepest_link).c_str(), -p.deepest_m * 1e3);
  }
}

std::string no_placement_reason(const fit::Placement& p, const fit::FitLimits& limits) {
  std::string why;
  const auto add = [&](const std::string& s) { why += (why.empty() ? "" : "; ") + s; };
  char text[200];
  if (!p.thumb_touches) {
    std::snprintf(text, sizeof text, "the thumb stays %.2f mm off the surface",
                  p.finger_distance_m[0] * 1e3);
    add(text);
  }
  const int touching = p.touching_fingers - (p.thumb_touches ? 1 : 0);
  if (touching < limits.other_fingers || p.gripping_fingers < limits.opposing_fingers) {
    std::snprintf(text, sizeof text,
                  "%d other finger%s within %.1f mm (needs %d), %d of them opposing the thumb "
                  "(needs %d)",
                  touching, touching == 1 ? "" : "s", limits.contact_m * 1e3, limits.other_fingers,
                  p.gripping_fingers, limits.opposing_fingers);
    add(text);
  }
  if (p.deepest_m > limits.max_depth_m) {
    std::snprintf(text, sizeof text, "%s %.2f mm inside (limit %.1f mm)",
                  name_of(p.deepest_link).c_str(), p.deepest_m * 1e3, limits.max_depth_m * 1e3);
    add(text);
  }
  return why;
}

void check_out_path(const std::string& out_path) {
  namespace fs = std::filesystem;
  const fs::path out(out_path);
  if (out_path.empty() || !out.has_filename())
    throw BadFlag("--out: '" + out_path + "' is not a file name");
  if (fs::is_directory(out)) throw BadFlag("--out: '" + out_path + "' is a directory, not a file");
  const fs::path dir = out.has_parent_path() ? out.parent_path() : ".";
  if (!fs::is_directory(dir))
    throw BadFlag("--out: directory '" + dir.string() + "' does not exist");
}

void print_moment(const fit::Moment& m, std::size_t sample_count, const char* why) {
  std::printf(
      "moment: t_s %.4f (sample %zu of %zu, %s; flexion %.2f rad, %.0f%% of the log's range; "
      "motion %.3f rad over +-50 ms)\n",
      hand::ns_to_log_seconds(m.t_ns), m.index + 1, sample_count, why, m.flexion_rad,
      m.closure_share * 100.0, m.motion);
}

void print_placement(const fit::GripTrial& t, const physics::Shape& shape,
                     const fit::FitLimits& limits) {
  const fit::Placement& p = t.placement;
  const Eigen::Vector3d p_GO = p.X_GO.translation();
  const Eigen::Vector3d rpy = object_rpy_deg(shape, p.X_GO.linear());
  std::printf("%s: %s at p_G (%.5f, %.5f, %.5f) m, rpy_deg (%.2f, %.2f, %.2f)%s%s\n",
              p.accepted ? "placement" : "best miss", shape_text(shape).c_str(), p_GO.x(), p_GO.y(),
              p_GO.z(), rpy.x(), rpy.y(), rpy.z(), p.accepted ? ", " : "",
              p.accepted ? p.rest_name : "");
  const Eigen::Isometry3d X_HO = t.grip.X_GH.inverse() * p.X_GO;
  std::printf(
      "  in the hand frame H (x to the fingertips, y to the thumb, z out of the back): "
      "centre (%.1f, %.1f, %.1f) mm",
      X_HO.translation().x() * 1e3, X_HO.translation().y() * 1e3, X_HO.translation().z() * 1e3);
  if (shape.kind == physics::ShapeKind::kCylinder || shape.kind == physics::ShapeKind::kCapsule) {
    const Eigen::Vector3d axis_H = X_HO.linear().col(2);
    std::printf(", axis (%.2f, %.2f, %.2f)", axis_H.x(), axis_H.y(), axis_H.z());
  }
  std::printf("\n");
  print_figures(p, limits);
}

int run(const Flags& f) {
  const physics::Shape shape = shape_from(f);
  if (!std::regex_match(f.name, std::regex("[A-Za-z_][A-Za-z0-9_]*")))
    throw BadFlag("--name: '" + f.name + "' is not a plain name (letters, digits, _)");
  check_out_path(f.out_path);

  hand::HandModel model = load_hand_model(f.hand_path);
  const bool left = hand::glove_log_left_hand(f.log_path);
  if (left != model.left) model = hand::mirrored(model);
  const hand::GloveLog log = hand::read_glove_log(f.log_path, model);
  for (const std::string& warning : hand::glove_log_warnings(log))
    std::fprintf(stderr, "grip_fit: %s\n", warning.c_str());

  fit::GripChoiceOptions options;
  options.verify = !f.no_verify;
  options.object_name = f.name;
  // VCOCKPIT_GRIP_FIT_TRACE=1: each replay's object, hand contacts and grasp test every 10 ms on
  // stderr (finding out why a candidate fails)
  options.trace_replays = std::getenv("VCOCKPIT_GRIP_FIT_TRACE") != nullptr;
  if (f.at_s) {
    const double first_s = hand::ns_to_log_seconds(log.samples.front().t_ns);
    const double last_s = hand::ns_to_log_seconds(log.samples.back().t_ns);
    if (*f.at_s < first_s || *f.at_s > last_s) {
      char text[160];
      std::snprintf(text, sizeof text, "--at %.6g: outside the log's t_s range [%.6g, %.6g]",
                    *f.at_s, first_s, last_s);
      throw BadFlag(text);
    }
    options.at_ns = hand::log_seconds_to_ns(*f.at_s);
  }
  const fit::FitLimits& limits = options.limits;
  if (const auto stretch = fit::first_closed_stretch(model, log.samples, options.moment_rule)) {
    const auto t_of = [&](std::size_t i) {
      return i < log.samples.size() ? hand::ns_to_log_seconds(log.samples[i].t_ns) : INFINITY;
    };
    char moments_text[160];
    std::snprintf(moments_text, sizeof moments_text,
                  "moments tried earliest first from t_s %.4f to %.4f, every %.0f ms",
                  t_of(stretch->closing), t_of(stretch->last_moment), options.moment_step_s * 1e3);
    const std::string moments = f.at_s ? "only the --at moment tried" : moments_text;
    std::printf(
        "first closed stretch: t_s %.4f to %.4f (its last closed sample), closing from t_s "
        "%.4f; the hand opens after t_s %.4f; %s%s\n",
        t_of(stretch->first), t_of(stretch->last_closed), t_of(stretch->closing),
        t_of(stretch->opening), moments.c_str(),
        f.no_verify ? ", not replayed (--no-verify)" : "; each candidate replayed until one holds");
  }

  GripSceneSpec base;
  base.object_name = f.name;
  base.shape = shape;
  base.mass_kg = f.mass_kg;
  base.hand_path = f.hand_path;
  base.left_hand = left;
  base.cockpit_path = f.cockpit_path;
  base.material_of = f.material_of;
  const auto scene_for = [&](const fit::GripTrial& t) {
    return grip_scene(with_candidate(base, t), f.out_path);
  };
  const auto report = [](const fit::GripTrial& t) {
    std::printf("  tried %s\n", fit::trial_line(t).c_str());
    std::fflush(stdout);
  };
  const fit::GripChoice choice =
      fit::choose_grip(model, log.samples, shape, options, scene_for, report);

  if (choice.placed == 0) {
    // the figures of the nearest miss over the moments tried
    const fit::GripTrial* best = nullptr;
    for (const fit::GripTrial& t : choice.trials)
      if (!best || t.placement.cost < best->placement.cost) best = &t;
    if (best == nullptr) throw BadFlag("the log has no samples");
    print_moment(best->moment, log.samples.size(), f.at_s ? "forced by --at" : "the nearest miss");
    print_placement(*best, shape, limits);
    std::fprintf(stderr,
                 "grip_fit: no placement of the %s in the grip at t_s %.4f%s (%d starts): "
                 "the best has %s\n",
                 shape_text(shape).c_str(), hand::ns_to_log_seconds(best->moment.t_ns),
                 choice.trials.size() > 1 ? " nor at any other moment tried" : "", best->starts,
                 no_placement_reason(best->placement, limits).c_str());
    return kNoPlacement;
  }
  if (choice.chosen < 0) {
    std::fprintf(stderr,
                 "grip_fit: no placement holds when replayed: %d candidate(s) of the %s tried "
                 "(one line each above); nothing written\n",
                 choice.placed, shape_text(shape).c_str());
    return kNoPlacement;
  }

  const fit::GripTrial& t = choice.trials[static_cast<std::size_t>(choice.chosen)];
  const fit::Placement& p = t.placement;
  const double t_s = hand::ns_to_log_seconds(t.moment.t_ns);
  print_moment(t.moment, log.samples.size(),
               f.at_s        ? "forced by --at"
               : f.no_verify ? "the earliest with a placement"
                             : "the earliest whose placement holds when replayed");
  print_placement(t, shape, limits);
  GripSceneSpec spec = with_candidate(base, t);
  const fit::SupportBox& ped = spec.layout.pedestal;
  const Eigen::Vector3d ped_offset = ped.p_G - t.placement.X_GO.translation();
  std::printf(
      "pedestal %.1f x %.1f x %.1f mm (from %.0f%% of the object's footprint, its sides pushed "
      "out as the grip leaves room; centre %.1f, %.1f mm off the object's), top z %.5f m%s; "
      "hand %.1f mm %s it (%s)\n",
      ped.size_m.x() * 1e3, ped.size_m.y() * 1e3, ped.size_m.z() * 1e3,
      spec.layout.footprint_share * 100.0, ped_offset.x() * 1e3, ped_offset.y() * 1e3,
      spec.layout.object_lowest_z_m, spec.layout.table ? ", on a table" : ", on the floor",
      std::abs(spec.layout.pedestal_clearance_m) * 1e3,
      spec.layout.pedestal_clearance_m >= 0.0 ? "clear of" : "INSIDE",
      name_of(spec.layout.pedestal_nearest_link).c_str());
  const fit::HandApproach& approach = t.approach;
  std::printf(
      "approach: the hand starts %.1f mm from the object; nearest before the moment "
      "%.2f mm (%s at t_s %.4f)%s\n",
      approach.first_m * 1e3, approach.nearest_m * 1e3, name_of(approach.nearest_link).c_str(),
      hand::ns_to_log_seconds(approach.nearest_t_ns),
      -approach.nearest_m > limits.max_depth_m ? ": the hand passes through its place before" : "");
  if (t.replayed)
    std::printf("replayed: %s\n", fit::replay_figures(t.run).c_str());
  else
    std::printf("replayed: no (--no-verify): the hand may push it away instead of grasping it\n");

  const std::string log_name = std::filesystem::path(f.log_path).filename().string();
  char line[320];
  spec.comments.push_back("Made by grip_fit from " + log_name + ": the " + shape_text(shape) +
                          " placed inside the recorded grip");
  std::snprintf(line, sizeof line, "at t_s %.4f%s, %s, on a static pedestal below it on a table.",
                t_s,
                f.at_s        ? " (--at)"
                : f.no_verify ? " (the earliest moment of the log's grip with a placement)"
                              : " (the earliest moment of the log's grip whose placement holds)",
                p.rest_name);
  spec.comments.push_back(line);
  std::snprintf(line, sizeof line,
                "The thumb and %d other finger(s) within %.1f mm of its surface, %d opposing the "
                "thumb; deepest link %s, %.2f mm in.",
                p.touching_fingers - 1, limits.contact_m * 1e3, p.gripping_fingers,
                name_of(p.deepest_link).c_str(), p.deepest_m * 1e3);
  spec.comments.push_back(line);
  if (t.replayed)
    spec.comments.push_back("Replayed on the log: " + fit::replay_figures(t.run) + ".");
  else
    spec.comments.push_back("Not replayed (--no-verify).");
  spec.comments.push_back("Run: physics_node --offline --scene " + f.out_path + " --log " +
                          f.log_path + " --out DIR");
  write_grip_scene(spec, f.out_path);
  std::printf("wrote %s\n", f.out_path.c_str());
  return 0;
}

}  // namespace
}  // namespace vcockpit

int main(int argc, char** argv) {
  using namespace vcockpit;
  CLI::App app(
      "grip_fit: places an object inside the grip a glove log records (moments across its "
      "first closed stretch, earliest first), replays the log on each candidate and writes the "
      "first scene whose object the hand grasps and holds, on a pedestal. Exit 0: written; 1: no "
      "placement, or none holds when replayed (nothing written); 2: bad flags or files.");
  Flags flags;
  add_flags(app, flags);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kBadInput;
  }
  try {
    return run(flags);
  } catch (const std::exception& e) {
    // flags the parser could not check, the loaders' file:line errors (hand, log, cockpit), I/O
    std::fprintf(stderr, "grip_fit: error: %s\n", e.what());
  }
  return kBadInput;
}
