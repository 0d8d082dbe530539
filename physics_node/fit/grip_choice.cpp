#include "physics_node/fit/grip_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace vcockpit::fit {
namespace {

// Why an unaccepted placement misses (the short form; grip_fit prints the figures).
std::string miss_reason(const Placement& p, const FitLimits& limits) {
  std::string why;
  const auto add = [&](const std::string& s) { why += (why.empty() ? "" : ", ") + s; };
  char text[160];
  if (!p.thumb_touches) {
    std::snprintf(text, sizeof text, "thumb %.1f mm off", p.finger_distance_m[0] * 1e3);
    add(text);
  }
  const int others = p.touching_fingers - (p.thumb_touches ? 1 : 0);
  if (others < limits.other_fingers || p.gripping_fingers < limits.opposing_fingers) {
    std::snprintf(text, sizeof text, "%d other finger(s) touching, %d opposing", others,
                  p.gripping_fingers);
    add(text);
  }
  if (p.deepest_m > limits.max_depth_m) {
    std::snprintf(text, sizeof text, "%s %.1f mm in",
                  std::string(hand::link_name(p.deepest_link)).c_str(), p.deepest_m * 1e3);
    add(text);
  }
  return why;
}

}  // namespace

GripChoice choose_grip(const hand::HandModel& model, const std::vector<hand::GloveSample>& samples,
                       const physics::Shape& shape, const GripChoiceOptions& options,
                       const SceneFor& scene_for, const TrialReport& report) {
  GripChoice choice;
  choice.stretch = first_closed_stretch(model, samples, options.moment_rule);
  if (!choice.stretch) return choice;
  const ClosedStretch& stretch = *choice.stretch;
  const int64_t opening_ns = samples[stretch.opening].t_ns;
  choice.opening_s = hand::ns_to_log_seconds(opening_ns);

  std::vector<Moment> moments;
  if (options.at_ns) {
    moments.push_back(*moment_at(model, samples, *options.at_ns, options.moment_rule));
  } else {
    for (std::size_t i : moments_across(stretch, samples, options.moment_step_s))
      moments.push_back(describe_moment(model, samples, i, stretch, options.moment_rule));
  }

  const auto done = [&](GripTrial&& trial) {
    choice.trials.push_back(std::move(trial));
    if (report) report(choice.trials.back());
    return choice.trials.back().holds;
  };
  // The recorded hands up to the last moment, once, at least approach_spacing_s apart (a 1 kHz
  // log has thousands; the approach only asks whether the hand sweeps through the object)
  std::size_t last_index = 0;
  for (const Moment& moment : moments)
    last_index = std::max(last_index, moment.index);
  std::vector<std::size_t> kept;  // sample indices
  const int64_t spacing_ns = std::llround(options.approach_spacing_s * 1e9);
  for (std::size_t i = 0; i <= last_index && i < samples.size(); ++i)
    if (kept.empty() || samples[i].t_ns - samples[kept.back()].t_ns >= spacing_ns)
      kept.push_back(i);
  std::vector<RecordedHand> recorded;
  recorded.reserve(kept.size());
  for (std::size_t i : kept)
    recorded.push_back({samples[i].t_ns, grip_hand_at(model, samples[i])});
  for (const Moment& moment : moments) {
    const GripHand grip = grip_hand_at(model, samples[moment.index]);
    // the kept hands before the moment (the first alone when the moment is the first sample)
    std::vector<RecordedHand> before;
    for (std::size_t k = 0; k < kept.size() && (kept[k] < moment.index || k == 0); ++k)
      before.push_back(recorded[k]);
    const FitResult fit = fit_object_in_grip(grip, shape, options.limits, before);
    if (fit.accepted.empty()) {
      GripTrial trial;
      trial.moment = moment;
      trial.grip = grip;
      trial.placement = fit.best;
      trial.starts = fit.starts;
      trial.why =
          "no placement in the grip (best miss: " + miss_reason(fit.best, options.limits) + ")";
      done(std::move(trial));
      continue;
    }
    std::vector<int> per_rest;
    for (std::size_t k = 0; k < fit.accepted.size(); ++k) {
      const auto rest = static_cast<std::size_t>(fit.accepted[k].rest_index);
      if (per_rest.size() <= rest) per_rest.resize(rest + 1, 0);
      if (++per_rest[rest] > options.per_orientation) continue;
      GripTrial trial;
      trial.moment = moment;
      trial.grip = grip;
      trial.placed = true;
      trial.placement = fit.accepted[k];
      trial.rank = static_cast<int>(k) + 1;
      trial.of = static_cast<int>(fit.accepted.size());
      trial.starts = fit.starts;
      ++choice.placed;
      trial.approach = hand_approach(before, shape, trial.placement.X_GO);
      try {
        trial.layout = lay_out_supports(grip, shape, trial.placement.X_GO, options.layout_rule);
      } catch (const std::invalid_argument& e) {
        trial.why = std::string("no scene: ") + e.what();
        done(std::move(trial));
        continue;
      }
      if (!options.verify) {
        trial.holds = true;
        choice.chosen = static_cast<int>(choice.trials.size());
        done(std::move(trial));
        return choice;
      }
      const physics::Scene scene = scene_for(trial);
      const int object = scene.find_object(options.object_name);
      const int support = scene.find_object(options.support_name);
      if (object < 0 || support < 0)
        throw std::invalid_argument("choose_grip: the scene has no '" + options.object_name +
                                    "' or '" + options.support_name + "'");
      physics_io::GripReplayOptions replay;
      replay.settle_s = options.hold.settle_s;
      replay.trace = options.trace_replays;
      // the times in world time, known once the replay has its origin (the first sample)
      const auto times_of = [&](const physics_io::GripReplay& run) {
        return HoldTimes{static_cast<double>(moment.t_ns - run.t0_ns) * 1e-9,
                         static_cast<double>(opening_ns - run.t0_ns) * 1e-9};
      };
      replay.stop = [&](const physics_io::GripReplay& run, double t_s) {
        return hold_already_failed(run, t_s, times_of(run), options.hold);
      };
      trial.run = physics_io::replay_grip(scene, samples, object, support, replay);
      trial.replayed = true;
      const HoldVerdict verdict = judge_hold(trial.run, times_of(trial.run), options.hold);
      trial.holds = verdict.holds;
      trial.why = verdict.why;
      if (trial.holds) choice.chosen = static_cast<int>(choice.trials.size());
      if (done(std::move(trial))) return choice;
    }
  }
  return choice;
}

