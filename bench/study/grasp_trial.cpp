#include "bench/study/grasp_trial.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <stdexcept>

#include "glove_driver/glove/gesture_script.hpp"
#include "hand/config/hand_yaml.hpp"
#include "hand/sample_validator.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/hand_timeline.hpp"
#include "physics_node/physics/grasp.hpp"
#include "physics_node/physics/grasp_tracker.hpp"

namespace vcockpit::study {
namespace {

// The shipped cockpit, read once per process and copied for each trial (a copy shares the
// models' meshes, which nothing changes): reading it costs 0.11 s of model files, and a study
// runs 1,554 trials on worker threads.
physics::Scene shipped_scene(const std::string& source_dir) {
  static std::mutex mutex;
  static std::map<std::string, physics::Scene> read;
  std::lock_guard lock(mutex);
  auto it = read.find(source_dir);
  if (it == read.end())
    it = read.emplace(source_dir, load_scene(source_dir + "/config/cockpit.yaml")).first;
  return it->second;
}

constexpr double kLift_m = 0.05;
constexpr double kPlaceTolerance_m = 0.03;
constexpr double kDropFall_m = 0.02;
constexpr int64_t kDropWindow_ns = 500'000'000;
constexpr int64_t kSettle_ns = 1'000'000'000;  // after the log: the object comes to rest
constexpr int64_t kTimelineEvery_ns = 10'000'000;

// The mean flexion of the four fingers (rad): how closed the pilot's hand is.
double mean_finger_flexion_rad(const hand::JointAngles& q) {
  double sum = 0.0;
  for (int f = 1; f < hand::kFingerCount; ++f)
    sum += physics::finger_flexion_rad(q, static_cast<physics::Finger>(f));
  return sum / (hand::kFingerCount - 1);
}

// [from, to] (the samples' time) while the fingers are closed: the flexion above
// halfway between its least and its most over the samples.
std::pair<int64_t, int64_t> closed_span_ns(const std::vector<hand::GloveSample>& samples) {
  double lo = 1e9, hi = -1e9;
  for (const auto& s : samples) {
    const double f = mean_finger_flexion_rad(s.joints_rad);
    lo = std::min(lo, f);
    hi = std::max(hi, f);
  }
  const double half = 0.5 * (lo + hi);
  int64_t from = -1, to = -1;
  for (const auto& s : samples) {
    if (mean_finger_flexion_rad(s.joints_rad) < half) continue;
    if (from < 0) from = s.t_ns;
    to = s.t_ns;
  }
  return {from, to};
}

}  // namespace

TrialResult run_trial(const std::string& source_dir, const StudyObject& study_object,
                      const Rule& rule, const TrialVariation& variation,
                      const std::function<void(const TimelineRow&)>& timeline) {
  physics::Scene scene = shipped_scene(source_dir);
  const hand::HandModel right = load_hand_model(source_dir + "/config/" + variation.hand_yaml);
  scene.hands.clear();
  for (const HandScript& h : study_object.hands)
    scene.hands.push_back(h.left ? hand::mirrored(right) : right);
  scene.grasp = rule.params;
  // what the trial measures: the object, or the grasped controls' moving parts
  std::vector<int> targets;
  if (study_object.is_control()) {
    for (const std::string& name : study_object.controls) {
      const int c = scene.find_control(name);
      if (c < 0) throw std::invalid_argument("no control '" + name + "'");
      targets.push_back(scene.controls[static_cast<std::size_t>(c)].body);
    }
  } else {
    const int o = scene.find_object(study_object.object);
    if (o < 0) throw std::invalid_argument("no object '" + study_object.object + "'");
    targets.push_back(o);
  }
  const int object = targets.front();
  int focus = object;  // the timeline's target (a control case has several)
  std::vector<char> is_target(scene.objects.size(), 0);
  for (int t : targets) is_target[static_cast<std::size_t>(t)] = 1;

  // each hand's input: the script, varied, degraded, then the checks the offline runner makes
  std::vector<physics_io::HandSamples> inputs;
  std::pair<int64_t, int64_t> closed{-1, -1};
  for (std::size_t h = 0; h < study_object.hands.size(); ++h) {
    const hand::HandModel& model = scene.hands[h];
    const int side = study_object.hands[h].left ? 1 : 0;
    std::vector<hand::GloveSample> samples = vary_approach(
        glove::script_samples(source_dir + "/config/gestures/" + study_object.hands[h].script, model),
        variation, side, study_object.offset_gone_s(), study_object.approach_end_s, model);
    if (h == 0) closed = closed_span_ns(samples);
    const auto rows = degrade::degrade(std::move(samples), model, degrade_spec(variation));
    hand::SampleValidator validator(model);
    physics_io::HandSamples input{static_cast<int>(h), {}};
    for (const auto& row : rows) {
      if (!row.valid) continue;  // the log reader skips dropout rows
      hand::GloveSample sample = row.sample;
      if (validator.accept(sample)) input.samples.push_back(sample);
    }
    if (input.samples.empty()) throw std::runtime_error("no valid sample");
    inputs.push_back(std::move(input));
  }
  const int64_t t0_ns = physics_io::HandTimeline::first_ns(inputs);
  // the closed span on the world's timeline (world time 0 is the earliest first sample)
  closed.first -= t0_ns;
  closed.second -= t0_ns;
  const int64_t end_ns = physics_io::HandTimeline::span_ns(inputs) + kSettle_ns;

  physics::World world(std::move(scene));
  const std::size_t object_count = world.scene().objects.size();
  const double start_z_m = world.bodies()[object].X_GO.translation().z();
  TrialResult r;
  r.control_case = study_object.is_control();
  std::vector<ControlChange> changes;  // the controls' changes, in order
  std::vector<char> was_held(targets.size(), 0);
  double hand_pen_sum_m = 0.0, object_pen_sum_m = 0.0;
  int hand_pen_steps = 0, object_pen_steps = 0;
  int64_t drop_watch_until_ns = -1;  // a release being watched for a fall
  double drop_from_z_m = 0.0;
  std::vector<physics::HandContact> first_hand;
  std::vector<int> touching_links;  // hand bodies touching the target this step (timeline)
  std::string pending_events;  // for the timeline's next row

  auto step = [&] {
    world.step();
    const int64_t t_ns = world.time_ns();
    const physics::BodyState& body = world.bodies()[object];
    const double z_m = body.X_GO.translation().z();
    for (const auto& c : world.control_events()) {
      const physics::ControlSpec& spec = world.scene().controls[static_cast<std::size_t>(c.control)];
      changes.push_back({spec.name, spec.positions[static_cast<std::size_t>(c.from)].name,
                         spec.positions[static_cast<std::size_t>(c.to)].name});
      char at[32];
      std::snprintf(at, sizeof at, " @%.3f", static_cast<double>(t_ns) * 1e-9);
      r.changes.push_back(spec.name + " " + changes.back().from + "->" + changes.back().to + at);
    }
    for (const auto& e : world.step_events()) {
      if (!is_target[static_cast<std::size_t>(e.object)]) {
        ++r.other_events;
        continue;
      }
      if (timeline) {
        if (!pending_events.empty()) pending_events += "; ";
        pending_events += std::string(e.grasp ? "grasp h" : "release h") + std::to_string(e.hand_id) +
                          ": " + physics::grasp_reason_name(e.reason);
      }
      if (e.grasp) {
        if (r.grasps++ == 0) r.first_grasp_s = static_cast<double>(t_ns) * 1e-9;
        drop_watch_until_ns = -1;
      } else {
        ++r.releases;
        drop_watch_until_ns = t_ns + kDropWindow_ns;
        drop_from_z_m = z_m;
      }
    }
    // the grasp state of each target (held by any hand or not) switching while the fingers are
    // closed
    for (std::size_t k = 0; k < targets.size(); ++k) {
      const bool held = world.bodies()[static_cast<std::size_t>(targets[k])].held();
      if (held != static_cast<bool>(was_held[k]) && t_ns >= closed.first && t_ns <= closed.second)
        ++r.switches_closed;
      was_held[k] = held;
    }
    if (drop_watch_until_ns >= 0 && !r.control_case) {
      if (z_m < drop_from_z_m - kDropFall_m) {
        ++r.drops;
        drop_watch_until_ns = -1;
      } else if (t_ns > drop_watch_until_ns) {
        drop_watch_until_ns = -1;
      }
    }
    if (r.grasps == 0) r.max_speed_before_grasp_mps = std::max(r.max_speed_before_grasp_mps, body.v_G.norm());
    if (body.held()) r.lift_m = std::max(r.lift_m, z_m - start_z_m);
    // penetration: the deepest contact of a hand link in the object, and of the object in
    // anything else, this step
    double hand_deepest_m = 0.0, object_deepest_m = 0.0;
    bool hand_touch = false, object_touch = false;
    first_hand.clear();
    touching_links.clear();
    // the target the timeline follows: a held one, else the one it followed while the first
    // hand still touches it, else one the first hand touches, else the last one
    if (timeline) {
      int touched = -1;
      bool still_touched = false;
      for (const auto& a : world.contacts()) {
        const int body = a.contact.body_a;
        const int link = a.contact.body_b - static_cast<int>(object_count);
        if (body >= static_cast<int>(object_count) || !is_target[static_cast<std::size_t>(body)] ||
            link < 0 || link >= hand::kLinkCount)
          continue;
        if (touched < 0) touched = body;
        still_touched = still_touched || body == focus;
      }
      if (touched >= 0 && !still_touched) focus = touched;
      for (const int t : targets)
        if (world.bodies()[static_cast<std::size_t>(t)].held()) focus = t;
    }
    for (const auto& a : world.contacts()) {
      const auto& c = a.contact;
      // a target is always body_a against a hand link (the objects come first)
      const bool a_target = c.body_a < static_cast<int>(object_count) &&
                            is_target[static_cast<std::size_t>(c.body_a)];
      const bool b_target = c.body_b < static_cast<int>(object_count) &&
                            is_target[static_cast<std::size_t>(c.body_b)];
      if (!a_target && !b_target) continue;
      const int target = a_target ? c.body_a : c.body_b;
      const int other = a_target ? c.body_b : c.body_a;
      if (other >= static_cast<int>(object_count)) {
        hand_touch = true;
        hand_deepest_m = std::max(hand_deepest_m, c.depth_m);
        const int body_in_hands = other - static_cast<int>(object_count);
        if (target == focus) touching_links.push_back(body_in_hands);
        if (target == focus && body_in_hands < hand::kLinkCount) {  // the first hand's link
          physics::HandContact hc;
          hc.link = static_cast<physics::Link>(body_in_hands);
          hc.p_G = c.p_G;
          hc.n_G = -c.n_G;
          hc.F_G = -a.F_on_b_G;
          first_hand.push_back(hc);
        }
      } else if (!r.control_case) {  // a control's part rests in its mount: not measured
        object_touch = true;
        object_deepest_m = std::max(object_deepest_m, c.depth_m);
      }
    }
    if (hand_touch) {
      if (r.first_contact_s < 0) r.first_contact_s = static_cast<double>(t_ns) * 1e-9;
      r.hand_pen_max_m = std::max(r.hand_pen_max_m, hand_deepest_m);
      hand_pen_sum_m += hand_deepest_m;
      ++hand_pen_steps;
    }
    if (object_touch) {
      r.object_pen_max_m = std::max(r.object_pen_max_m, object_deepest_m);
      object_pen_sum_m += object_deepest_m;
      ++object_pen_steps;
    }
    if (timeline && t_ns % kTimelineEvery_ns == 0) {
      const auto& o = world.scene().objects[static_cast<std::size_t>(focus)];
      const physics::BodyState& seen = world.bodies()[static_cast<std::size_t>(focus)];
      const physics::GraspCheck check = physics::evaluate_grasp(
          first_hand.data(), first_hand.size(), seen.X_GO.translation(), o.mass_kg,
          world.scene().gravity_mps2, world.scene().grasp, seen.held(),
          world.grasp_joint_of(focus));
      TimelineRow row;
      row.t_s = static_cast<double>(t_ns) * 1e-9;
      row.target = o.name;
      row.links = check.links_in_contact;
      row.residual_force_N = check.residual_force_N;
      row.residual_torque_Nm = check.residual_torque_Nm;
      row.held = seen.held();
      row.verdict = physics::grasp_reason_name(check.verdict);
      row.opposition_deg = check.best_opposition_deg;
      row.x_m = seen.X_GO.translation().x();
      row.y_m = seen.X_GO.translation().y();
      row.z_m = seen.X_GO.translation().z();
      for (int h = 0; h < static_cast<int>(world.scene().hands.size()); ++h) {
        const auto& proxy_X_GL = world.X_GL(h);
        const auto& tracked_X_GL = world.tracked_X_GL(h);
        for (int l = 0; l < hand::kLinkCount; ++l) {
          const auto k = static_cast<std::size_t>(l);
          const double lag_mm =
              1e3 * (proxy_X_GL[k].translation() - tracked_X_GL[k].translation()).norm();
          if (lag_mm <= row.lag_mm) continue;
          row.lag_mm = lag_mm;
          row.lag_link = "h" + std::to_string(h) + " " +
                         std::string(hand::link_name(static_cast<hand::Link>(l)));
        }
      }
      if (row.lag_mm < 0.005) row.lag_link.clear();  // (none off, to the column's 0.01 mm)
      std::sort(touching_links.begin(), touching_links.end());
      touching_links.erase(std::unique(touching_links.begin(), touching_links.end()), touching_links.end());
      for (const int l : touching_links) {
        if (!row.touching.empty()) row.touching += "; ";
        row.touching += "h" + std::to_string(l / hand::kLinkCount) + " " +
                        std::string(hand::link_name(static_cast<hand::Link>(l % hand::kLinkCount)));
      }
      row.events = std::move(pending_events);
      pending_events.clear();
      timeline(row);
    }
  };
  physics_io::HandTimeline replay(world, inputs, physics_io::InputTiming{}, end_ns, true);
  replay.run(step);

  const physics::BodyState& body = world.bodies()[object];
  r.simulated_s = static_cast<double>(world.time_ns()) * 1e-9;
  r.place_error_m = (body.X_GO.translation() - study_object.place_G).norm();
  r.grasped = r.grasps > 0;
  if (r.control_case) {
    // operated as the gesture means: exactly its changes, in order, and nothing else
    r.lift_m = 0.0;
    r.place_error_m = 0.0;
    r.control_changes = static_cast<int>(changes.size());
    r.success = changes.size() == study_object.changes.size();
    for (std::size_t k = 0; r.success && k < changes.size(); ++k) {
      const ControlChange& a = changes[k];
      const ControlChange& b = study_object.changes[k];
      r.success = a.control == b.control && a.from == b.from && a.to == b.to;
    }
    r.success = r.success && r.other_events == 0 && !body.held();
  } else {
    r.lifted = r.lift_m >= kLift_m;
    r.placed = !body.held() && r.place_error_m <= kPlaceTolerance_m;
    r.success = r.grasped && r.lifted && r.placed;
  }
  if (r.success) {
    r.failure.clear();
  } else if (!r.grasped) {
    r.failure = "never grasped";
  } else if (r.control_case) {
    r.failure = "wrong changes";
  } else if (!r.lifted) {
    r.failure = "lost while held";
  } else if (r.drops > 0) {
    r.failure = "dropped";
  } else {
    r.failure = "misplaced";
  }
  if (r.grasped && r.first_contact_s >= 0) r.convergence_s = r.first_grasp_s - r.first_contact_s;
  r.closed_s = closed.first >= 0 ? static_cast<double>(closed.second - closed.first) * 1e-9 : 0.0;
  r.switch_rate_hz = r.closed_s > 0 ? r.switches_closed / r.closed_s : 0.0;
  r.hand_pen_mean_m = hand_pen_steps > 0 ? hand_pen_sum_m / hand_pen_steps : 0.0;
  r.object_pen_mean_m = object_pen_steps > 0 ? object_pen_sum_m / object_pen_steps : 0.0;
  return r;
}

}  // namespace vcockpit::study
