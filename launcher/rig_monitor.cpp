#include "launcher/rig_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vcockpit::rig {

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double rank = p * static_cast<double>(values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(rank));
  const auto hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (rank - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

RigMonitor::RigMonitor(DdsParticipant& participant)
    : status_reader_(participant.make_reader<cockpit::NodeStatus>("state")),
      event_reader_(participant.make_reader<cockpit::GraspEvent>("event")),
      frame_reader_(participant.make_reader<cockpit::FrameInfo>("stream")),
      info_reader_(participant.make_reader<cockpit::ObjectInfo>("state")),
      state_reader_(participant.make_reader<cockpit::ObjectState>("state")) {
  latencies_ms_.reserve(1 << 16);
}

std::string RigMonitor::object_name(uint32_t id) const {
  auto it = names_.find(id);
  return it == names_.end() ? "object " + std::to_string(id) : it->second;
}

void RigMonitor::poll() {
  cockpit::ObjectInfo info;
  while (info_reader_.take(info)) {
    names_[info.object_id()] = info.name().to_string();
    dynamic_[info.object_id()] = info.kind() == cockpit::DYNAMIC_OBJECT;
  }
  cockpit::ObjectState state;
  while (state_reader_.take(state)) {
    if (dynamic_[state.object_id()]) final_[object_name(state.object_id())] = state;
  }
  cockpit::NodeStatus status;
  while (status_reader_.take(status)) {
    const std::string name = status.node_name().to_string();
    if (name == "physics_node" && status.input_alive()) step_rates_hz_.push_back(status.loop_rate_hz());
    statuses_[name] = status;
  }
  cockpit::GraspEvent e;
  while (event_reader_.take(e)) {
    SeenEvent seen;
    seen.t_s = static_cast<double>(e.sim_time_ns()) / 1e9;  // prints as its exact decimal
    seen.grasp = e.kind() == cockpit::GRASP;
    seen.object = object_name(e.object_id());
    seen.reason = e.reason().to_string();
    held_ = seen.grasp ? seen.object : "";
    events_.push_back(seen);
  }
  cockpit::FrameInfo frame;
  while (frame_reader_.take(frame)) {
    ++frames_seen_;
    // each hand sample counts once, at the first frame that drew it
    if (frame.source_stamp_ns() <= 0 || frame.source_stamp_ns() == last_source_stamp_ns_) continue;
    last_source_stamp_ns_ = frame.source_stamp_ns();
    latencies_ms_.push_back(static_cast<double>(frame.render_end_ns() - frame.source_stamp_ns()) * 1e-6);
    // where the latency goes: the sample's age when the frame began, and the render itself
    age_at_render_ms_.push_back(static_cast<double>(frame.render_start_ns() - frame.source_stamp_ns()) * 1e-6);
    render_ms_.push_back(static_cast<double>(frame.render_end_ns() - frame.render_start_ns()) * 1e-6);
  }
}

double RigMonitor::mean_step_rate_hz() const {
  if (step_rates_hz_.size() < 2) return step_rates_hz_.empty() ? 0.0 : step_rates_hz_.front();
  double sum = 0;  // the first report covers a partial second
  for (std::size_t i = 1; i < step_rates_hz_.size(); ++i) sum += step_rates_hz_[i];
  return sum / static_cast<double>(step_rates_hz_.size() - 1);
}

uint64_t RigMonitor::late_steps() const {
  auto it = statuses_.find("physics_node");
  return it == statuses_.end() ? 0 : it->second.late_steps();
}

std::string RigMonitor::status_line(double elapsed_s) const {
  auto rate = [&](const char* node) {
    auto it = statuses_.find(node);
    return it == statuses_.end() ? 0.0 : it->second.loop_rate_hz();
  };
  auto glove = statuses_.find("physics_node");
  const bool alive = glove != statuses_.end() && glove->second.input_alive();
  char line[256];
  std::snprintf(line, sizeof line,
                "%6.1f s | physics %6.0f Hz | glove %5.0f Hz %s | frames %4.0f fps | %s | "
                "latency p50 %5.1f ms",
                elapsed_s, rate("physics_node"), rate("glove_driver"), alive ? "   " : "LOST",
                rate("image_generator"), held_.empty() ? "nothing held" : ("holding " + held_).c_str(),
                percentile(latencies_ms_, 0.5));
  return line;
}

}  // namespace vcockpit::rig