std::string trial_line(const GripTrial& t) {
  char head[160];
  std::snprintf(head, sizeof head, "t_s %.4f (closure %.0f%%)",
                hand::ns_to_log_seconds(t.moment.t_ns), t.moment.closure_share * 100.0);
  std::string line = head;
  if (!t.placed) return line + ": " + t.why;
  const Eigen::Vector3d p = t.placement.X_GO.translation();
  char pose[200];
  char yaw[40] = "";
  if (t.placement.yaw_free)
    std::snprintf(yaw, sizeof yaw, " (yaw %.0f deg)", t.placement.yaw_rad * 180.0 / M_PI);
  std::snprintf(pose, sizeof pose, " %s%s, result %d of %d at (%.4f, %.4f, %.4f) m",
                t.placement.rest_name, yaw, t.rank, t.of, p.x(), p.y(), p.z());
  line += pose;
  if (t.holds && !t.replayed) return line + ": taken unreplayed (--no-verify)";
  if (t.holds) return line + ": HOLDS: " + fit::replay_figures(t.run);
  if (!t.replayed) return line + ": " + t.why;
  char run[200];
  std::snprintf(run, sizeof run, " [%s%s]", t.run.grasp_s >= 0.0 ? "grasped" : "not grasped",
                t.run.stopped ? ", replay stopped" : "");
  return line + ": " + t.why + run;
}

}  // namespace vcockpit::fit
