// hand_calibrate: a user's hand measured on a hand-joints log (bones, knuckles, the tracker's palm
// point: hand/tracking/hand_calibration.hpp) and written as a hand.yaml, scaled per finger from
// the hand file, for openxr_hand_bridge --hand-file, glove_driver --hand-file and the scenes.
// Prints the fingertip error of the fit before and after, on the same recording.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "hand/config/calibrated_hand_yaml.hpp"
#include "hand/config/hand_yaml.hpp"
#include "hand/tracking/joints_replay.hpp"

namespace vcockpit::hand::tracking {
namespace {

struct Flags {
  std::string in_path;
  std::string out_path;
  std::string out_left_path;
  std::string hand_file = std::string(VCOCKPIT_CONFIG_DIR) + "/hand.yaml";
};

int run(const Flags& f) {
  namespace fs = std::filesystem;
  const auto same = [](const std::string& a, const std::string& b) {
    std::error_code ec;
    return !a.empty() && !b.empty() && (a == b || fs::equivalent(a, b, ec));
  };
  if (same(f.out_path, f.out_left_path)) throw CLI::ValidationError("--out and --out-left are the same file");
  if (same(f.out_path, f.hand_file) || same(f.out_left_path, f.hand_file))
    throw CLI::ValidationError("an output is the --hand-file it is scaled from: write elsewhere");
  const JointsLog log = read_joints_log(f.in_path);
  const HandModel right = load_hand_model(f.hand_file);
  if (right.left) throw CLI::ValidationError("--hand-file must describe a right hand (side: right)");
  const JointsReplay before = replay_joints(log.frames, log.space, right, false);
  const JointsReplay after = replay_joints(log.frames, log.space, right, true);
  const std::string source = std::filesystem::path(f.in_path).filename().string();
  // every output is checked before any is written: a refused run leaves no file behind
  for (int s = 0; s < 2; ++s) {
    const ReplayedHand& hand = after.hands[static_cast<std::size_t>(s)];
    const std::string& out = s == 1 ? f.out_left_path : f.out_path;
    const char* side = s == 1 ? "left" : "right";
    const char* flag = s == 1 ? "--out-left" : "--out";
    if (hand.present && out.empty())
      throw CLI::ValidationError(source + " has a " + side + " hand: give " + flag + " for its hand.yaml");
    if (!hand.present && !out.empty())
      throw CLI::ValidationError(source + " has no " + side + " hand: leave out " + flag);
    if (hand.present && hand.calibration->steady_frames == 0)
      throw JointsLogError(f.in_path + ": the " + side + " hand is never steady (palm under 0.5 m/s with a placeable palm): nothing to measure");
  }
  for (int s = 0; s < 2; ++s) {
    const ReplayedHand& hand = after.hands[static_cast<std::size_t>(s)];
    if (!hand.present) continue;
    const char* side = s == 1 ? "left" : "right";
    const std::string& out = s == 1 ? f.out_left_path : f.out_path;
    const HandCalibration& c = *hand.calibration;
    write_calibrated_hand_yaml(f.hand_file, hand.model, out,
                               {std::string("calibrated on ") + source + " (" + side + " hand, " +
                                std::to_string(c.steady_frames) + " steady frames) from " +
                                std::filesystem::path(f.hand_file).filename().string()});
    int bones = 0;
    for (bool measured : c.bones_measured) bones += measured ? 1 : 0;
    const ReplayedHand& uncalibrated = before.hands[static_cast<std::size_t>(s)];
    std::printf("%s: %s hand, %d steady frames, bones of %d of 5 fingers measured; fingertip error "
                "p50 / p99 %.1f / %.1f mm on %s, %.1f / %.1f mm calibrated\n",
                out.c_str(), side, c.steady_frames, bones, uncalibrated.tip_error_p50_m * 1e3,
                uncalibrated.tip_error_p99_m * 1e3, std::filesystem::path(f.hand_file).filename().c_str(),
                hand.tip_error_p50_m * 1e3, hand.tip_error_p99_m * 1e3);
  }
  return 0;
}

}  // namespace
}  // namespace vcockpit::hand::tracking

int main(int argc, char** argv) {
  using namespace vcockpit::hand::tracking;
  CLI::App app("hand_calibrate: a user's hand measured on a hand-joints log, written as hand.yaml");
  Flags flags;
  app.add_option("input", flags.in_path, "the hand-joints log (hand open and moving slowly helps)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--out", flags.out_path, "hand.yaml of the right hand (or the only one)");
  app.add_option("--out-left", flags.out_left_path, "hand.yaml of the left hand");
  app.add_option("--hand-file", flags.hand_file, "the hand model to scale (a right hand)")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(flags);
  } catch (const CLI::Error& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hand_calibrate: error: %s\n", e.what());
    return 1;
  }
}
