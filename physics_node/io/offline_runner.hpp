#pragma once
// physics_node --offline: the world with no DDS, as fast as it can go, driven by a glove log (or
// by nothing for --duration), writing trajectories, events and a summary (run_outputs.hpp).
//
// Time: the ReplayDriver's rule (replay_driver.hpp, one driver per hand on one timeline), which
// lockstep replay over DDS shares, so both give the same result: the hand interpolated between samples, gaps beyond the max gap held,
// the glove lost after the timeout. Without --duration the run ends at the last step that ends
// by the last sample (where a lockstep replay of the log stops); with a longer one the hand holds the last sample (and the glove is lost after the timeout, as a live
// node would find). Every sample passes the SampleValidator a live node applies; the log's and
// the validator's counts go to summary.json ("input") and the log. No YAML and no DDS here: the
// caller loads the scene.

#include <optional>
#include <string>
#include <vector>

#include "physics_node/io/input_timing.hpp"
#include "physics_node/io/run_outputs.hpp"
#include "physics_node/physics/scene.hpp"

namespace vcockpit::physics_io {

struct OfflineOptions {
  std::string scene_path;            // for the summary (the scene itself comes loaded)
  // Glove logs, one per hand (each log's `# hand:` line names its hand; the scene must have it),
  // on one timeline: their stamps share a clock, and the earliest first sample is world time 0.
  // Empty: no hand input.
  std::vector<std::string> log_paths;
  std::optional<double> duration_s;  // default: the log's span
  std::string out_dir;
  double output_hz = 100.0;
  double control_frame_hz = 100.0;  // control_frames.csv (the aircraft systems' input)
  InputTiming timing;  // --max-gap, --glove-timeout
};

// Throws (GloveLogError, FileError, std::invalid_argument) with a message naming the file; on any
// error no output file is left behind.
RunSummary run_offline(physics::Scene scene, const OfflineOptions& options);

}  // namespace vcockpit::physics_io
