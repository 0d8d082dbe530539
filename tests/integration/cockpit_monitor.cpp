// Test monitor: subscribes to the physics node's outputs and writes what it sees as text lines,
// flushed as they come so a test can watch the file while the rig runs:
//   event t_ns=.. kind=grasp|release hand=.. object=.. contacts=.. reason=<text to end of line>
//   status node=.. state=.. rate_hz=.. input_hz=.. received=.. rejected=.. nonfinite=.. range=..
//          stale=.. clamped=.. late=.. alive=0|1 missing=.. intervals=.. interpolated=..
//          bridged=.. unbridged=.. intervals_late=.. longest_s=.. lost=.. delay_ms=..
//   hand id=.. seq=.. sample_time_ns=.. source_stamp_ns=.. sim_time_ns=.. tracking=0|1 held=..
//        received_ns=.. x=.. y=.. z=.. qw=.. qx=.. qy=.. qz=..
//   watched id=.. sim_time_ns=.. held=.. received_ns=.. x=.. y=.. z=.. qw=.. qx=.. qy=.. qz=..
//        (every state of the object --watch-object names, as it comes)
//   frame seq=.. width=.. height=.. source_stamp_ns=.. start_ns=.. end_ns=.. received_ns=..
// and the last state of every object, every 0.5 s while new states come and on exit
// (SIGINT/SIGTERM or --duration; the last line of an id is its newest state):
//   object id=.. sim_time_ns=.. held=.. x=.. y=.. z=.. qw=.. qx=.. qy=.. qz=..

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <chrono>
#include <map>
#include <thread>

#include "common/clock.hpp"
#include "dds/dds_participant.hpp"
#include "common/logging.hpp"
#include "common/signals.hpp"

