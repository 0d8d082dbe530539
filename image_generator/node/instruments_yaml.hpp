#pragma once
// config/instruments.yaml -> the panel's live instruments (render/instrument_panel.hpp): the
// panel face frame, round gauges, heading displays and lamps, each naming the aircraft system
// that drives it. Every bad value is a ConfigError naming file, line and key; a system name the
// systems node does not have is reported when its systems_info arrives.

#include <string>

#include "common/config_error.hpp"
#include "image_generator/render/instrument_panel.hpp"

namespace vcockpit {

render::InstrumentsSpec load_instruments(const std::string& path);
render::InstrumentsSpec parse_instruments(const ConfigNode& root);

}  // namespace vcockpit
