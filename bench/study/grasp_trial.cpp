#include "bench/study/grasp_trial.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "glove_driver/glove/gesture_script.hpp"
#include "hand/hand_yaml.hpp"
#include "hand/sample_validator.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/hand_timeline.hpp"
#include "physics_node/physics/grasp.hpp"
#include "physics_node/physics/grasp_tracker.hpp"

namespace vcockpit::study {
namespace {

constexpr double kLift_m = 0.05;
constexpr double kPlaceTolerance_m = 0.03;
constexpr double kDropFall_m = 0.02;
constexpr int64_t kDropWindow_ns = 500'000'000;
constexpr int64_t kSettle_ns = 1'000'000'000;  // after the log: the object comes to rest
constexpr int64_t kTimelineEvery_ns = 10'000'000;

std::vector<hand::GloveSample> script_samples(const std::string& path, const hand::HandModel& hand) {
  const auto script = glove::GestureScript::load(path, hand);
  std::vector<hand::GloveSample> out;
  for (int64_t k = 0;; ++k) {
    const int64_t t_ns = std::llround(static_cast<double>(k) * 1e9 / script.rate_hz());
    if (t_ns > script.duration_ns()) break;
    out.push_back(script.sample_at(t_ns));
  }
  return out;
}

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
  physics::Scene scene = load_scene(source_dir + "/config/cockpit.yaml");
  const hand::HandModel right = load_hand_model(source_dir + "/config/" + variation.hand_yaml);
  scene.hands.clear();
  for (const HandScript& h : study_object.hands)
    scene.hands.push_back(h.left ? hand::mirrored(right) : right);
  scene.grasp = rule.params;
  const int object = scene.find_object(study_object.object);
  if (object < 0) throw std::invalid_argument("no object '" + study_object.object + "'");

  // each hand's input: the script, varied, degraded, then the checks the offline runner makes
  std::vector<physics_io::HandSamples> inputs;
  std::pair<int64_t, int64_t> closed{-1, -1};
  for (std::size_t h = 0; h < study_object.hands.size(); ++h) {
    const hand::HandModel& model = scene.hands[h];
    const int side = study_object.hands[h].left ? 1 : 0;
    std::vector<hand::GloveSample> samples = vary_approach(
        script_samples(source_dir + "/config/gestures/" + study_object.hands[h].script, model),
        variation, side, study_object.approach_end_s, model);
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
  double hand_pen_sum_m = 0.0, object_pen_sum_m = 0.0;
  int hand_pen_steps = 0, object_pen_steps = 0;
  int64_t drop_watch_until_ns = -1;  // a release being watched for a fall
  double drop_from_z_m = 0.0;
  std::vector<physics::HandContact> first_hand;
  bool was_held = false;

  auto step = [&] {
    world.step();
    const int64_t t_ns = world.time_ns();
    const physics::BodyState& body = world.bodies()[object];
    const double z_m = body.X_GO.translation().z();
    for (const auto& e : world.step_events()) {
      if (e.object != object) {
        ++r.other_events;
        continue;
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
    // the grasp state (held by any hand or not) switching while the fingers are closed
    if (body.held() != was_held && t_ns >= closed.first && t_ns <= closed.second) ++r.switches_closed;
    was_held = body.held();
    if (drop_watch_until_ns >= 0) {
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
    for (const auto& a : world.contacts()) {
      const auto& c = a.contact;
      if (c.body_a != object && c.body_b != object) continue;
      const int other = c.body_a == object ? c.body_b : c.body_a;
      if (other >= static_cast<int>(object_count)) {
        hand_touch = true;
        hand_deepest_m = std::max(hand_deepest_m, c.depth_m);
        const int body_in_hands = other - static_cast<int>(object_count);
        if (body_in_hands < hand::kLinkCount) {  // the first hand's link (the object is body_a)
          physics::HandContact hc;
          hc.link = static_cast<physics::Link>(body_in_hands);
          hc.p_G = c.p_G;
          hc.n_G = -c.n_G;
          hc.F_G = -a.F_on_b_G;
          first_hand.push_back(hc);
        }
      } else {
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
      const auto& o = world.scene().objects[object];
      const physics::GraspCheck check = physics::evaluate_grasp(
          first_hand.data(), first_hand.size(), body.X_GO.translation(), o.mass_kg,
          world.scene().gravity_mps2, world.scene().grasp, body.held());
      TimelineRow row;
      row.t_s = static_cast<double>(t_ns) * 1e-9;
      row.links = check.links_in_contact;
      row.residual_force_N = check.residual_force_N;
      row.residual_torque_Nm = check.residual_torque_Nm;
      row.held = body.held();
      row.verdict = physics::grasp_reason_name(check.verdict);
      row.z_m = z_m;
      timeline(row);
    }
  };
  physics_io::HandTimeline replay(world, inputs, physics_io::InputTiming{}, end_ns, true);
  replay.run(step);

  const physics::BodyState& body = world.bodies()[object];
  r.simulated_s = static_cast<double>(world.time_ns()) * 1e-9;
  r.place_error_m = (body.X_GO.translation() - study_object.place_G).norm();
  r.grasped = r.grasps > 0;
  r.lifted = r.lift_m >= kLift_m;
  r.placed = !body.held() && r.place_error_m <= kPlaceTolerance_m;
  r.success = r.grasped && r.lifted && r.placed;
  if (r.grasped && r.first_contact_s >= 0) r.convergence_s = r.first_grasp_s - r.first_contact_s;
  r.closed_s = closed.first >= 0 ? static_cast<double>(closed.second - closed.first) * 1e-9 : 0.0;
  r.switch_rate_hz = r.closed_s > 0 ? r.switches_closed / r.closed_s : 0.0;
  r.hand_pen_mean_m = hand_pen_steps > 0 ? hand_pen_sum_m / hand_pen_steps : 0.0;
  r.object_pen_mean_m = object_pen_steps > 0 ? object_pen_sum_m / object_pen_steps : 0.0;
  return r;
}

}  // namespace vcockpit::study
