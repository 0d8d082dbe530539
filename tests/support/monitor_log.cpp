#include "tests/support/monitor_log.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>

namespace vcockpit::test {
namespace {

// key=value fields of a line; the value of `reason` runs to the end of the line.
std::map<std::string, std::string> fields(const std::string& line) {
  std::map<std::string, std::string> out;
  std::size_t pos = line.find(' ');
  while (pos != std::string::npos && pos < line.size()) {
    const std::size_t start = pos + 1;
    const std::size_t eq = line.find('=', start);
    if (eq == std::string::npos) break;
    const std::string key = line.substr(start, eq - start);
    std::size_t end = key == "reason" ? std::string::npos : line.find(' ', eq + 1);
    out[key] = line.substr(eq + 1, end == std::string::npos ? std::string::npos : end - eq - 1);
    pos = end;
  }
  return out;
}

double num(const std::map<std::string, std::string>& f, const std::string& key) {
  auto it = f.find(key);
  return it == f.end() ? 0.0 : std::stod(it->second);
}

int64_t integer(const std::map<std::string, std::string>& f, const std::string& key) {
  auto it = f.find(key);
  return it == f.end() ? 0 : std::stoll(it->second);
}

Eigen::Vector3d position(const std::map<std::string, std::string>& f) {
  return {num(f, "x"), num(f, "y"), num(f, "z")};
}

}  // namespace

MonitorLog MonitorLog::read(const std::string& path) {
  MonitorLog log;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const std::string kind = line.substr(0, line.find(' '));
    const auto f = fields(line);
    if (kind == "event") {
      log.events.push_back({integer(f, "t_ns"), f.count("kind") ? f.at("kind") : "",
                            static_cast<int>(integer(f, "object")),
                            f.count("reason") ? f.at("reason") : ""});
    } else if (kind == "status") {
      SeenStatus s;
      s.node = f.count("node") ? f.at("node") : "";
      s.rate_hz = num(f, "rate_hz");
      s.input_hz = num(f, "input_hz");
      s.received = static_cast<uint64_t>(integer(f, "received"));
      s.rejected = static_cast<uint64_t>(integer(f, "rejected"));
      s.nonfinite = static_cast<uint64_t>(integer(f, "nonfinite"));
      s.range = static_cast<uint64_t>(integer(f, "range"));
      s.stale = static_cast<uint64_t>(integer(f, "stale"));
      s.late = static_cast<uint64_t>(integer(f, "late"));
      s.alive = integer(f, "alive") != 0;
      s.state = static_cast<int>(integer(f, "state"));
      s.clamped = static_cast<uint64_t>(integer(f, "clamped"));
      s.missing = static_cast<uint64_t>(integer(f, "missing"));
      s.intervals = static_cast<uint64_t>(integer(f, "intervals"));
      s.interpolated = static_cast<uint64_t>(integer(f, "interpolated"));
      s.bridged = static_cast<uint64_t>(integer(f, "bridged"));
      s.unbridged = static_cast<uint64_t>(integer(f, "unbridged"));
      s.intervals_late = static_cast<uint64_t>(integer(f, "intervals_late"));
      s.lost = static_cast<uint64_t>(integer(f, "lost"));
      s.longest_s = num(f, "longest_s");
      s.delay_ms = num(f, "delay_ms");
      log.statuses.push_back(s);
    } else if (kind == "hand") {
      SeenHand h;
      h.id = static_cast<int>(integer(f, "id"));
      h.seq = static_cast<uint64_t>(integer(f, "seq"));
      h.sample_time_ns = integer(f, "sample_time_ns");
      h.source_stamp_ns = integer(f, "source_stamp_ns");
      h.sim_time_ns = integer(f, "sim_time_ns");
      if (f.count("received_ns")) h.received_ns = integer(f, "received_ns");
      h.tracking = integer(f, "tracking") != 0;
      h.held = static_cast<int>(integer(f, "held"));
      h.position = position(f);
      log.hands.push_back(h);
    } else if (kind == "watched") {
      SeenObject o;
      o.sim_time_ns = integer(f, "sim_time_ns");
      o.received_ns = integer(f, "received_ns");
      o.held = static_cast<int>(integer(f, "held"));
      o.position = position(f);
      o.quaternion_wxyz = {num(f, "qw"), num(f, "qx"), num(f, "qy"), num(f, "qz")};
      log.watched.push_back(o);
    } else if (kind == "object") {
      SeenObject o;
      o.sim_time_ns = integer(f, "sim_time_ns");
      o.held = static_cast<int>(integer(f, "held"));
      o.position = position(f);
      o.quaternion_wxyz = {num(f, "qw"), num(f, "qx"), num(f, "qy"), num(f, "qz")};
      log.objects[static_cast<int>(integer(f, "id"))] = o;
    } else if (kind == "frame") {
      SeenFrame fr;
      fr.seq = static_cast<uint64_t>(integer(f, "seq"));
      fr.width = static_cast<int>(integer(f, "width"));
      fr.height = static_cast<int>(integer(f, "height"));
      fr.source_stamp_ns = integer(f, "source_stamp_ns");
      fr.start_ns = integer(f, "start_ns");
      fr.end_ns = integer(f, "end_ns");
      fr.received_ns = integer(f, "received_ns");
      log.frames.push_back(fr);
    }
  }
  return log;
}

MonitorLog MonitorLog::from_events_jsonl(const std::string& path) {
  MonitorLog log;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const auto record = nlohmann::json::parse(line);  // throws on a line that is not JSON
    SeenEvent e;
    e.t_ns = std::llround(record.value("t_s", 0.0) * 1e9);
    e.kind = record.value("event", "");
    e.reason = record.value("reason", "");
    log.events.push_back(e);
  }
  return log;
}

std::map<std::string, Eigen::Vector3d> read_final_poses(const std::string& summary_path) {
  std::map<std::string, Eigen::Vector3d> out;
  const auto summary = nlohmann::json::parse(read_text(summary_path), nullptr, false);
  if (!summary.is_object() || !summary.contains("final")) return out;
  for (const auto& [name, object] : summary.at("final").items()) {
    if (!object.is_object() || !object.contains("position")) continue;
    const auto& p = object.at("position");
    if (!p.is_array() || p.size() != 3) continue;
    out[name] = {p[0].get<double>(), p[1].get<double>(), p[2].get<double>()};
  }
  return out;
}

bool wait_for_line(const std::string& path, const std::string& needle, int64_t timeout_ns,
                   const std::string& after_line) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::nanoseconds(timeout_ns);
  while (std::chrono::steady_clock::now() < deadline) {
    const std::string text = read_text(path);
    std::size_t from = 0;
    if (!after_line.empty()) {
      from = text.find(after_line);
      if (from == std::string::npos) from = text.size();
    }
    if (text.find(needle, from) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

}  // namespace vcockpit::test
