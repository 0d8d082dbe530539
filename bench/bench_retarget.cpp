// bench_retarget: the time to retarget one frame of hand tracking (hand/tracking/retarget.hpp),
// both hands, over the real Leap recordings (three-claps has both hands in every frame; the
// others one). Each recording is calibrated on itself first (not timed), then every frame is
// timed as the glove driver would fit it: the frame's hands one after the other. Prints p50 / p99
// / max per frame in microseconds, and writes them as JSON with --out.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>

#include "hand/config/hand_yaml.hpp"
#include "hand/tracking/hand_calibration.hpp"
#include "hand/tracking/joints_replay.hpp"
#include "hand/tracking/leapjs_import.hpp"

using namespace vcockpit;
using namespace vcockpit::hand::tracking;

int main(int argc, char** argv) {
  CLI::App app("bench_retarget: retargeting time per frame, both hands, on the real Leap recordings");
  std::string source = VCOCKPIT_SOURCE_DIR, out_path;
  int repeats = 5;
  app.add_option("--source", source, "the source tree")->capture_default_str();
  app.add_option("--repeats", repeats, "passes over each recording")->check(CLI::Range(1, 1000));
  app.add_option("--out", out_path, "JSON of the figures");
  CLI11_PARSE(app, argc, argv);

  const hand::HandModel right = load_hand_model(source + "/config/hand.yaml");
  nlohmann::json doc = nlohmann::json::object();
  std::vector<double> all_us;
  for (const char* name : {"grab", "HandSplay-110fps", "wave", "three-claps", "gun", "brian"}) {
    const LeapImport in = import_leapjs(source + "/tests/data/real/leap/" + name + ".json");
    const Eigen::Isometry3d X_GS = placement(in.frames, JointsSpace::kXr, Eigen::Vector3d(0.36, -0.35, 0.84));
    std::vector<JointsFrame> frames;
    std::array<std::vector<JointsFrame>, 2> sides;
    for (const JointsFrame& f : in.frames) {
      frames.push_back(to_cockpit(f, X_GS));
      sides[f.left_hand ? 1 : 0].push_back(frames.back());
    }
    std::array<hand::HandModel, 2> models = {right, hand::mirrored(right)};
    for (int s = 0; s < 2; ++s)
      if (!sides[static_cast<std::size_t>(s)].empty())
        models[static_cast<std::size_t>(s)] = calibrated(models[static_cast<std::size_t>(s)], estimate_hand(models[static_cast<std::size_t>(s)], sides[static_cast<std::size_t>(s)]));
    std::vector<double> us;
    for (int r = 0; r < repeats; ++r) {
      std::array<Retargeter, 2> retarget = {Retargeter(models[0]), Retargeter(models[1])};
      // a frame: the rows that share a stamp (both hands of three-claps)
      for (std::size_t i = 0; i < frames.size();) {
        const auto start = std::chrono::steady_clock::now();
        std::size_t j = i;
        for (; j < frames.size() && frames[j].t_ns == frames[i].t_ns; ++j)
          retarget[frames[j].left_hand ? 1 : 0].fit(frames[j]);
        us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
        i = j;
      }
    }
    std::sort(us.begin(), us.end());
    const double p50 = us[us.size() / 2], p99 = us[us.size() * 99 / 100], max = us.back();
    std::printf("%-17s %5zu frames x %d: per frame p50 %6.1f us, p99 %6.1f us, max %6.1f us\n", name,
                us.size() / static_cast<std::size_t>(repeats), repeats, p50, p99, max);
    doc[name] = {{"frames", us.size() / static_cast<std::size_t>(repeats)}, {"p50_us", p50}, {"p99_us", p99}, {"max_us", max}};
    all_us.insert(all_us.end(), us.begin(), us.end());
  }
  std::sort(all_us.begin(), all_us.end());
  std::printf("all recordings: per frame p50 %.1f us, p99 %.1f us\n", all_us[all_us.size() / 2],
              all_us[all_us.size() * 99 / 100]);
  doc["all"] = {{"p50_us", all_us[all_us.size() / 2]}, {"p99_us", all_us[all_us.size() * 99 / 100]}};
  if (!out_path.empty()) std::ofstream(out_path) << doc.dump(1) << "\n";
  return 0;
}
