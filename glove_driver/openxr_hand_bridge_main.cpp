// openxr_hand_bridge: a headset's hand tracking (OpenXR, XR_EXT_hand_tracking) live on the rig.
// Both hands' joints are located at --rate-hz through the Khronos loader and the active runtime,
// placed in the cockpit (the reference space's origin at --xr-origin, turned by --xr-yaw),
// retargeted to the hand model and published on cockpit/hand_sample (hand 0 right, 1 left) with
// the joints on cockpit/tracked_joints, for as long as the runtime's session runs.

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <array>
#include <cmath>
#include <memory>
#include <optional>

#include "common/cli_finite.hpp"
#include "common/clock.hpp"
#include "common/logging.hpp"
#include "common/signals.hpp"
#include "glove_driver/node/bridged_hand.hpp"
#include "glove_driver/openxr/xr_hand_session.hpp"
#include "hand/config/hand_yaml.hpp"
#include "hand/tracking/retarget.hpp"

namespace vcockpit::glove::xr {
namespace {

struct Flags {
  DdsFlags dds;
  std::string hand_file = std::string(VCOCKPIT_CONFIG_DIR) + "/hand.yaml";
  std::string left_hand_file;
  std::string hands = "both";
  std::string space = "local";
  std::vector<double> xr_origin = {0.0, -0.05, 1.15};
  double xr_yaw_deg = 0.0;
  double rate_hz = 90.0;
  double calibrate_s = 0.0;
  int wait_readers = 1;
  double match_timeout_s = 30.0;
  double max_gap_s = 0.25;
  std::string node_name = "openxr_hand_bridge";
  std::string log_level = "info";
};

void add_flags(CLI::App& app, Flags& f) {
  add_dds_flags(app, f.dds);
  app.add_option("--hand-file,--hand-config", f.hand_file,
                 "hand model YAML: the right hand's (a left model is mirrored), e.g. one "
                 "hand_retarget --calibrated-hand wrote")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  app.add_option("--left-hand-file", f.left_hand_file,
                 "the left hand's model YAML (default: the right's mirror image)")
      ->check(CLI::ExistingFile);
  app.add_option("--hands", f.hands, "which hands to publish: both, right or left")
      ->check(CLI::IsMember({"both", "right", "left"}))
      ->capture_default_str();
  app.add_option("--space", f.space,
                 "the OpenXR reference space the joints are located in: local (origin at the "
                 "head when the session began) or stage (on the floor)")
      ->check(CLI::IsMember({"local", "stage"}))
      ->capture_default_str();
  app.add_option("--xr-origin", f.xr_origin,
                 "where the reference space's origin is in the cockpit (m; default: the design "
                 "eye of config/hmd.yaml, for the local space)")
      ->expected(3)
      ->check(kFinite)
      ->capture_default_str();
  app.add_option("--xr-yaw", f.xr_yaw_deg,
                 "the reference space's forward (-z) turned this many degrees left of the "
                 "cockpit's x")
      ->check(CLI::Range(-360.0, 360.0))
      ->capture_default_str();
  app.add_option("--rate-hz", f.rate_hz, "hand samples per second per hand")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  app.add_option("--calibrate", f.calibrate_s,
                 "measure each hand on its first this many seconds of tracking (hand open, "
                 "fingers apart, moving slowly), then retarget on the measured hand; nothing is "
                 "published meanwhile (0: use the hand files as they are)")
      ->check(CLI::Range(0.0, 60.0))
      ->capture_default_str();
  app.add_option("--wait-readers", f.wait_readers,
                 "readers of cockpit/hand_sample each hand waits for before its first sample")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--match-timeout", f.match_timeout_s, "seconds to wait for them (then it starts anyway)")
      ->check(CLI::Range(0.001, 86400.0))
      ->capture_default_str();
  app.add_option("--max-gap", f.max_gap_s,
                 "count intervals between published samples longer than this as gaps")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
  app.add_option("--node-name", f.node_name, "name on cockpit/node_status (+ /right, /left)")
      ->capture_default_str();
  app.add_option("--log-level", f.log_level, "trace, debug, info, warn, error")->capture_default_str();
}

// The reference space in G: OpenXR's axes (x right, y up, z back) onto the cockpit's, turned by
// the yaw about G's z, its origin at `origin`.
Eigen::Isometry3d X_G_space(const std::vector<double>& origin, double yaw_deg) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
               hand::tracking::R_G_xr();
  X.translation() = Eigen::Vector3d(origin[0], origin[1], origin[2]);
  return X;
}

constexpr int64_t kExitWait_ns = 5'000'000'000;

int run(const Flags& f) {
  hand::HandModel right = load_hand_model(f.hand_file);
  if (right.left) right = hand::mirrored(right);
  hand::HandModel left = f.left_hand_file.empty() ? hand::mirrored(right) : load_hand_model(f.left_hand_file);
  if (!left.left) left = hand::mirrored(left);

  XrHandSessionOptions xr_options;
  xr_options.space = f.space == "stage" ? XR_REFERENCE_SPACE_TYPE_STAGE : XR_REFERENCE_SPACE_TYPE_LOCAL;
  XrHandSession xr(xr_options);
  spdlog::info("OpenXR runtime '{}', system '{}': hand tracking, headless session, {} space",
               xr.runtime_name(), xr.system_name(), f.space);

  DdsParticipant participant(resolve_dds_options(f.dds, "glove_driver"), "glove_driver");
  std::array<std::unique_ptr<BridgedHand>, 2> hands;  // right, left
  for (int side = 0; side < 2; ++side) {
    if (f.hands != "both" && (f.hands == "left") != (side == 1)) continue;
    BridgedHandOptions options;
    options.hand_id = static_cast<uint32_t>(side);
    options.calibrate_s = f.calibrate_s;
    options.publisher.hand_id = options.hand_id;
    options.publisher.readers = f.wait_readers;
    options.publisher.match_timeout_s = f.match_timeout_s;
    options.publisher.node_name = f.node_name + (side == 1 ? "/left" : "/right");
    options.publisher.max_gap_ns = std::llround(f.max_gap_s * 1e9);
    hands[static_cast<std::size_t>(side)] =
        std::make_unique<BridgedHand>(participant, side == 1 ? left : right, options);
  }
  for (auto& hand : hands)
    if (hand && !hand->wait_for_readers()) return shutdown_requested() ? 0 : 1;
  if (f.calibrate_s > 0)
    spdlog::info("calibrating: each hand's first {:.1f} s of tracking is measured before it is "
                 "published (hand open, fingers apart, moving slowly)", f.calibrate_s);

  const Eigen::Isometry3d X_GS = X_G_space(f.xr_origin, f.xr_yaw_deg);
  const int64_t period_ns = std::llround(1e9 / f.rate_hz);
  const int64_t start_ns = monotonic_now_ns();
  int64_t next_ns = start_ns;
  bool exit_requested = false;
  int64_t exit_deadline_ns = 0;  // a runtime that does not end the session is left after it
  hand::tracking::JointsFrame frame;
  while (xr.poll()) {
    if (shutdown_requested() && !exit_requested) {
      spdlog::info("stopping: asking the runtime to end the session");
      xr.request_exit();
      exit_requested = true;
      exit_deadline_ns = monotonic_now_ns() + kExitWait_ns;
    }
    if (exit_requested && monotonic_now_ns() > exit_deadline_ns) {
      spdlog::warn("the OpenXR runtime did not end the session within {} s: leaving it",
                   ns_to_seconds(kExitWait_ns));
      break;
    }
    const int64_t now_ns = monotonic_now_ns();
    if (xr.focused()) {
      const XrTime time = xr.time_at(now_ns);
      for (int side = 0; side < 2; ++side) {
        BridgedHand* hand = hands[static_cast<std::size_t>(side)].get();
        if (hand == nullptr || !xr.locate(side == 1, time, now_ns - start_ns, frame)) continue;
        hand->take(hand::tracking::to_cockpit(frame, X_GS));
      }
    }
    for (auto& hand : hands)
      if (hand) hand->tick(now_ns);
    next_ns += period_ns;
    if (next_ns < monotonic_now_ns()) next_ns = monotonic_now_ns();  // behind: no burst to catch up
    sleep_until_ns(next_ns);
  }

  bool ok = !xr.lost();
  if (xr.lost()) spdlog::error("the OpenXR runtime lost the session (device gone?)");
  for (int side = 0; side < 2; ++side) {
    BridgedHand* hand = hands[static_cast<std::size_t>(side)].get();
    if (hand == nullptr) continue;
    ok = hand->finish() && ok;
    spdlog::info("{} hand: located {} frames, published {} samples ({} frames without a placeable "
                 "palm{}); fingertip error p50 {:.1f} mm, p99 {:.1f} mm over {} tips",
                 side == 1 ? "left" : "right", hand->located(), hand->published(), hand->unplaced(),
                 hand->calibrating() ? ", still calibrating" : "",
                 hand->tip_errors().quantile_m(0.5) * 1e3, hand->tip_errors().quantile_m(0.99) * 1e3,
                 hand->tip_errors().count());
  }
  const ValidationCounts& v = xr.validation();
  spdlog::info("OpenXR messages from the loader and API layers: {} errors, {} warnings, {} others",
               v.errors, v.warnings, v.others);
  return ok && v.errors == 0 ? 0 : 1;
}

}  // namespace
}  // namespace vcockpit::glove::xr

int main(int argc, char** argv) {
  using namespace vcockpit;
  CLI::App app("openxr_hand_bridge: a headset's hand tracking (OpenXR XR_EXT_hand_tracking), "
               "retargeted to the hand model and published on cockpit/hand_sample");
  glove::xr::Flags flags;
  glove::xr::add_flags(app, flags);
  CLI11_PARSE(app, argc, argv);
  try {
    setup_logging("openxr_hand_bridge", flags.log_level);
    install_shutdown_handlers();
    return glove::xr::run(flags);
  } catch (const CLI::Error& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}
