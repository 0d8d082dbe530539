// physics_node: the central computer of the paper's prototype. `--offline` runs the world with no
// DDS from a scene and a glove log, as fast as it can, and writes trajectories, events and a
// summary.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "common/logging.hpp"
#include "physics_node/io/offline_runner.hpp"

int main(int argc, char** argv) {
  using namespace vcockpit;
  CLI::App app("physics_node: hand kinematics, collision, virtual forces, rigid-body motion and "
               "the stable grasp of the virtual cockpit");
  bool offline = false;
  physics_io::OfflineOptions options;
  options.scene_path = std::string(VCOCKPIT_CONFIG_DIR) + "/cockpit.yaml";
  std::string log_level = "info";
  app.add_flag("--offline", offline, "run without DDS, as fast as possible, and write DIR outputs");
  app.add_option("--scene", options.scene_path, "scene YAML")->capture_default_str();
  app.add_option("--log", options.log_path, "glove log CSV driving the hand (--offline)");
  app.add_option("--duration", options.duration_s,
                 "simulated seconds (default: the log's span)");
  app.add_option("--out", options.out_dir, "output directory (--offline)");
  app.add_option("--output-hz", options.output_hz, "trajectory rows per second")
      ->capture_default_str();
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    setup_logging("physics_node", log_level);
    if (!offline) {
      spdlog::error("the DDS (real-time and lockstep) mode is not built yet; use --offline");
      return 2;
    }
    if (options.out_dir.empty()) throw CLI::ValidationError("--offline needs --out DIR");
    const auto summary = physics_io::run_offline(options);
    spdlog::info("{} steps ({} substeps each), {:.3f} s simulated in {:.3f} s wall ({:.1f}x real "
                 "time); {} grasp(s), {} release(s); hand penetration max {:.2f} mm",
                 summary.steps, summary.substeps, summary.simulated_s, summary.wall_s,
                 summary.wall_s > 0 ? summary.simulated_s / summary.wall_s : 0.0, summary.grasps,
                 summary.releases, summary.penetration_max_m * 1e3);
    return 0;
  } catch (const CLI::Error& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
