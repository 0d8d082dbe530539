#include "launcher/supervisor.hpp"

#include <poll.h>
#include <signal.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>
#include <thread>

#include "common/clock.hpp"
#include "common/signals.hpp"
#include "launcher/rig_monitor.hpp"

namespace vcockpit::rig {

Supervisor::Supervisor(RigConfig rig, std::string out_dir, std::string bin_dir)
    : rig_(std::move(rig)), out_dir_(std::move(out_dir)), bin_dir_(std::move(bin_dir)) {
  combined_ = std::fopen((out_dir_ + "/logs/rig.log").c_str(), "w");
  env_ = {{"VCOCKPIT_DOMAIN", std::to_string(rig_.domain_id)},
          {"VCOCKPIT_QOS_FILE", rig_.qos_file},
          {"VCOCKPIT_PARTICIPANT", rig_.participant_profile}};
  // each node takes its own identity (glove_driver, physics_node, ...) from the directory
  if (!rig_.pki_dir.empty()) env_["VCOCKPIT_PKI_DIR"] = rig_.pki_dir;
}

Supervisor::~Supervisor() {
  if (combined_) std::fclose(combined_);
}

void Supervisor::start_nodes() {
  for (const NodeSpec& spec : rig_.nodes) {
    if (!node_starts(spec, rig_)) continue;
    std::vector<std::string> argv = expand_command(spec, rig_, out_dir_);
    std::vector<std::string> restart_argv = expand_command(spec, rig_, out_dir_, true);
    argv[0] = bin_dir_ + "/" + argv[0];
    restart_argv[0] = argv[0];
    if (access(argv[0].c_str(), X_OK) != 0) {
      throw std::runtime_error(rig_.path + ": node " + spec.name + ": no executable " + argv[0] +
                               " (build first: scripts/rig builds it)");
    }
    auto node = std::make_unique<NodeProcess>(spec, argv, out_dir_ + "/logs/" + spec.name + ".log",
                                              restart_argv);
    node->start(env_);
    spdlog::info("started {} (pid {})", spec.name, node->pid());
    nodes_.push_back(std::move(node));
    const int64_t until = monotonic_now_ns() + seconds_to_ns(spec.start_delay_s);
    while (monotonic_now_ns() < until) pump_all(20);
  }
}

void Supervisor::pump_all(int timeout_ms) {
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

namespace {
constexpr int64_t kCatchUpLimit_ns = 60'000'000'000;
constexpr int64_t kShowTheEnd_ns = 1'500'000'000;
}  // namespace

void Supervisor::supervise(RigMonitor& monitor, bool status_line) {
  const int64_t start_ns = monotonic_now_ns();
  int64_t last_line_ns = 0;
  int64_t drain_until_ns = -1;
  int64_t catch_up_until_ns = -1;  // the input has ended: waiting for the physics to take it all
  std::vector<std::string> input_nodes;
  for (const auto& node : nodes_)
    if (node->spec().ends_run) input_nodes.push_back(node->spec().name);
  while (true) {
    pump_all(20);
    monitor.poll();
    const int64_t now_ns = monotonic_now_ns();
    if (shutdown_requested()) {
      end_reason_ = "interrupted (Ctrl-C)";
      break;
    }
    if (catch_up_until_ns >= 0 &&
        (monitor.input_consumed(input_nodes) || now_ns >= catch_up_until_ns)) {
      if (now_ns >= catch_up_until_ns)
        spdlog::warn("the physics node had not taken every sample {} s after the input ended",
                     ns_to_seconds(kCatchUpLimit_ns));
      catch_up_until_ns = -1;
      drain_until_ns = now_ns + kShowTheEnd_ns;
    }
    if (drain_until_ns >= 0 && now_ns >= drain_until_ns) break;
    for (auto& node : nodes_) {
      if (!node->reap()) continue;
      const NodeSpec& spec = node->spec();
      const int status = node->exit_status();
      if (spec.ends_run && status == 0) {
        // the run is over when every node that ends it has (a glove driver per hand)
        bool all_ended = true;
        for (const auto& other : nodes_)
          if (other->spec().ends_run && other.get() != node.get() && other->running()) all_ended = false;
        if (!all_ended) {
          spdlog::info("{} finished", spec.name);
          continue;
        }
        spdlog::info("{} finished: the run is over", spec.name);
        end_reason_ = spec.name + " finished";
        // a busy machine's physics node may still be stepping through queued samples: the run
        // ends when it has taken them all (bounded), then the others have a moment to show it
        catch_up_until_ns = now_ns + kCatchUpLimit_ns;
      } else if (spec.restart_delay_s &&
                 restart_guards_[node.get()].allows_restart(node->started_at_ns(),
                                                            node->ended_at_ns(), status)) {
        spdlog::warn("{} ended with status {}: restarting in {} s", spec.name, status,
                     *spec.restart_delay_s);
        restart_at_ns_[node.get()] = now_ns + seconds_to_ns(*spec.restart_delay_s);
      } else if (spec.restart_delay_s) {
        spdlog::error("{} ended with status {} within {:.0f} s of its start {} times in a row: "
                      "not restarted again (why: {}/logs/{}.log){}",
                      spec.name, status, ns_to_seconds(RestartGuard::kSoon_ns),
                      RestartGuard::kInARow, out_dir_, spec.name,
                      spec.required ? "; stopping the rig" : "");
        if (spec.required) {
          end_reason_ = spec.name + " cannot start";
          failed_ = true;
          drain_until_ns = now_ns;
        }
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
    if (status_line && now_ns - last_line_ns > 250'000'000) {
      std::fprintf(stderr, "\r%s ", monitor.status_line(ns_to_seconds(now_ns - start_ns)).c_str());
      std::fflush(stderr);
      last_line_ns = now_ns;
    }
  }
  if (status_line) std::fputc('\n', stderr);
}

void Supervisor::stop_nodes() {
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

}  // namespace vcockpit::rig
