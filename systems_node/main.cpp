// systems_node: the aircraft's systems (config/aircraft.yaml, docs/systems.md) stepped in the
// physics' time. On DDS it follows cockpit/control_frame (systems_node/node/systems_node_loop.hpp);
// --offline it reads the control_frames.csv a physics run wrote. With --lesson it scores the
// lesson's procedures as they are flown (systems/procedure_runner.hpp). Both write, with --out,
// the same systems_events.jsonl, systems.csv, systems_summary.json and (with a lesson)
// procedures.json and procedure_events.jsonl for the same frames.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "common/cli_finite.hpp"
#include "common/config_error.hpp"
#include "common/logging.hpp"
#include "common/signals.hpp"
#include "dds/dds_options.hpp"
#include "systems/config/procedure_yaml.hpp"
#include "systems/config/systems_yaml.hpp"
#include "systems/control_frames_file.hpp"
#include "systems/systems_session.hpp"
#include "systems_node/node/systems_node_loop.hpp"

namespace {

using namespace vcockpit;

int run_offline(const std::string& aircraft, const std::string& frames_path,
                const systems::SessionOptions& options) {
  const systems::ControlFrames frames = systems::read_control_frames(frames_path);
  systems::SystemsSession session(load_systems_model(aircraft), frames.controls, options);
  for (const systems::ControlFrame& f : frames.frames) session.take(f);
  session.finish();
  if (const systems::ProcedureRunner* runner = session.procedures()) {
    for (std::size_t p = 0; p < runner->scores().size(); ++p) {
      const systems::ProcedureScore& score = runner->scores()[p];
      spdlog::info("procedure '{}': {}, {} error(s)", runner->lesson().procedures[p].title,
                   systems::state_name(score.state), score.errors());
    }
  }
  const auto& c = session.counts();
  spdlog::info("{} frames: {} steps to t {:.3f} s, {} events; {} periods without a frame, {} off "
               "the grid", frames.frames.size(), session.systems().state().step,
               static_cast<double>(session.systems().state().time_ns) * 1e-9, session.events(),
               c.missed, c.off_grid);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("systems_node: the aircraft's systems, stepped in the physics' time");
  std::string aircraft = std::string(VCOCKPIT_CONFIG_DIR) + "/aircraft.yaml";
  bool offline = false;
  std::string frames_path;
  std::vector<std::string> failures;
  std::string log_level = "info";
  systems_node::NodeOptions node;
  DdsFlags dds_flags;
  app.add_option("--aircraft", aircraft, "the aircraft's systems file")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  app.add_flag("--offline", offline, "no DDS: step the systems through --control-frames");
  app.add_option("--control-frames", frames_path,
                 "--offline: the control_frames.csv of a physics run (physics_node --offline, or a "
                 "lockstep node's --out)")
      ->check(CLI::ExistingFile);
  app.add_option("--out", node.session.out_dir,
                 "write systems_events.jsonl, systems.csv and systems_summary.json here (at stop)");
  std::string lesson;
  app.add_option("--lesson", lesson,
                 "score the procedures of this lesson file (config/lessons/*.yaml) as they are flown")
      ->check(CLI::ExistingFile);
  app.add_option("--failure-at", failures,
                 "SECONDS:NAME: insert a failure at that simulated time (repeatable)");
  app.add_option("--checkpoint", node.checkpoint_path,
                 "DDS: save the systems' state here every --checkpoint-every of simulated time");
  app.add_option("--checkpoint-every", node.checkpoint_every_s, "seconds of simulated time")
      ->check(CLI::Range(0.01, 3600.0) & kFinite)
      ->capture_default_str();
  app.add_flag("--resume", node.resume, "DDS: start from --checkpoint's state when there is one");
  app.add_option("--duration", node.duration_s, "DDS: stop after this many seconds (0: on a signal)")
      ->check(CLI::Range(0.0, 1e7) & kFinite);
  app.add_option("--node-name", node.node_name, "its name in cockpit/node_status")->capture_default_str();
  add_dds_flags(app, dds_flags);
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  setup_logging("systems_node", log_level);
  try {
    node.session.aircraft_path = aircraft;
    for (const std::string& f : failures) node.session.failures.push_back(systems::parse_scheduled_failure(f));
    if (!lesson.empty()) node.session.lesson = load_lesson(lesson);
    if (offline) {
      if (frames_path.empty()) throw std::invalid_argument("--offline needs --control-frames");
      if (node.session.out_dir.empty()) throw std::invalid_argument("--offline needs --out");
      return run_offline(aircraft, frames_path, node.session);
    }
    if (!frames_path.empty()) throw std::invalid_argument("--control-frames is for --offline");
    systems::SystemsModel model = load_systems_model(aircraft);  // file errors before joining DDS
    install_shutdown_handlers();
    DdsParticipant participant(resolve_dds_options(dds_flags, "systems_node"), node.node_name);
    spdlog::info("{} on domain {}: waiting for the physics' control frames", aircraft,
                 participant.domain_id());
    return systems_node::run_node(participant, std::move(model), node);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
