// fingertip_error: how far the drawn index fingertip is from where the glove puts it when the
// frame is finished, with and without the image generator's hand prediction. Reads the image
// generator's --frame-log (per frame and hand: the stamps of the hand state drawn, the tracked
// index fingertip as received and as predicted for the frame's end) and the glove log the run
// replayed in real time (rate 1): at render end the glove is at log time
//   t = sample_time + (render_end - source_stamp)
// (the source stamp is the glove driver's clock when it published the sample the state shows);
// the log's hand there (interpolated, forward kinematics of the scene's hand model) is the truth.
//   fingertip_error --frame-log F.csv --log GLOVE.csv [--scene cockpit.yaml] [--skip 1.0]
//                   [--out result.json]
// Prints p50/p99/max of both errors (mm) and the prediction's horizon; writes them as JSON.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "common/json_file.hpp"
#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/hand_input.hpp"
#include "physics_node/io/sample_interpolation.hpp"

namespace {

using namespace vcockpit;

struct FrameRow {
  int64_t render_end_ns = 0;
  uint32_t hand_id = 0;
  int64_t sample_time_ns = 0;
  int64_t source_stamp_ns = 0;
  int64_t horizon_ns = 0;
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  Eigen::Vector3d predicted = Eigen::Vector3d::Zero();
};

std::vector<FrameRow> read_frame_log(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  std::vector<FrameRow> rows;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line_no == 1 || line.empty()) continue;  // header
    FrameRow r;
    unsigned long long frame = 0;
    long long end = 0, sample = 0, stamp = 0, horizon = 0;
    unsigned hand = 0;
    if (std::sscanf(line.c_str(), "%llu,%lld,%u,%lld,%lld,%lld,%lf,%lf,%lf,%lf,%lf,%lf", &frame,
                    &end, &hand, &sample, &stamp, &horizon, &r.tip.x(), &r.tip.y(), &r.tip.z(),
                    &r.predicted.x(), &r.predicted.y(), &r.predicted.z()) != 12) {
      throw std::runtime_error(path + ":" + std::to_string(line_no) + ": not a frame-log row");
    }
    r.render_end_ns = end;
    r.hand_id = hand;
    r.sample_time_ns = sample;
    r.source_stamp_ns = stamp;
    r.horizon_ns = horizon;
    rows.push_back(r);
  }
  return rows;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5)];
}

nlohmann::ordered_json summary(const std::vector<double>& mm) {
  return {{"p50", percentile(mm, 0.5)}, {"p99", percentile(mm, 0.99)},
          {"max", mm.empty() ? 0.0 : *std::max_element(mm.begin(), mm.end())}};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("fingertip_error: the drawn index fingertip against the glove log at frame end");
  std::string frame_log, log_path, out_path;
  std::string scene_path = std::string(VCOCKPIT_CONFIG_DIR) + "/cockpit.yaml";
  double skip_s = 1.0;
  app.add_option("--frame-log", frame_log, "image_generator --frame-log CSV")->required()
      ->check(CLI::ExistingFile);
  app.add_option("--log", log_path, "the glove log replayed (real time, rate 1)")->required()
      ->check(CLI::ExistingFile);
  app.add_option("--scene", scene_path, "the scene (its hand model)")->check(CLI::ExistingFile)
      ->capture_default_str();
  app.add_option("--skip", skip_s, "seconds of frames left out at the start (the run settling)")
      ->capture_default_str();
  app.add_option("--out", out_path, "write the figures here (JSON)");
  CLI11_PARSE(app, argc, argv);
  try {
    const physics::Scene scene = load_scene(scene_path);
    const std::vector<FrameRow> rows = read_frame_log(frame_log);
    if (rows.empty()) throw std::runtime_error(frame_log + ": no frames");
    std::vector<double> plain_mm, predicted_mm, horizon_ms;
    for (const hand::HandModel& model : scene.hands) {
      const uint32_t hand_id = model.left ? 1 : 0;
      const hand::GloveLog log = hand::read_glove_log(log_path, model);
      if (log.left_hand != model.left || log.samples.size() < 2) continue;
      const auto& samples = log.samples;
      const int64_t first_end = rows.front().render_end_ns;
      for (const FrameRow& r : rows) {
        if (r.hand_id != hand_id || r.render_end_ns - first_end < static_cast<int64_t>(skip_s * 1e9))
          continue;
        const int64_t t_ns = r.sample_time_ns + (r.render_end_ns - r.source_stamp_ns);
        if (t_ns < samples.front().t_ns || t_ns > samples.back().t_ns) continue;
        const auto after = std::lower_bound(samples.begin(), samples.end(), t_ns,
                                            [](const hand::GloveSample& s, int64_t t) { return s.t_ns < t; });
        const hand::GloveSample& b = *after;
        const hand::GloveSample& a = after == samples.begin() ? b : *(after - 1);
        const hand::GloveSample truth = a.t_ns == b.t_ns ? b : physics_io::interpolate_sample(a, b, t_ns);
        physics::HandInput input = physics_io::hand_input_from_glove(model, truth);
        hand::clamp_to_limits(model, input.q_rad);
        hand::HandLinkPoses poses;
        hand::forward_kinematics(model, input.q_rad, poses);
        const Eigen::Vector3d tip_G =
            input.X_GH * poses.p_H_tip[static_cast<std::size_t>(hand::Finger::kIndex)];
        plain_mm.push_back(1e3 * (r.tip - tip_G).norm());
        predicted_mm.push_back(1e3 * (r.predicted - tip_G).norm());
        horizon_ms.push_back(static_cast<double>(r.horizon_ns) * 1e-6);
      }
    }
    if (plain_mm.empty()) throw std::runtime_error("no frame falls within the log's time");
    nlohmann::ordered_json j;
    j["frames"] = plain_mm.size();
    j["without_prediction_mm"] = summary(plain_mm);
    j["with_prediction_mm"] = summary(predicted_mm);
    j["horizon_ms"] = summary(horizon_ms);
    std::printf("%zu frames: fingertip error without prediction p50 %.1f mm, p99 %.1f mm; with "
                "prediction p50 %.1f mm, p99 %.1f mm (horizon p50 %.1f ms)\n",
                plain_mm.size(), percentile(plain_mm, 0.5), percentile(plain_mm, 0.99),
                percentile(predicted_mm, 0.5), percentile(predicted_mm, 0.99),
                percentile(horizon_ms, 0.5));
    if (!out_path.empty()) write_json_file(out_path, j);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fingertip_error: %s\n", e.what());
    return 1;
  }
}
