// An aircraft's systems file (systems/config/systems_yaml.cpp) bound to the default cockpit's
// controls and stepped: any text is either a model or a ConfigError / ModelError, and a model
// steps without a NaN or an infinity in any value (the expressions' promise: division by 0 and
// overflow give 0).

#include <cmath>

#include "common/yaml_config.hpp"
#include "fuzz/fuzz_support.hpp"
#include "systems/config/systems_yaml.hpp"
#include "systems/systems_engine.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  using systems::ControlSpec;
  static const std::vector<ControlSpec> kControls = {
      {"avionics_master", false, {"off", "on"}}, {"fuel_pump", true, {"off", "on"}},
      {"engine_start", true, {"off", "start"}}, {"throttle", true, {"cutoff", "idle", "full"}},
      {"gear", false, {"down", "up"}}, {"flaps", true, {"up", "approach", "landing"}},
      {"landing_lights", true, {"off", "taxi", "on"}},
      {"nav_mode", true, {"off", "vor", "gps", "loc", "app"}},
      {"heading_bug", true, {"click", "between"}}, {"master_caution", false, {"out", "pressed"}},
      {"engine_start_guard", true, {"closed", "open"}}};
  try {
    const auto root = ConfigNode::load_string(std::string(fuzz::as_text(data, size)), "aircraft.yaml");
    systems::Systems s(parse_systems_model(root), kControls);
    systems::ControlFrame frame;
    frame.position.assign(kControls.size(), 0);
    frame.q.assign(kControls.size(), 0.0);
    std::vector<systems::SystemsEvent> events;
    for (int k = 1; k <= 40; ++k) {
      // every control through its positions, the bytes choosing
      for (std::size_t c = 0; c < kControls.size(); ++c) {
        const uint8_t b = size > 0 ? data[(c + static_cast<std::size_t>(k)) % size] : 0;
        frame.position[c] = static_cast<int32_t>(b % kControls[c].positions.size());
        frame.q[c] = (b - 128) * 0.01;
      }
      frame.time_ns = k * s.period_ns();
      if (k == 20 && !s.model().failures.empty()) s.set_failure(0, true);
      s.step(frame, events);
      for (double v : s.state().value) fuzz::require(std::isfinite(v), "a system's value is not finite");
      if (events.size() > 100000) events.clear();
    }
  } catch (const ConfigError&) {
  } catch (const systems::ModelError&) {
  }
  return 0;
}
