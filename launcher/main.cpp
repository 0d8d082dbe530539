// rig_launcher: runs the vcockpit rig described by config/rig.yaml — starts the nodes in order
// on the rig's DDS domain, prefixes and saves their logs under OUT/logs/, shows a live status
// line, restarts or stops on a node's death per its policy, stops everything cleanly on Ctrl-C or
// when the replay ends, removes the /dev/shm files its run left, and writes OUT/summary.json.
// scripts/rig builds it and runs it.
//
// This file reads the flags and wires the parts: supervisor (the node processes), rig_monitor
// (the rig seen over DDS), run_summary (summary.json), console_report (the printed end report)
// and shm_cleanup.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include "common/clock.hpp"
#include "common/logging.hpp"
#include "hand/glove_log.hpp"
#include "common/signals.hpp"
#include "launcher/console_report.hpp"
#include "launcher/rig_monitor.hpp"
#include "launcher/run_report.hpp"
#include "launcher/run_summary.hpp"
#include "launcher/shm_cleanup.hpp"
#include "launcher/supervisor.hpp"

namespace vcockpit::rig {
namespace {

namespace fs = std::filesystem;

// The glove drivers begin this long after the launch: room for every node to start and match
// (Fast DDS's first handshake takes up to a second now and then).
constexpr int64_t kGloveStartMargin_ns = 3'000'000'000;

struct Options {
  std::string rig_path;
  std::string scene_path;              // the cockpit's scene; empty: the rig file's
  std::vector<std::string> log_paths;  // one per hand; empty: the rig file's
  std::string out_dir = "out";
  std::string bin_dir;
  bool quiet = false;
  std::string participant;  // overrides the rig file's participant profile
  std::string pki_dir;      // DDS Security files for a secured profile (scripts/make-pki)
  bool ui = false;          // the instructor station too; the replays wait at their end
  int ui_port = 8077;
};

int run(RigConfig rig, const Options& options) {
  if (!options.participant.empty()) rig.participant_profile = options.participant;
  if (options.ui) rig.ui_port = options.ui_port;
  rig.start_at_ns = monotonic_now_ns() + kGloveStartMargin_ns;
  if (!options.pki_dir.empty()) {
    if (!fs::is_directory(options.pki_dir))
      throw std::runtime_error("--pki: not a directory: " + options.pki_dir);
    rig.pki_dir = fs::absolute(options.pki_dir).string();
  }
  if (!options.scene_path.empty()) rig.scene_path = fs::absolute(options.scene_path).string();
  // --log replaces the rig file's logs: each log's '# hand:' line says whose it is
  if (!options.log_paths.empty()) {
    rig.log_path.clear();
    rig.left_log_path.clear();
    for (const std::string& given : options.log_paths) {
      std::string& slot = hand::glove_log_left_hand(given) ? rig.left_log_path : rig.log_path;
      if (!slot.empty()) throw std::runtime_error(given + ": a second log for the same hand");
      slot = fs::absolute(given).string();
    }
    if (rig.log_path.empty()) throw std::runtime_error("--log: no right hand's log");
  }
  for (const std::string& log : {rig.log_path, rig.left_log_path}) {
    if (!log.empty() && !fs::exists(log)) throw std::runtime_error("glove log " + log + " does not exist");
  }
  const std::string out_dir = fs::absolute(options.out_dir).lexically_normal().string();
  fs::create_directories(out_dir + "/logs");
  fs::remove_all(out_dir + "/frames");  // this run's snapshots only
  fs::remove(out_dir + "/summary.json");
  for (const auto& entry : fs::directory_iterator(out_dir)) {  // the last run's videos
    const std::string name = entry.path().filename().string();
    if (name.rfind("rig", 0) == 0 && name.find(".mp4") != std::string::npos) fs::remove(entry.path());
  }
  Supervisor supervisor(rig, out_dir, options.bin_dir);
  const auto shm_before = dev_shm_entries();
  const int64_t start_ns = monotonic_now_ns();
  {
    DdsOptions dds;
    dds.domain_id = rig.domain_id;
    dds.qos_file = rig.qos_file;
    dds.participant_profile = rig.participant_profile;
    dds.pki_dir = rig.pki_dir;
    dds.identity = "rig_monitor";  // a secured rig's launcher reads, never writes
    DdsParticipant participant(dds, "rig_launcher");
    RigMonitor monitor(participant);
    spdlog::info("rig {} on domain {}; logs in {}/logs", rig.path, rig.domain_id, out_dir);
    // the rig's timeline: a glove log's first sample is due here, and a restarted driver
    // (--join-timeline) joins the log where this clock puts it
    spdlog::info("the glove drivers begin at start_at_ns={} (CLOCK_MONOTONIC, {:.1f} s from now)",
                 rig.start_at_ns, ns_to_seconds(rig.start_at_ns - monotonic_now_ns()));
    try {
      supervisor.start_nodes();
      if (options.ui) {
        spdlog::info("instructor station: http://127.0.0.1:{}/ (the replays wait at their end for "
                     "a restart; Ctrl-C ends the run)",
                     rig.ui_port);
      }
      supervisor.supervise(monitor, isatty(STDERR_FILENO) == 1 && !options.quiet);
    } catch (...) {
      supervisor.stop_nodes();
      throw;
    }
    supervisor.stop_nodes();
    for (int i = 0; i < 10; ++i) {  // statuses the nodes sent as they stopped
      monitor.poll();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    const RunSummary summary = collect_run_summary(rig, out_dir, supervisor, monitor,
                                                   ns_to_seconds(monotonic_now_ns() - start_ns));
    write_run_summary(out_dir + "/summary.json", summary);
    if (!summary.procedures.empty()) {
      try {
        spdlog::info("procedure report: {}", write_report(summary, out_dir));
      } catch (const std::exception& e) {
        spdlog::warn("procedure report: {}", e.what());
      }
    }
    print_console_report(summary);
  }
  const int removed = remove_new_dds_shm(shm_before);
  if (removed > 0) spdlog::info("removed {} /dev/shm file(s) left by killed nodes", removed);
  return supervisor.failed() ? 1 : 0;
}

}  // namespace
}  // namespace vcockpit::rig

int main(int argc, char** argv) {
  using namespace vcockpit;
  CLI::App app("rig_launcher: starts, watches and stops the vcockpit nodes of a rig file");
  rig::Options options;
  options.rig_path = std::string(VCOCKPIT_CONFIG_DIR) + "/rig.yaml";
  options.bin_dir = VCOCKPIT_BIN_DIR;
  app.add_option("rig", options.rig_path, "rig YAML")->check(CLI::ExistingFile)->capture_default_str();
  app.add_option("--log", options.log_paths,
                 "glove log to replay, one per hand: --log right.csv [--log left.csv] (each log's "
                 "'# hand:' line says whose; default: the rig file's log and left_log)")
      ->check(CLI::ExistingFile);
  app.add_option("--scene", options.scene_path,
                 "the cockpit's scene file, instead of the rig file's ({scene})")
      ->check(CLI::ExistingFile);
  app.add_option("--out", options.out_dir, "output directory")->capture_default_str();
  app.add_option("--bin-dir", options.bin_dir, "where the node executables are")->capture_default_str();
  app.add_flag("--quiet", options.quiet, "no live status line");
  app.add_option("--participant", options.participant,
                 "participant profile for every node and the launcher (default: the rig file's; "
                 "secure: DDS Security, with --pki)");
  app.add_option("--pki", options.pki_dir,
                 "DDS Security files (scripts/make-pki DIR): each node uses its own identity");
  app.add_flag("--ui", options.ui,
               "start the instructor station too (the rig file's with_ui nodes and ui_args): a web "
               "page on loopback to watch and command the run, which then lasts until Ctrl-C");
  app.add_option("--ui-port", options.ui_port, "the instructor station's TCP port")
      ->check(CLI::Range(1, 65535))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    setup_logging("rig");
    install_shutdown_handlers();
    return rig::run(rig::load_rig_config(options.rig_path), options);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
