// image_generator: renders the virtual cockpit off-screen in stereo for the head-mounted display
// (OSMesa, no window, no X server), publishes cockpit/frame_info per frame and writes PNG
// snapshots. The hand's geometry comes from the physics node (cockpit/hand_info), not a file.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <optional>

#include "common/logging.hpp"
#include "common/signals.hpp"
#include "image_generator/node/ig_loop.hpp"

int main(int argc, char** argv) {
  using namespace vcockpit;
  CLI::App app("image_generator: off-screen stereo rendering of the virtual cockpit for the HMD");
  DdsFlags dds_flags;
  image_generator::IgOptions options;
  std::string hmd_path = std::string(VCOCKPIT_CONFIG_DIR) + "/hmd.yaml";
  std::string layout = "side";
  std::string log_level = "info";
  app.add_option("--hmd", hmd_path, "HMD config YAML (IPD, per-eye FOV, resolution, eye point)")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  app.add_option("--out", options.out_dir, "directory for PNG snapshots (none if not given)");
  app.add_option("--snapshot-every", options.snapshot_every, "frames between snapshots (0: none)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--snapshot-layout", layout, "side (both eyes in one PNG), left, right, both")
      ->check(CLI::IsMember({"side", "left", "right", "both"}))
      ->capture_default_str();
  app.add_option("--frames", options.frames, "render this many frames and exit (0: until Ctrl-C)");
  std::optional<double> fps;
  app.add_option("--fps", fps,
                 "frame rate to pace at (default: the HMD's refresh_hz; 0: as fast as possible)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("!--no-background-cache", options.background_cache,
               "draw the whole cockpit every frame (default: the static cockpit is drawn once and "
               "copied, only what moves is drawn)");
  app.add_flag("--predict-hand", options.predict_hand,
               "draw the hands extrapolated to the moment the frame will be finished");
  app.add_option("--frame-log", options.frame_log,
                 "CSV of every frame's hand: stamps, the tracked index fingertip as drawn and as "
                 "predicted (for bench/fingertip_error)");
  app.add_option("--wait-timeout", options.wait_timeout_s,
                 "seconds to wait for the scene (cockpit/object_info) before giving up")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--ghost-threshold", options.ghost_threshold_m,
                 "draw the tracked hand as thin pale bones while it is farther than this (m) from "
                 "the simulated hand")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_flag("--tracked-joints", options.show_tracked_joints,
               "draw what a hand tracker saw (cockpit/tracked_joints, from glove_driver --source "
               "joints) as small dots beside each hand");
  app.add_option("--instruments", options.instruments_path,
                 "draw the panel's live instruments (config/instruments.yaml) from the aircraft's "
                 "systems (cockpit/systems_state)")
      ->check(CLI::ExistingFile);
  app.add_option("--node-name", options.node_name, "name on cockpit/node_status")
      ->capture_default_str();
  std::string video_view = "left";
  app.add_option("--video", options.video_path,
                 "record the run as an H.264 MP4 here (the ffmpeg program, off the render thread; "
                 "the sim time burned in; an existing file is kept and -2, -3... added)");
  app.add_option("--video-view", video_view, "left (the left eye) or side (both eyes)")
      ->check(CLI::IsMember({"left", "side"}))
      ->capture_default_str();
  app.add_option("--video-scale-down", options.video_scale_down,
                 "divide the video's width and height by this (1: full size)")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  app.add_option("--preview-hz", options.preview_hz,
                 "pictures of the left eye a second on cockpit/preview_frame for instructor "
                 "displays, made only while one is watching (0: none)")
      ->check(CLI::Range(0.0, 30.0))
      ->capture_default_str();
  app.add_option("--stats-out", options.stats_out,
                 "write the run's frames per second and render times (JSON) here at exit");
  add_dds_flags(app, dds_flags);
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  options.video_side_by_side = video_view == "side";
  options.layout = layout == "left"    ? image_generator::SnapshotLayout::kLeft
                   : layout == "right" ? image_generator::SnapshotLayout::kRight
                   : layout == "both"  ? image_generator::SnapshotLayout::kBothSeparate
                                       : image_generator::SnapshotLayout::kSideBySide;
  try {
    setup_logging("image_generator", log_level);
    install_shutdown_handlers();
    const HmdSetup hmd = load_hmd_config(hmd_path);
    options.fps = fps.value_or(hmd.refresh_hz);
    DdsParticipant participant(resolve_dds_options(dds_flags, "image_generator"), options.node_name);
    return image_generator::run_image_generator(participant, hmd, options);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
