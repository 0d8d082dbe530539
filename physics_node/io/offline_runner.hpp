#pragma once
// physics_node --offline: the world with no DDS, as fast as it can go, driven by a glove log (or
// by nothing for --duration), writing trajectories, events and a summary (run_outputs.hpp).
//
// Time: world time 0 is the log's first sample. A sample takes effect at the first step boundary
// at or after its stamp (the latest such sample wins), so each step uses the newest sample not
// later than its start. Lockstep replay over DDS follows the same rule and gives the same result.

#include <optional>
#include <string>

#include "physics_node/io/run_outputs.hpp"

namespace vcockpit::physics_io {

struct OfflineOptions {
  std::string scene_path;
  std::string log_path;              // empty: no hand input
  std::optional<double> duration_s;  // default: the log's span
  std::string out_dir;
  double output_hz = 100.0;
};

// Throws (ConfigError, GloveLogError, FileError, std::invalid_argument) with a message naming
// the file; on any error no output file is left behind.
RunSummary run_offline(const OfflineOptions& options);

}  // namespace vcockpit::physics_io
