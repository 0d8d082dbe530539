// grasp_study: runs the grasp study's trials (study_cases.hpp, grasp_trial.hpp) and writes them
// as one JSON document: the rules with their parameters, and per trial its rule, object,
// variation and measurements. scripts/study runs it and scripts/study_report.py makes the tables
// and plots of docs/study/ from its output.
//
//   grasp_study --source DIR --out FILE.json [--trials N] [--sweep-trials N] [--seed S]
//               [--jobs J] [--plain] [--timeline-dir DIR [--timeline-object NAME]
//               [--timeline-index N]]
//
// Every rule runs the same trials (trial i of an object has the same seed, so the same hand,
// approach and input, under each rule): the rules are compared on paired trials.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "bench/study/grasp_trial.hpp"
#include "physics_node/config/scene_config.hpp"

namespace vcockpit::study {
namespace {

struct Work {
  std::size_t rule = 0;
  std::size_t object = 0;
  int index = 0;  // the trial's number for its object
};

uint64_t trial_seed(uint64_t base, std::size_t object, int index) {
  return base * 1'000'003ULL + object * 10'007ULL + static_cast<uint64_t>(index);
}

nlohmann::json params_json(const physics::GraspParams& p) {
  return {{"xi_N", p.xi_N},
          {"eta_Nm", p.eta_Nm},
          {"alpha0_deg", p.alpha0_deg},
          {"gesture_rule", p.gesture_rule == physics::GestureRule::kProject ? "project"
                           : p.gesture_rule == physics::GestureRule::kPaper ? "paper"
                                                                            : "none"},
          {"hold_rule", p.hold_rule == physics::HoldRule::kTrackedGrip ? "grip" : "test"},
          {"min_contacts", p.min_contacts},
          {"exit_min_contacts", p.exit_min_contacts},
          {"exit_scale", p.exit_scale},
          {"exit_alpha_margin_deg", p.exit_alpha_margin_deg},
          {"min_hold_s", p.min_hold_s},
          {"release_delay_s", p.release_delay_s},
          {"regrab_cooldown_s", p.regrab_cooldown_s},
          {"release_opening_share", p.release_opening_share},
          {"release_opening_deg", p.release_opening_deg},
          {"release_gap_m", p.release_gap_m},
          {"palm_opposition", p.palm_opposition}};
}

nlohmann::json result_json(const TrialResult& r) {
  return {{"control_case", r.control_case},
          {"control_changes", r.control_changes},
          {"changes", r.changes},
          {"success", r.success},
          {"failure", r.failure},
          {"grasped", r.grasped},
          {"lifted", r.lifted},
          {"placed", r.placed},
          {"grasps", r.grasps},
          {"releases", r.releases},
          {"other_events", r.other_events},
          {"first_contact_s", r.first_contact_s},
          {"first_grasp_s", r.first_grasp_s},
          {"convergence_s", r.convergence_s},
          {"closed_s", r.closed_s},
          {"switches_closed", r.switches_closed},
          {"switch_rate_hz", r.switch_rate_hz},
          {"hand_pen_max_mm", r.hand_pen_max_m * 1e3},
          {"hand_pen_mean_mm", r.hand_pen_mean_m * 1e3},
          {"object_pen_max_mm", r.object_pen_max_m * 1e3},
          {"object_pen_mean_mm", r.object_pen_mean_m * 1e3},
          {"drops", r.drops},
          {"lift_mm", r.lift_m * 1e3},
          {"place_error_mm", r.place_error_m * 1e3},
          {"max_speed_before_grasp_mps", r.max_speed_before_grasp_mps}};
}

nlohmann::json variation_json(const TrialVariation& v) {
  auto vec = [](const Eigen::Vector3d& x) { return nlohmann::json{x.x(), x.y(), x.z()}; };
  return {{"seed", v.seed},
          {"hand_size", v.hand_size},
          {"input", v.input},
          {"grip_closure_s", v.grip_closure_s},
          {"aperture_scale", v.aperture_scale},
          {"approach_offset_right_m", vec(v.approach_offset_G[0])},
          {"approach_offset_left_m", vec(v.approach_offset_G[1])}};
}

// The file appears whole or not at all.
void write_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << text;
    if (!out.flush()) throw std::runtime_error("cannot write " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

int run(int argc, char** argv) {
  CLI::App app{"grasp_study: the grasp rules compared on seeded trials"};
  std::string source_dir = ".";
  std::string out_path;
  std::string timeline_dir;
  int trials = 50;
  int sweep_trials = 12;
  uint64_t seed = 1;
  unsigned jobs = std::max(1u, std::thread::hardware_concurrency());
  app.add_option("--source", source_dir, "the source tree (config/ is read from it)")
      ->check(CLI::ExistingDirectory);
  app.add_option("--out", out_path, "the trials, as JSON")->required();
  app.add_option("--trials", trials, "trials per object for each compared rule")
      ->check(CLI::Range(1, 10000));
  app.add_option("--sweep-trials", sweep_trials, "trials per object for each sweep point")
      ->check(CLI::Range(0, 10000));
  app.add_option("--seed", seed, "the study's seed (the same seed, the same trials)");
  app.add_option("--jobs", jobs, "trials run at once")->check(CLI::Range(1u, 64u));
  app.add_option("--timeline-dir", timeline_dir,
                 "write one trial's timeline under each compared rule here (CSV)");
  std::string timeline_object = "cup";
  int timeline_index = 0;
  app.add_option("--timeline-object", timeline_object, "the timeline trial's object");
  app.add_option("--timeline-index", timeline_index, "... and its number")
      ->check(CLI::NonNegativeNumber);
  bool plain = false;
  std::vector<std::string> only_rules;
  app.add_option("--rules", only_rules,
                 "only these compared rules (strict, relaxed, relaxed_gesture, default, "
                 "default_paper_gesture); default: all")
      ->delimiter(',');
  std::vector<std::string> only_objects;
  app.add_option("--objects", only_objects, "only these objects or control cases; default: all")
      ->delimiter(',');
  app.add_flag("--plain", plain,
               "no variation: each gesture as scripted, 50th-percentile hand, clean input (one "
               "trial per object and rule)");
  CLI11_PARSE(app, argc, argv);
  if (plain) trials = 1;
  const auto variation_of = [&](std::size_t object, int index) {
    return plain ? plain_variation() : draw_variation(trial_seed(seed, object, index));
  };

  const physics::Scene shipped = load_scene(source_dir + "/config/cockpit.yaml");
  std::vector<Rule> rules = compared_rules(shipped.grasp);
  if (!only_rules.empty()) {
    std::vector<Rule> kept;
    for (const Rule& r : rules)
      if (std::find(only_rules.begin(), only_rules.end(), r.name) != only_rules.end()) kept.push_back(r);
    if (kept.size() != only_rules.size()) throw std::invalid_argument("--rules: an unknown rule");
    rules = kept;
  }
  const std::size_t compared = rules.size();
  if (sweep_trials > 0) {
    for (auto& r : alpha0_sweep(shipped.grasp)) rules.push_back(r);
    for (auto& r : xi_sweep(shipped.grasp)) rules.push_back(r);
  }
  const auto& objects = study_objects();
  std::size_t timeline_of = objects.size();  // the timeline trial's object
  for (std::size_t o = 0; o < objects.size(); ++o)
    if (objects[o].object == timeline_object) timeline_of = o;
  if (timeline_of == objects.size())
    throw std::invalid_argument("--timeline-object: no object '" + timeline_object + "'");
  std::vector<Work> work;
  for (std::size_t r = 0; r < rules.size(); ++r) {
    const int n = r < compared ? trials : sweep_trials;
    for (std::size_t o = 0; o < objects.size(); ++o) {
      if (!only_objects.empty() &&
          std::find(only_objects.begin(), only_objects.end(), objects[o].object) == only_objects.end())
        continue;
      for (int i = 0; i < n; ++i) work.push_back({r, o, i});
    }
  }
  std::vector<TrialResult> results(work.size());
  std::vector<std::string> errors(work.size());
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> done{0};
  std::mutex print;
  const auto t_start = std::chrono::steady_clock::now();
  auto worker = [&] {
    for (std::size_t k = next++; k < work.size(); k = next++) {
      const Work& w = work[k];
      const TrialVariation v = variation_of(w.object, w.index);
      try {
        results[k] = run_trial(source_dir, objects[w.object], rules[w.rule], v);
      } catch (const std::exception& e) {
        errors[k] = e.what();
      }
      const std::size_t n = ++done;
      if (n % 50 == 0 || n == work.size()) {
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
        std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "grasp_study: %zu of %zu trials (%.0f s)\n", n, work.size(), s);
      }
    }
  };
  std::vector<std::thread> threads;
  for (unsigned j = 0; j < jobs; ++j) threads.emplace_back(worker);
  for (auto& t : threads) t.join();
  for (std::size_t k = 0; k < work.size(); ++k) {
    if (!errors[k].empty()) {
      std::fprintf(stderr, "grasp_study: trial %d of %s under %s: %s\n", work[k].index,
                   objects[work[k].object].object.c_str(), rules[work[k].rule].name.c_str(),
                   errors[k].c_str());
      return 1;
    }
  }

  nlohmann::json doc;
  doc["seed"] = seed;
  doc["plain"] = plain;
  doc["trials_per_object"] = trials;
  doc["sweep_trials_per_object"] = sweep_trials;
  doc["strict"] = {{"xi_N", kStrictXi_N}, {"eta_Nm", kStrictEta_Nm}};
  doc["wall_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  for (const Rule& r : rules)
    doc["rules"].push_back({{"name", r.name}, {"group", r.group}, {"value", r.value},
                            {"params", params_json(r.params)}});
  for (const StudyObject& o : objects) {
    nlohmann::json hands = nlohmann::json::array();
    for (const auto& h : o.hands) hands.push_back(h.script);
    doc["objects"].push_back({{"name", o.object}, {"scripts", hands}});
  }
  doc["trials"] = nlohmann::json::array();
  for (std::size_t k = 0; k < work.size(); ++k) {
    const Work& w = work[k];
    doc["trials"].push_back({{"rule", rules[w.rule].name},
                             {"object", objects[w.object].object},
                             {"index", w.index},
                             {"variation", variation_json(variation_of(w.object, w.index))},
                             {"result", result_json(results[k])}});
  }
  write_atomically(out_path, doc.dump(1) + "\n");

  if (!timeline_dir.empty()) {
    std::filesystem::create_directories(timeline_dir);
    for (std::size_t r = 0; r < compared; ++r) {
      std::string csv =
          "t_s,target,links,residual_force_N,residual_torque_Nm,held,verdict,opposition_deg,"
          "x_m,y_m,z_m,lag_mm,lag_link,touching,events\n";
      run_trial(source_dir, objects[timeline_of], rules[r], variation_of(timeline_of, timeline_index),
                [&](const TimelineRow& row) {
                  char line[200];
                  std::snprintf(line, sizeof line, "%.3f,", row.t_s);
                  csv += line;
                  csv += row.target + ",";
                  std::snprintf(line, sizeof line, "%d,%.4f,%.5f,%d,%s,%.1f,%.5f,%.5f,%.5f,%.2f,",
                                row.links, row.residual_force_N, row.residual_torque_Nm,
                                row.held ? 1 : 0, row.verdict.c_str(), row.opposition_deg, row.x_m,
                                row.y_m, row.z_m, row.lag_mm);
                  csv += line;
                  csv += "\"" + row.lag_link + "\",";
                  csv += "\"" + row.touching + "\",\"" + row.events + "\"\n";
                });
      write_atomically(timeline_dir + "/timeline_" + rules[r].name + ".csv", csv);
    }
  }
  std::fprintf(stderr, "grasp_study: %zu trials -> %s\n", work.size(), out_path.c_str());
  return 0;
}

}  // namespace
}  // namespace vcockpit::study

int main(int argc, char** argv) {
  try {
    return vcockpit::study::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grasp_study: %s\n", e.what());
    return 1;
  }
}
