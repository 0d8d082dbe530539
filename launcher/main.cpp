// rig_launcher: runs the vcockpit rig described by config/rig.yaml — starts the nodes in order
// on the rig's DDS domain, prefixes and saves their logs under OUT/logs/, shows a live status
// line, restarts or stops on a node's death per its policy, stops everything cleanly on Ctrl-C or
// when the replay ends, removes the /dev/shm files its run left, and writes OUT/summary.json.
// scripts/rig builds it and runs it.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <poll.h>
#include <signal.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <thread>

#include "common/clock.hpp"
#include "common/json_file.hpp"
#include "common/logging.hpp"
#include "common/signals.hpp"
#include "launcher/node_process.hpp"
#include "launcher/rig_monitor.hpp"

namespace vcockpit::rig {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> dev_shm_entries() {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator("/dev/shm", ec)) out.push_back(e.path().filename());
  std::sort(out.begin(), out.end());
  return out;
}

// Fast DDS's shared-memory files that appeared during the run (a killed node leaves its own).
int remove_new_dds_shm(const std::vector<std::string>& before) {
  int removed = 0;
  for (const auto& name : dev_shm_entries()) {
    if (std::binary_search(before.begin(), before.end(), name)) continue;
    const bool dds = name.rfind("fastrtps_", 0) == 0 || name.rfind("sem.fastrtps_", 0) == 0 ||
                     name.rfind("fast_datasharing_", 0) == 0 ||
                     name.rfind("sem.fast_datasharing_", 0) == 0;
    std::error_code ec;
    if (dds && fs::remove(fs::path("/dev/shm") / name, ec)) ++removed;
  }
  return removed;
}

struct Options {
  std::string rig_path;
  std::string log_path;
  std::string out_dir = "out";
  std::string bin_dir;
  bool quiet = false;
};

class Launcher {
 public:
  Launcher(RigConfig rig, Options options) : rig_(std::move(rig)), options_(std::move(options)) {}
  int run();

 private:
  void start_nodes();
  void supervise();
  void stop_nodes();
  void pump_all(int timeout_ms);
  void write_summary(double elapsed_s);

  RigConfig rig_;
  Options options_;
  std::map<std::string, std::string> env_;
  std::vector<std::unique_ptr<NodeProcess>> nodes_;
  std::map<NodeProcess*, int64_t> restart_at_ns_;
  std::FILE* combined_ = nullptr;
  std::unique_ptr<DdsParticipant> participant_;
  std::unique_ptr<RigMonitor> monitor_;
  bool failed_ = false;
  std::string end_reason_ = "stopped";
};

void Launcher::start_nodes() {
  for (const NodeSpec& spec : rig_.nodes) {
    std::vector<std::string> argv = expand_command(spec, rig_, options_.out_dir);
    argv[0] = options_.bin_dir + "/" + argv[0];
    if (access(argv[0].c_str(), X_OK) != 0) {
      throw std::runtime_error(rig_.path + ": node " + spec.name + ": no executable " + argv[0] +
                               " (build first: scripts/rig builds it)");
    }
    auto node = std::make_unique<NodeProcess>(spec, argv, options_.out_dir + "/logs/" + spec.name + ".log");
    node->start(env_);
    spdlog::info("started {} (pid {})", spec.name, node->pid());
    nodes_.push_back(std::move(node));
    const int64_t until = monotonic_now_ns() + seconds_to_ns(spec.start_delay_s);
    while (monotonic_now_ns() < until) pump_all(20);
  }
}

void Launcher::pump_all(int timeout_ms) {
  std::vector<pollfd> fds;
  for (auto& n : nodes_) {
    if (n->fd() >= 0) fds.push_back({n->fd(), POLLIN, 0});
  }
  if (fds.empty()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(timeout_ms));
  } else {
    poll(fds.data(), fds.size(), timeout_ms);
  }
  for (auto& n : nodes_) n->pump(combined_);
}