namespace {

using namespace vcockpit;

void print_pose(std::FILE* f, const cockpit::Pose& p) {
  std::fprintf(f, " x=%.17g y=%.17g z=%.17g qw=%.17g qx=%.17g qy=%.17g qz=%.17g",
               p.position_m().x(), p.position_m().y(), p.position_m().z(), p.orientation().w(),
               p.orientation().x(), p.orientation().y(), p.orientation().z());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("cockpit_monitor: records the physics node's topics for tests");
  DdsFlags dds_flags;
  add_dds_flags(app, dds_flags);
  std::string out_path;
  double duration_s = 0;
  app.add_option("--out", out_path)->required();
  app.add_option("--duration", duration_s, "stop after this many seconds (0: on a signal)");
  int64_t watched_id = -1;
  app.add_option("--watch-object", watched_id, "object id whose every state is written");
  CLI11_PARSE(app, argc, argv);
  setup_logging("cockpit_monitor");
  install_shutdown_handlers();
  try {
    DdsParticipant participant(resolve_dds_options(dds_flags), "cockpit_monitor");
    auto events = participant.make_reader<cockpit::GraspEvent>("event");
    auto status = participant.make_reader<cockpit::NodeStatus>("state");
    auto hands = participant.make_reader<cockpit::HandState>("stream");
    auto objects = participant.make_reader<cockpit::ObjectState>("state");
    auto frames = participant.make_reader<cockpit::FrameInfo>("stream");
    std::FILE* f = std::fopen(out_path.c_str(), "w");
    if (!f) {
      spdlog::error("{}: cannot open", out_path);
      return 1;
    }
    std::map<uint32_t, cockpit::ObjectState> last_objects;
    const auto write_objects = [&] {
      for (const auto& [id, state] : last_objects) {
        std::fprintf(f, "object id=%u sim_time_ns=%lld held=%d", id,
                     static_cast<long long>(state.sim_time_ns()), state.held_by_hand_id());
        print_pose(f, state.X_GO());
        std::fputc('\n', f);
      }
    };
    bool objects_changed = false;
    int64_t objects_written_ns = 0;
    const int64_t end_ns =
        duration_s > 0 ? monotonic_now_ns() + seconds_to_ns(duration_s) : INT64_MAX;
    cockpit::GraspEvent e;
    cockpit::NodeStatus s;
    cockpit::HandState h;
    cockpit::ObjectState o;
    cockpit::FrameInfo fr;
    while (!shutdown_requested() && monotonic_now_ns() < end_ns) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      while (events.take(e)) {
        std::fprintf(f, "event t_ns=%lld kind=%s hand=%u object=%u contacts=%u reason=%s\n",
                     static_cast<long long>(e.sim_time_ns()),
                     e.kind() == cockpit::GRASP ? "grasp" : "release", e.hand_id(), e.object_id(),
                     e.contact_count(), e.reason().c_str());
      }
      while (status.take(s)) {
        std::fprintf(f,
                     "status node=%s state=%d rate_hz=%.3f input_hz=%.3f received=%llu "
                     "rejected=%llu nonfinite=%llu range=%llu stale=%llu clamped=%llu late=%llu "
                     "alive=%d missing=%llu intervals=%llu interpolated=%llu bridged=%llu "
                     "unbridged=%llu intervals_late=%llu longest_s=%.6f lost=%llu delay_ms=%.3f\n",
                     s.node_name().c_str(), static_cast<int>(s.state()), s.loop_rate_hz(),
                     s.input_rate_hz(), static_cast<unsigned long long>(s.received()),
                     static_cast<unsigned long long>(s.rejected()),
                     static_cast<unsigned long long>(s.rejected_nonfinite()),
                     static_cast<unsigned long long>(s.rejected_out_of_range()),
                     static_cast<unsigned long long>(s.rejected_stale()),
                     static_cast<unsigned long long>(s.clamped()),
                     static_cast<unsigned long long>(s.late_steps()), s.input_alive() ? 1 : 0,
                     static_cast<unsigned long long>(s.missing_columns()),
                     static_cast<unsigned long long>(s.intervals()),
                     static_cast<unsigned long long>(s.intervals_interpolated()),
                     static_cast<unsigned long long>(s.gaps_bridged()),
                     static_cast<unsigned long long>(s.gaps_not_bridged()),
                     static_cast<unsigned long long>(s.intervals_late()), s.longest_interval_s(),
                     static_cast<unsigned long long>(s.glove_lost()), s.input_delay_ms());
      }
      while (hands.take(h)) {
        std::fprintf(f,
                     "hand id=%u seq=%llu sample_time_ns=%lld source_stamp_ns=%lld sim_time_ns=%lld "
                     "tracking=%d held=%d received_ns=%lld",
                     h.hand_id(), static_cast<unsigned long long>(h.seq()),
                     static_cast<long long>(h.sample_time_ns()),
                     static_cast<long long>(h.source_stamp_ns()),
                     static_cast<long long>(h.sim_time_ns()), h.tracking() ? 1 : 0,
                     h.grasped_object_id(), static_cast<long long>(monotonic_now_ns()));
        print_pose(f, h.X_GH());
        std::fputc('\n', f);
      }
      while (objects.take(o)) {
        last_objects[o.object_id()] = o;
        objects_changed = true;
        if (static_cast<int64_t>(o.object_id()) != watched_id) continue;
        std::fprintf(f, "watched id=%u sim_time_ns=%lld held=%d received_ns=%lld", o.object_id(),
                     static_cast<long long>(o.sim_time_ns()), o.held_by_hand_id(),
                     static_cast<long long>(monotonic_now_ns()));
        print_pose(f, o.X_GO());
        std::fputc('\n', f);
      }
      while (frames.take(fr)) {
        std::fprintf(f,
                     "frame seq=%llu width=%u height=%u source_stamp_ns=%lld start_ns=%lld "
                     "end_ns=%lld received_ns=%lld\n",
                     static_cast<unsigned long long>(fr.frame_seq()), fr.width_px(),
                     fr.height_px(), static_cast<long long>(fr.source_stamp_ns()),
                     static_cast<long long>(fr.render_start_ns()),
                     static_cast<long long>(fr.render_end_ns()),
                     static_cast<long long>(monotonic_now_ns()));
      }
      if (objects_changed && monotonic_now_ns() - objects_written_ns >= 500'000'000) {
        write_objects();
        objects_changed = false;
        objects_written_ns = monotonic_now_ns();
      }
      std::fflush(f);
    }
    write_objects();
    std::fclose(f);
  } catch (const std::exception& ex) {
    spdlog::error("{}", ex.what());
    return 1;
  }
  return 0;
}
