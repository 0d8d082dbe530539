#include "launcher/console_report.hpp"

#include <cstdio>

namespace vcockpit::rig {

void print_console_report(const RunSummary& s) {
  std::printf("\nvcockpit rig: %s after %.1f s (%s)\n", s.ok ? "done" : "FAILED", s.wall_s,
              s.ended.c_str());
  std::printf("  samples replayed     %llu\n", static_cast<unsigned long long>(s.samples_replayed));
  for (const RunSummary::HandOutcome& h : s.hands) {
    std::printf("  %-5s hand           %llu samples, %u grasp(s), glove lost %llu time(s)\n",
                h.hand_id == 1 ? "left" : "right", static_cast<unsigned long long>(h.samples), h.grasps,
                static_cast<unsigned long long>(h.glove_lost));
  }
  for (const auto& e : s.events) {
    std::printf("  %-7s %-10s %-5s at %.3f s: %s\n", e.grasp ? "GRASP" : "RELEASE", e.object.c_str(),
                e.hand_id == 1 ? "left" : "right",
                e.t_s, e.reason.c_str());
  }
  for (const auto& e : s.control_events) {
    std::printf("  CONTROL %s %s -> %s at %.3f s: %s%s%s\n", e.control.c_str(), e.from.c_str(),
                e.to.c_str(), e.t_s, e.cause.c_str(), e.link.empty() ? "" : " by ", e.link.c_str());
  }
  for (const auto& e : s.systems_events) {
    if (e.kind == "changed") {
      std::printf("  SYSTEM  %s %s -> %s at %.3f s\n", e.name.c_str(), e.from.c_str(), e.to.c_str(), e.t_s);
    } else {
      std::printf("  FAILURE %s %s at %.3f s\n", e.name.c_str(),
                  e.kind == "failure_inserted" ? "inserted" : "cleared", e.t_s);
    }
  }
  for (const auto& p : s.procedures) {
    std::printf("  PROCEDURE %s: %s", p.title.c_str(), p.state.c_str());
    if (p.state != "waiting") std::printf(", %u error(s)", p.errors);
    if (p.started_s >= 0 && p.ended_s >= 0) std::printf(", %.2f s", p.ended_s - p.started_s);
    std::printf("\n");
  }
  std::printf("  frames rendered      %llu, snapshots written %d (%s/frames)\n",
              static_cast<unsigned long long>(s.frames_rendered), s.snapshots_written,
              s.out_dir.c_str());
  std::printf("  physics step rate    %.1f Hz, late steps %llu\n", s.physics_step_rate_hz,
              static_cast<unsigned long long>(s.late_steps));
  std::printf("  glove->frame latency p50 %.1f ms, p99 %.1f ms, max %.1f ms (%zu samples)\n",
              s.latency_p50_ms, s.latency_p99_ms, s.latency_max_ms, s.latency_samples);
  std::printf("    of which: sample age when latched p50 %.1f ms, latch to frame end p50 %.1f ms\n",
              s.age_at_render_start_p50_ms, s.render_p50_ms);
  std::printf("  summary              %s/summary.json, logs %s/logs/\n", s.out_dir.c_str(),
              s.out_dir.c_str());
}

}  // namespace vcockpit::rig
