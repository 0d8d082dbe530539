#include "systems/systems_recorder.hpp"

#include <cstdio>
#include <filesystem>

namespace vcockpit::systems {
namespace {

const std::string& created(const std::string& dir) {
  std::filesystem::create_directories(dir);
  return dir;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::string event_json(const Systems& systems, const SystemsEvent& e) {
  char t[64];
  std::snprintf(t, sizeof t, "{\"t_ns\": %lld, \"t_s\": %.3f, ", static_cast<long long>(e.time_ns),
                static_cast<double>(e.time_ns) * 1e-9);
  std::string out = t;
  if (e.kind == SystemsEventKind::kChange) {
    const Element& el = systems.model().elements[static_cast<std::size_t>(e.index)];
    const auto text = [&](double v) {
      return el.kind == ElementKind::kMachine ? quoted(systems.value_text(e.index, v))
                                              : systems.value_text(e.index, v);
    };
    out += "\"event\": \"change\", \"system\": " + quoted(el.name) + ", \"from\": " + text(e.from) +
           ", \"to\": " + text(e.to) + "}";
  } else {
    const Failure& f = systems.model().failures[static_cast<std::size_t>(e.index)];
    out += std::string("\"event\": \"") +
           (e.kind == SystemsEventKind::kFailureInserted ? "failure_inserted" : "failure_cleared") +
           "\", \"failure\": " + quoted(f.name) + "}";
  }
  return out;
}

SystemsRecorder::SystemsRecorder(const std::string& out_dir, const Systems& systems)
    : events_(created(out_dir) + "/systems_events.jsonl"), values_(out_dir + "/systems.csv") {
  std::string header = "t_ns";
  for (const Element& e : systems.model().elements) header += "," + e.name;
  values_.write(header + "\n");
}

void SystemsRecorder::after_step(const Systems& systems) {
  std::string row = std::to_string(systems.state().time_ns);
  char number[32];
  for (double v : systems.state().value) {
    std::snprintf(number, sizeof number, ",%.9g", v);
    row += number;
  }
  values_.write(row + "\n");
}

void SystemsRecorder::write(const Systems& systems, const SystemsEvent& event) {
  events_.write(event_json(systems, event) + "\n");
  ++events_written_;
}

void SystemsRecorder::commit() {
  events_.commit();
  values_.commit();
}

}  // namespace vcockpit::systems
