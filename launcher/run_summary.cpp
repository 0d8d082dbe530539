#include "launcher/run_summary.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "common/json_file.hpp"
#include "launcher/run_report.hpp"
#include "launcher/supervisor.hpp"

namespace vcockpit::rig {

RunSummary collect_run_summary(const RigConfig& rig, const std::string& out_dir,
                               const Supervisor& supervisor, const RigMonitor& monitor,
                               double wall_s) {
  RunSummary s;
  s.rig_path = rig.path;
  s.log_path = rig.log_path;
  s.left_log_path = rig.left_log_path;
  s.domain_id = rig.domain_id;
  s.out_dir = out_dir;
  s.ended = supervisor.end_reason();
  s.ok = !supervisor.failed();
  s.wall_s = wall_s;

  const auto& statuses = monitor.statuses();
  auto published = [&](const char* node) -> uint64_t {
    auto it = statuses.find(node);
    return it == statuses.end() ? 0 : it->second.published();
  };
  // what the inputs published: the nodes that end the run (glove drivers, the OpenXR bridge) and
  // the glove drivers that do not (a soak's looping ones), each by its own status or its
  // "<name>/..." ones (openxr_hand_bridge/right, /left)
  for (const NodeSpec& node : rig.nodes) {
    if (!node.ends_run && node.name.rfind("glove_driver", 0) != 0) continue;
    for (const auto& [name, status] : statuses)
      if (RigMonitor::is_status_of(name, node.name)) s.samples_replayed += status.published();
  }
  if (auto it = statuses.find("physics_node"); it != statuses.end()) {
    for (const cockpit::HandInputStatus& h : it->second.hands())
      s.hands.push_back({static_cast<int>(h.hand_id()), h.received(), h.glove_lost(), h.grasps(), h.tracking()});
  }
  s.frames_rendered = published("image_generator");
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(out_dir + "/frames", ec)) {
    s.snapshots_written += e.path().extension() == ".png" ? 1 : 0;
  }
  s.events = monitor.events();
  for (const auto& e : s.events) (e.grasp ? s.grasps : s.releases)++;
  s.control_events = monitor.control_events();
  s.controls = monitor.control_positions();
  s.systems_events = monitor.systems_events();
  s.systems = monitor.systems_values();
  s.procedures = monitor.procedures();
  s.physics_step_rate_hz = monitor.mean_step_rate_hz();
  s.late_steps = monitor.late_steps();

  auto ms = [](int64_t ns) { return static_cast<double>(ns) * 1e-6; };
  const LatencyHistogram& lat = monitor.latency();
  s.latency_p50_ms = ms(lat.percentile_ns(0.5));
  s.latency_p99_ms = ms(lat.percentile_ns(0.99));
  s.latency_max_ms = ms(lat.max_ns());
  s.latency_samples = lat.count();
  s.age_at_render_start_p50_ms = ms(monitor.age_at_render().percentile_ns(0.5));
  s.age_at_render_start_p99_ms = ms(monitor.age_at_render().percentile_ns(0.99));
  s.render_p50_ms = ms(monitor.render().percentile_ns(0.5));
  s.render_p99_ms = ms(monitor.render().percentile_ns(0.99));

  for (const auto& [name, st] : monitor.final_states()) {
    const auto& p = st.X_GO().position_m();
    const auto& q = st.X_GO().orientation();
    s.final_objects.push_back({name,
                               static_cast<double>(st.sim_time_ns()) / 1e9,
                               {p.x(), p.y(), p.z()},
                               {q.w(), q.x(), q.y(), q.z()},
                               st.held_by_hand_id()});
  }
  for (const auto& node : supervisor.nodes()) {
    s.nodes.push_back({node->spec().name, node->exit_status(), node->restarts()});
  }
  return s;
}

void write_run_summary(const std::string& path, const RunSummary& s) {
  nlohmann::ordered_json j;
  j["rig"] = s.rig_path;
  j["log"] = s.log_path;
  if (!s.left_log_path.empty()) j["left_log"] = s.left_log_path;
  auto& hands = j["hands"] = nlohmann::ordered_json::array();
  for (const RunSummary::HandOutcome& h : s.hands) {
    hands.push_back({{"hand", h.hand_id == 1 ? "left" : "right"},
                     {"samples", h.samples},
                     {"glove_lost", h.glove_lost},
                     {"grasps", h.grasps},
                     {"tracking_at_end", h.tracking}});
  }
  j["domain"] = s.domain_id;
  j["ended"] = s.ended;
  j["ok"] = s.ok;
  j["wall_s"] = s.wall_s;
  j["samples_replayed"] = s.samples_replayed;
  j["grasps"] = s.grasps;
  j["releases"] = s.releases;
  auto& events = j["events"] = nlohmann::ordered_json::array();
  for (const auto& e : s.events) {
    events.push_back({{"t_s", e.t_s},
                      {"event", e.grasp ? "grasp" : "release"},
                      {"hand", e.hand_id == 1 ? "left" : "right"},
                      {"object", e.object},
                      {"reason", e.reason}});
  }
  auto& control_events = j["control_events"] = nlohmann::ordered_json::array();
  for (const auto& e : s.control_events) {
    nlohmann::ordered_json c = {{"t_s", e.t_s}, {"control", e.control}, {"from", e.from},
                                {"to", e.to}, {"cause", e.cause}};
    c["link"] = e.link.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(e.link);
    control_events.push_back(c);
  }
  auto& controls = j["controls"] = nlohmann::ordered_json::object();
  for (const auto& [name, position] : s.controls) controls[name] = position;
  auto& systems_events = j["systems_events"] = nlohmann::ordered_json::array();
  for (const auto& e : s.systems_events) {
    systems_events.push_back({{"t_s", e.t_s}, {"event", e.kind}, {"name", e.name},
                              {"from", e.from}, {"to", e.to}});
  }
  auto& systems = j["systems"] = nlohmann::ordered_json::object();
  for (const auto& [name, value] : s.systems) systems[name] = value;
  j["procedures"] = procedures_json(s.procedures);
  j["frames_rendered"] = s.frames_rendered;
  j["snapshots_written"] = s.snapshots_written;
  j["physics_step_rate_hz"] = s.physics_step_rate_hz;
  j["late_steps"] = s.late_steps;
  j["glove_to_frame_latency_ms"] = {{"p50", s.latency_p50_ms},
                                    {"p99", s.latency_p99_ms},
                                    {"max", s.latency_max_ms},
                                    {"samples", s.latency_samples}};
  j["latency_parts_ms"] = {{"age_at_render_start_p50", s.age_at_render_start_p50_ms},
                           {"age_at_render_start_p99", s.age_at_render_start_p99_ms},
                           {"render_p50", s.render_p50_ms},
                           {"render_p99", s.render_p99_ms}};
  auto& final_objects = j["final"] = nlohmann::ordered_json::object();
  for (const auto& o : s.final_objects) {
    final_objects[o.name] = {{"sim_time_s", o.sim_time_s},
                             {"position", o.position},
                             {"quaternion_wxyz", o.quaternion_wxyz},
                             {"held_by", o.held_by}};
  }
  auto& nodes = j["nodes"] = nlohmann::ordered_json::object();
  for (const auto& n : s.nodes) {
    nodes[n.name] = {{"exit_status", n.exit_status}, {"restarts", n.restarts}};
  }
  write_json_file(path, j);
}

}  // namespace vcockpit::rig
