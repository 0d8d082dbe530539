// hand_retarget: a hand-joints log (hand_import's output, or a tracker's own) retargeted to the
// DH hand and written as glove logs, one per hand, which the offline runner and the glove driver
// replay as any glove log. Optionally calibrates the hand on the recording and writes it as a
// hand.yaml (hand/tracking/hand_calibration.hpp).

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <optional>

#include "common/cli_finite.hpp"
#include "hand/config/calibrated_hand_yaml.hpp"
#include "hand/config/hand_yaml.hpp"
#include "hand/glove_log.hpp"
#include "hand/tracking/joints_replay.hpp"

namespace vcockpit::hand::tracking {
namespace {

struct Flags {
  std::string in_path;
  std::string out_path;
  std::string out_left_path;
  std::string hand_file = std::string(VCOCKPIT_CONFIG_DIR) + "/hand.yaml";
  std::string calibrated_hand;
  std::string calibrated_left_hand;
  std::vector<double> palm_at = {0.36, -0.35, 0.84};
};

std::string mm(double m) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f mm", m * 1e3);
  return text;
}

int run(const Flags& f) {
  const JointsLog log = read_joints_log(f.in_path);
  const HandModel right = load_hand_model(f.hand_file);
  if (right.left) throw CLI::ValidationError("--hand-file must describe a right hand (side: right)");
  const bool calibrate = !f.calibrated_hand.empty() || !f.calibrated_left_hand.empty();
  const Eigen::Vector3d palm_G(f.palm_at[0], f.palm_at[1], f.palm_at[2]);
  const JointsReplay replay = replay_joints(log.frames, log.space, right, calibrate, palm_G);
  const std::string source = std::filesystem::path(f.in_path).filename().string();
  // every output is checked before any is written: a refused run leaves no file behind
  for (int s = 0; s < 2; ++s) {
    const ReplayedHand& hand = replay.hands[static_cast<std::size_t>(s)];
    const std::string& out = s == 1 ? f.out_left_path : f.out_path;
    const char* flag = s == 1 ? "--out-left" : "--out";
    if (hand.present && out.empty())
      throw CLI::ValidationError(source + " has a " + (s == 1 ? "left" : "right") + " hand: give " + flag + " for its glove log");
    if (!hand.present && !out.empty())
      throw CLI::ValidationError(source + " has no " + (s == 1 ? "left" : "right") + " hand: leave out " + flag);
    if (hand.present && hand.samples.empty())
      throw JointsLogError(f.in_path + ": no frame of the " + (s == 1 ? "left" : "right") + " hand has a palm to place");
  }
  for (int s = 0; s < 2; ++s) {
    const ReplayedHand& hand = replay.hands[static_cast<std::size_t>(s)];
    const char* side = s == 1 ? "left" : "right";
    const std::string& out = s == 1 ? f.out_left_path : f.out_path;
    const std::string& hand_out = s == 1 ? f.calibrated_left_hand : f.calibrated_hand;
    if (!hand.present) continue;
    if (!hand_out.empty()) {
      write_calibrated_hand_yaml(f.hand_file, hand.model, hand_out,
                                 {std::string("calibrated on ") + source + " (" + side + " hand, " +
                                  std::to_string(hand.calibration->steady_frames) + " steady frames) from " +
                                  std::filesystem::path(f.hand_file).filename().string()});
    }
    const std::vector<std::string> comments = {
        std::string("retargeted from the hand-joints log ") + source + " (" + side + " hand) on " +
            (hand_out.empty() ? f.hand_file : hand_out),
        "placed with the recording's mean palm at (" + std::to_string(palm_G.x()) + ", " +
            std::to_string(palm_G.y()) + ", " + std::to_string(palm_G.z()) + ") m",
        "fingertip error of the fit p50 " + mm(hand.tip_error_p50_m) + ", p99 " + mm(hand.tip_error_p99_m) +
            "; frames without a placeable palm: " + std::to_string(hand.unplaced_frames)};
    write_glove_log(out, hand.samples, s == 1, comments);
    std::printf("%s: %zu samples (%s hand), fingertip error p50 %s, p99 %s%s\n", out.c_str(),
                hand.samples.size(), side, mm(hand.tip_error_p50_m).c_str(),
                mm(hand.tip_error_p99_m).c_str(), hand_out.empty() ? "" : (", hand " + hand_out).c_str());
  }
  return 0;
}

}  // namespace
}  // namespace vcockpit::hand::tracking

int main(int argc, char** argv) {
  using namespace vcockpit::hand::tracking;
  CLI::App app("hand_retarget: a hand-joints log retargeted to the hand model, written as glove logs");
  Flags flags;
  app.add_option("input", flags.in_path, "the hand-joints log")->required()->check(CLI::ExistingFile);
  app.add_option("--out", flags.out_path, "glove log of the right hand (or the only one)");
  app.add_option("--out-left", flags.out_left_path, "glove log of the left hand");
  app.add_option("--hand-file", flags.hand_file, "hand model YAML (a right hand; the left is its mirror image)")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  app.add_option("--calibrated-hand", flags.calibrated_hand,
                 "calibrate the right hand on the recording, write it here and retarget on it");
  app.add_option("--calibrated-left-hand", flags.calibrated_left_hand, "the same for the left hand");
  app.add_option("--palm-at", flags.palm_at, "where the recording's mean palm goes in the cockpit (m)")
      ->expected(3)
      ->check(vcockpit::kFinite)
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(flags);
  } catch (const CLI::Error& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hand_retarget: error: %s\n", e.what());
    return 1;
  }
}