void Launcher::supervise() {
  const bool terminal = isatty(STDERR_FILENO) == 1 && !options_.quiet;
  const int64_t start_ns = monotonic_now_ns();
  int64_t last_line_ns = 0;
  int64_t drain_until_ns = -1;
  while (true) {
    pump_all(20);
    monitor_->poll();
    const int64_t now_ns = monotonic_now_ns();
    if (shutdown_requested()) {
      end_reason_ = "interrupted (Ctrl-C)";
      break;
    }
    if (drain_until_ns >= 0 && now_ns >= drain_until_ns) break;
    for (auto& node : nodes_) {
      if (!node->reap()) continue;
      const NodeSpec& spec = node->spec();
      const int status = node->exit_status();
      if (spec.ends_run && status == 0) {
        spdlog::info("{} finished: the run is over", spec.name);
        end_reason_ = spec.name + " finished";
        drain_until_ns = now_ns + 1'500'000'000;  // let the others show the end
      } else if (spec.restart_delay_s) {
        spdlog::warn("{} ended with status {}: restarting in {} s", spec.name, status,
                     *spec.restart_delay_s);
        restart_at_ns_[node.get()] = now_ns + seconds_to_ns(*spec.restart_delay_s);
      } else if (spec.required) {
        spdlog::error("{} (required) ended with status {}: stopping the rig", spec.name, status);
        end_reason_ = spec.name + " died";
        failed_ = true;
        drain_until_ns = now_ns;
      } else {
        spdlog::warn("{} ended with status {}", spec.name, status);
      }
    }
    for (auto it = restart_at_ns_.begin(); it != restart_at_ns_.end();) {
      if (now_ns < it->second) {
        ++it;
        continue;
      }
      it->first->start(env_);
      spdlog::info("restarted {} (pid {})", it->first->spec().name, it->first->pid());
      it = restart_at_ns_.erase(it);
    }
    if (terminal && now_ns - last_line_ns > 250'000'000) {
      std::fprintf(stderr, "\r%s ", monitor_->status_line(ns_to_seconds(now_ns - start_ns)).c_str());
      std::fflush(stderr);
      last_line_ns = now_ns;
    }
  }
  if (terminal) std::fputc('\n', stderr);
}

void Launcher::stop_nodes() {
  for (auto it = nodes_.rbegin(); it != nodes_.rend(); ++it) (*it)->signal(SIGINT);
  const int64_t deadline = monotonic_now_ns() + 3'000'000'000;
  auto all_ended = [&] {
    bool ended = true;
    for (auto& n : nodes_) {
      n->reap();
      ended = ended && !n->running();
    }
    return ended;
  };
  while (!all_ended() && monotonic_now_ns() < deadline) pump_all(20);
  for (auto& n : nodes_) {
    if (!n->running()) continue;
    spdlog::warn("{} did not stop within 3 s: killing it", n->spec().name);
    n->signal(SIGKILL);
  }
  while (!all_ended()) pump_all(20);
  for (int i = 0; i < 5; ++i) pump_all(1);  // the last lines
}

void Launcher::write_summary(double elapsed_s) {
  const auto& statuses = monitor_->statuses();
  auto count = [&](const char* node, auto field) -> unsigned long long {
    auto it = statuses.find(node);
    return it == statuses.end() ? 0ULL : static_cast<unsigned long long>(field(it->second));
  };
  int snapshots = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(options_.out_dir + "/frames", ec)) {
    snapshots += e.path().extension() == ".png" ? 1 : 0;
  }
  const auto& lat = monitor_->latencies_ms();
  int grasps = 0, releases = 0;
  for (const auto& e : monitor_->events()) (e.grasp ? grasps : releases)++;
  const auto samples = count("glove_driver", [](const cockpit::NodeStatus& s) { return s.published(); });
  const auto frames =
      count("image_generator", [](const cockpit::NodeStatus& s) { return s.published(); });

  const auto& age = monitor_->age_at_render_ms();
  const auto& render = monitor_->render_ms();
  nlohmann::ordered_json j;
  j["rig"] = rig_.path;
  j["log"] = rig_.log_path;
  j["domain"] = rig_.domain_id;
  j["ended"] = end_reason_;
  j["ok"] = !failed_;
  j["wall_s"] = elapsed_s;
  j["samples_replayed"] = samples;
  j["grasps"] = grasps;
  j["releases"] = releases;
  auto& events = j["events"] = nlohmann::ordered_json::array();
  for (const auto& e : monitor_->events()) {
    events.push_back({{"t_s", e.t_s},
                      {"event", e.grasp ? "grasp" : "release"},
                      {"object", e.object},
                      {"reason", e.reason}});
  }
  j["frames_rendered"] = frames;
  j["snapshots_written"] = snapshots;
  j["physics_step_rate_hz"] = monitor_->mean_step_rate_hz();
  j["late_steps"] = monitor_->late_steps();
  j["glove_to_frame_latency_ms"] = {
      {"p50", percentile(lat, 0.5)},
      {"p99", percentile(lat, 0.99)},
      {"max", lat.empty() ? 0.0 : *std::max_element(lat.begin(), lat.end())},
      {"samples", lat.size()}};
  j["latency_parts_ms"] = {{"age_at_render_start_p50", percentile(age, 0.5)},
                           {"age_at_render_start_p99", percentile(age, 0.99)},
                           {"render_p50", percentile(render, 0.5)},
                           {"render_p99", percentile(render, 0.99)}};
  auto& final_states = j["final"] = nlohmann::ordered_json::object();
  for (const auto& [name, st] : monitor_->final_states()) {
    const auto& p = st.X_GO().position_m();
    const auto& q = st.X_GO().orientation();
    final_states[name] = {{"sim_time_s", static_cast<double>(st.sim_time_ns()) / 1e9},
                          {"position", {p.x(), p.y(), p.z()}},
                          {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}},
                          {"held_by", st.held_by_hand_id()}};
  }
  auto& nodes = j["nodes"] = nlohmann::ordered_json::object();
  for (const auto& node : nodes_) {
    nodes[node->spec().name] = {{"exit_status", node->exit_status()},
                                {"restarts", node->restarts()}};
  }
  write_json_file(options_.out_dir + "/summary.json", j);

  std::printf("\nvcockpit rig: %s after %.1f s (%s)\n", failed_ ? "FAILED" : "done", elapsed_s,
              end_reason_.c_str());
  std::printf("  samples replayed     %llu\n", samples);
  for (const auto& e : monitor_->events()) {
    std::printf("  %-7s %-10s at %.3f s: %s\n", e.grasp ? "GRASP" : "RELEASE", e.object.c_str(),
                e.t_s, e.reason.c_str());
  }
  std::printf("  frames rendered      %llu, snapshots written %d (%s/frames)\n", frames, snapshots,
              options_.out_dir.c_str());
  std::printf("  physics step rate    %.1f Hz, late steps %llu\n", monitor_->mean_step_rate_hz(),
              static_cast<unsigned long long>(monitor_->late_steps()));
  std::printf("  glove->frame latency p50 %.1f ms, p99 %.1f ms, max %.1f ms (%zu samples)\n",
              percentile(lat, 0.5), percentile(lat, 0.99),
              lat.empty() ? 0.0 : *std::max_element(lat.begin(), lat.end()), lat.size());
  std::printf("    of which: sample age at render start p50 %.1f ms, render p50 %.1f ms\n",
              percentile(monitor_->age_at_render_ms(), 0.5), percentile(monitor_->render_ms(), 0.5));
  std::printf("  summary              %s/summary.json, logs %s/logs/\n", options_.out_dir.c_str(),
              options_.out_dir.c_str());
}

