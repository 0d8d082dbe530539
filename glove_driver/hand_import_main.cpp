// hand_import: a hand tracker's recording into a hand-joints log (hand/tracking/joints_log.hpp),
// which the rig replays. Formats: LeapJS playback JSON (Leap Motion's recorder), MediaPipe Hands
// world landmarks (the hand landmarker's JSON, with each frame's time).

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "hand/tracking/joints_log.hpp"
#include "hand/tracking/leapjs_import.hpp"
#include "hand/tracking/mediapipe_import.hpp"

namespace vcockpit::hand::tracking {
namespace {

struct Flags {
  std::string from = "leapjs";
  std::string in_path;
  std::string out_path;
};

int run(const Flags& f) {
  std::error_code ec;
  if (std::filesystem::equivalent(f.in_path, f.out_path, ec))
    throw CLI::ValidationError("--out must not be the input file");
  TrackerImport in;
  std::string what;
  if (f.from == "leapjs") {
    LeapImport leap = import_leapjs(f.in_path);
    what = std::string("LeapJS playback") +
           (leap.protocol_version > 0 ? ", protocol " + std::to_string(leap.protocol_version) : std::string()) +
           "): mm -> m, t = timestamp - first; wrist and finger metacarpals not tracked";
    in = std::move(leap);
  } else {
    in = import_mediapipe(f.in_path);
    what = "MediaPipe world landmarks): (x, -y, -z), about the hand's centre; palm and finger "
           "metacarpals not tracked";
  }
  int rows[2] = {0, 0};
  for (const JointsFrame& frame : in.frames) ++rows[frame.left_hand ? 1 : 0];
  std::vector<std::string> comments = {
      "imported from " + std::filesystem::path(f.in_path).filename().string() + " (" + what};
  write_joints_log(f.out_path, JointsSpace::kXr, in.frames, comments);
  std::printf("%s: %zu rows (%d right, %d left) from %d frames; %d frames without hands, %d out of "
              "order (skipped)\n",
              f.out_path.c_str(), in.frames.size(), rows[0], rows[1], in.source_frames,
              in.frames_without_hands, in.frames_out_of_order);
  return 0;
}

}  // namespace
}  // namespace vcockpit::hand::tracking

int main(int argc, char** argv) {
  using namespace vcockpit::hand::tracking;
  CLI::App app("hand_import: a hand tracker's recording into a hand-joints log");
  Flags flags;
  app.add_option("--from", flags.from, "the recording's format")
      ->check(CLI::IsMember({"leapjs", "mediapipe"}))
      ->capture_default_str();
  app.add_option("input", flags.in_path, "the recording")->required()->check(CLI::ExistingFile);
  app.add_option("--out", flags.out_path, "the hand-joints log to write (atomically)")->required();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(flags);
  } catch (const CLI::Error& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hand_import: error: %s\n", e.what());
    return 1;
  }
}
