#include "physics_node/fit/hold_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vcockpit::fit {
namespace {

using physics::GraspReason;

bool lets_go(GraspReason reason) {
  return reason == GraspReason::kHandOpened || reason == GraspReason::kThumbLeft ||
         reason == GraspReason::kFingersLeft;
}

// A release that counts (rule 2): the first after the grasp, before the log's end.
bool counted_release(const physics_io::GripReplay& run) {
  return run.release_s >= 0.0 && run.release_s <= run.last_sample_s;
}

// The time by which rule 1 wants the grasp.
double grasp_deadline_s(const HoldTimes& times, const HoldRule& rule) {
  return std::min(times.moment_s + rule.grasp_within_s, times.opening_s);
}

// Rules 2-5 on the figures so far ("" when none is broken yet).
std::string broken_rule(const physics_io::GripReplay& run, const HoldTimes& times,
                        const HoldRule& rule) {
  char text[240];
  if (run.deepest_below_support_m > rule.max_below_support_m) {
    std::snprintf(text, sizeof text,
                  "%s %.1f mm below the pedestal's top at %.3f s (limit %.0f mm)",
                  run.grasp_s < 0.0 ? "not grasped (yet), off its pedestal:"
                  : run.deepest_below_support_at_s < run.grasp_s ? "pushed off before the grasp:"
                  : run.release_s >= 0.0 && run.deepest_below_support_at_s >= run.release_s
                      ? "fell when let go:"
                      : "carried down while held:",
                  run.deepest_below_support_m * 1e3, run.deepest_below_support_at_s,
                  rule.max_below_support_m * 1e3);
    return text;
  }
  if (run.fastest_free_horizontal_mps > rule.max_free_horizontal_mps) {
    std::snprintf(text, sizeof text, "moved %.2f m/s free at %.3f s (limit %.2f m/s)",
                  run.fastest_free_horizontal_mps, run.fastest_free_at_s,
                  rule.max_free_horizontal_mps);
    return text;
  }
  if (counted_release(run)) {
    if (!lets_go(run.release_reason)) {
      std::snprintf(text, sizeof text, "let go at %.3f s for %s, not the hand letting go",
                    run.release_s, physics::grasp_reason_name(run.release_reason));
      return text;
    }
    if (run.release_s <= times.opening_s) {
      std::snprintf(text, sizeof text, "let go at %.3f s (%s) before the hand opens (at %.3f s)",
                    run.release_s, physics::grasp_reason_name(run.release_reason), times.opening_s);
      return text;
    }
  }
  if (run.deepest_link_in_object_m > rule.max_link_depth_m ||
      run.deepest_link_in_static_m > rule.max_link_depth_m) {
    std::snprintf(text, sizeof text,
                  "a hand link %.2f mm into the object, %.2f mm into a static one (limit %.1f mm)",
                  run.deepest_link_in_object_m * 1e3, run.deepest_link_in_static_m * 1e3,
                  rule.max_link_depth_m * 1e3);
    return text;
  }
  return "";
}

// Rule 1 at world time t_s ("" while it may still hold).
std::string not_grasped(const physics_io::GripReplay& run, double t_s, const HoldTimes& times,
                        const HoldRule& rule) {
  const double deadline_s = grasp_deadline_s(times, rule);
  char text[200];
  if (run.grasp_s < 0.0 && t_s > deadline_s) {
    std::snprintf(text, sizeof text,
                  "not grasped by %.3f s (within %.1f s of the moment, before the hand opens at "
                  "%.3f s)",
                  deadline_s, rule.grasp_within_s, times.opening_s);
    return text;
  }
  if (run.grasp_s > deadline_s) {
    std::snprintf(text, sizeof text,
                  "grasped only at %.3f s (wanted within %.1f s of the moment, before the hand "
                  "opens at %.3f s)",
                  run.grasp_s, rule.grasp_within_s, times.opening_s);
    return text;
  }
  return "";
}

}  // namespace

HoldVerdict judge_hold(const physics_io::GripReplay& run, const HoldTimes& times,
                       const HoldRule& rule) {
  HoldVerdict v;
  v.why = broken_rule(run, times, rule);
  if (v.why.empty()) v.why = not_grasped(run, INFINITY, times, rule);
  v.holds = v.why.empty();
  return v;
}

bool hold_already_failed(const physics_io::GripReplay& run, double t_s, const HoldTimes& times,
                         const HoldRule& rule) {
  return !broken_rule(run, times, rule).empty() || !not_grasped(run, t_s, times, rule).empty();
}

std::string replay_figures(const physics_io::GripReplay& run) {
  char text[400];
  char grasp[48] = "no grasp", release[96] = "no release";
  if (run.grasp_s >= 0.0) std::snprintf(grasp, sizeof grasp, "GRASP %.3f s", run.grasp_s);
  if (run.release_s >= 0.0)
    std::snprintf(release, sizeof release, "RELEASE %.3f s (%s)", run.release_s,
                  physics::grasp_reason_name(run.release_reason));
  std::snprintf(text, sizeof text,
                "%s, %s; %.1f mm below the pedestal's top at most, fastest free %.3f m/s (at "
                "%.3f s), links %.2f mm into it and %.2f mm into static ones%s",
                grasp, release, run.deepest_below_support_m * 1e3, run.fastest_free_horizontal_mps,
                run.fastest_free_at_s, run.deepest_link_in_object_m * 1e3,
                run.deepest_link_in_static_m * 1e3, run.stopped ? " (replay stopped there)" : "");
  return text;
}

}  // namespace vcockpit::fit