int Launcher::run() {
  if (!options_.log_path.empty()) rig_.log_path = fs::absolute(options_.log_path).string();
  if (!rig_.log_path.empty() && !fs::exists(rig_.log_path)) {
    throw std::runtime_error("glove log " + rig_.log_path + " does not exist");
  }
  options_.out_dir = fs::absolute(options_.out_dir).lexically_normal().string();
  fs::create_directories(options_.out_dir + "/logs");
  fs::remove_all(options_.out_dir + "/frames");  // this run's snapshots only
  fs::remove(options_.out_dir + "/summary.json");
  combined_ = std::fopen((options_.out_dir + "/logs/rig.log").c_str(), "w");
  env_ = {{"VCOCKPIT_DOMAIN", std::to_string(rig_.domain_id)},
          {"VCOCKPIT_QOS_FILE", rig_.qos_file},
          {"VCOCKPIT_PARTICIPANT", rig_.participant_profile}};
  const auto shm_before = dev_shm_entries();
  const int64_t start_ns = monotonic_now_ns();
  {
    DdsOptions dds;
    dds.domain_id = rig_.domain_id;
    dds.qos_file = rig_.qos_file;
    dds.participant_profile = rig_.participant_profile;
    participant_ = std::make_unique<DdsParticipant>(dds, "rig_launcher");
    monitor_ = std::make_unique<RigMonitor>(*participant_);
    spdlog::info("rig {} on domain {}; logs in {}/logs", rig_.path, rig_.domain_id, options_.out_dir);
    try {
      start_nodes();
      supervise();
    } catch (...) {
      stop_nodes();
      throw;
    }
    stop_nodes();
    for (int i = 0; i < 10; ++i) {  // statuses the nodes sent as they stopped
      monitor_->poll();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    write_summary(ns_to_seconds(monotonic_now_ns() - start_ns));
    monitor_.reset();
    participant_.reset();
  }
  const int removed = remove_new_dds_shm(shm_before);
  if (removed > 0) spdlog::info("removed {} /dev/shm file(s) left by killed nodes", removed);
  if (combined_) std::fclose(combined_);
  return failed_ ? 1 : 0;
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
  app.add_option("--log", options.log_path, "glove log to replay (default: the rig file's)")
      ->check(CLI::ExistingFile);
  app.add_option("--out", options.out_dir, "output directory")->capture_default_str();
  app.add_option("--bin-dir", options.bin_dir, "where the node executables are")->capture_default_str();
  app.add_flag("--quiet", options.quiet, "no live status line");
  CLI11_PARSE(app, argc, argv);
  try {
    setup_logging("rig");
    install_shutdown_handlers();
    return rig::Launcher(rig::load_rig_config(options.rig_path), options).run();
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
