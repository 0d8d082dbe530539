// glove_degrade: degrades a glove log the way real devices do (lower sample rates, tracker
// jitter, joint noise and quantisation, readings past the calibrated range, dropouts, gaps,
// faster grip closures), seeded, into a new log. The library does the work (degrade.hpp).

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "common/cli_finite.hpp"
#include "common/pose.hpp"
#include "glove_driver/degrade/degrade.hpp"
#include "glove_driver/degrade/degraded_log_file.hpp"
#include "hand/glove_log.hpp"
#include "hand/config/hand_yaml.hpp"

namespace vcockpit::degrade {
namespace {

struct Flags {
  std::string in_path;
  std::string out_path;
  std::string hand_config = std::string(VCOCKPIT_CONFIG_DIR) + "/hand.yaml";
  std::vector<std::string> presets;
  bool list_presets = false;
  uint64_t seed = 1;
  std::optional<double> grip_closure_s;
  std::optional<double> rate_hz;
  std::optional<double> jitter_mm;
  std::optional<double> jitter_deg;
  std::optional<double> joint_noise_deg;
  std::optional<double> overrange_deg;
  std::optional<double> overrange_gain;
  std::optional<int> quantize_bits;
  std::optional<int> gaps;
  std::optional<double> gap_min_s;
  std::optional<double> gap_max_s;
  std::vector<double> gap_at_s;
  std::optional<double> dropout_rate;
};

void add_flags(CLI::App& app, Flags& f) {
  app.add_option("--in", f.in_path, "glove log to degrade")->check(CLI::ExistingFile);
  app.add_option("--out", f.out_path, "degraded glove log to write (atomically)");
  app.add_option("--hand-config", f.hand_config, "hand model YAML (joint ranges, kinematics)")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  app.add_option("--preset", f.presets, "named degradation, repeatable; see --list-presets");
  app.add_flag("--list-presets", f.list_presets, "print the presets and exit");
  app.add_option("--seed", f.seed, "seed of every random draw")->capture_default_str();
  app.add_option("--grip-closure", f.grip_closure_s, "time-warp grip closures to S seconds")
      ->check(CLI::PositiveNumber & kFinite);
  app.add_option("--rate-hz", f.rate_hz, "resample to this rate")
      ->check(CLI::Range(1.0, 100000.0) & kFinite);
  app.add_option("--jitter-mm", f.jitter_mm, "tracker position jitter, 1 sigma per axis")
      ->check(CLI::NonNegativeNumber & kFinite);
  app.add_option("--jitter-deg", f.jitter_deg, "tracker orientation jitter, 1 sigma per axis")
      ->check(CLI::NonNegativeNumber & kFinite);
  app.add_option("--joint-noise-deg", f.joint_noise_deg, "joint noise, 1 sigma")
      ->check(CLI::NonNegativeNumber & kFinite);
  app.add_option("--overrange-deg", f.overrange_deg,
                 "calibration offset per channel, uniform in +-DEG")
      ->check(CLI::NonNegativeNumber & kFinite);
  app.add_option("--overrange-gain", f.overrange_gain,
                 "calibration gain error per channel, uniform in 1 +- G")
      ->check(CLI::Range(0.0, 0.99) & kFinite);
  app.add_option("--quantize-bits", f.quantize_bits, "quantise joints over their range (0: off)")
      ->check(CLI::Range(0, 24));
  app.add_option("--gaps", f.gaps, "stretches without rows, at random places")
      ->check(CLI::Range(0, 1000));
  app.add_option("--gap-min", f.gap_min_s, "shortest gap (s)")->check(CLI::PositiveNumber & kFinite);
  app.add_option("--gap-max", f.gap_max_s, "longest gap (s)")->check(CLI::PositiveNumber & kFinite);
  app.add_option("--gap-at", f.gap_at_s, "a gap starting S seconds into the log (repeatable; "
                                         "instead of random places)")
      ->check(CLI::PositiveNumber & kFinite);
  app.add_option("--dropout-rate", f.dropout_rate, "share of rows without valid data")
      ->check(CLI::Range(0.0, 0.99) & kFinite);
}

DegradeSpec spec_from(const Flags& f) {
  DegradeSpec spec;
  for (const auto& name : f.presets) apply_preset(name, spec);
  spec.seed = f.seed;
  if (f.grip_closure_s) spec.grip_closure_s = *f.grip_closure_s;
  if (f.rate_hz) spec.resample_hz = *f.rate_hz;
  if (f.jitter_mm) spec.jitter.sigma_m = *f.jitter_mm * 1e-3;
  if (f.jitter_deg) spec.jitter.sigma_rad = deg_to_rad(*f.jitter_deg);
  if (f.joint_noise_deg) spec.joint_noise_rad = deg_to_rad(*f.joint_noise_deg);
  if (f.overrange_deg) spec.calibration.offset_rad = deg_to_rad(*f.overrange_deg);
  if (f.overrange_gain) spec.calibration.gain = *f.overrange_gain;
  if (f.quantize_bits) spec.quantize_bits = *f.quantize_bits;
  if (f.gaps) spec.gaps.count = *f.gaps;
  if (f.gap_min_s) spec.gaps.min_s = *f.gap_min_s;
  if (f.gap_max_s) spec.gaps.max_s = *f.gap_max_s;
  if (!f.gap_at_s.empty()) spec.gaps.at_s = f.gap_at_s;
  if (f.dropout_rate) spec.dropout_rate = *f.dropout_rate;
  return spec;
}

int run(const Flags& f) {
  if (f.list_presets) {
    for (const Preset& p : presets()) {
      std::printf("%-12.*s %.*s\n", static_cast<int>(p.name.size()), p.name.data(),
                  static_cast<int>(p.description.size()), p.description.data());
    }
    return 0;
  }
  if (f.in_path.empty() || f.out_path.empty()) {
    throw CLI::ValidationError("give --in LOG and --out LOG (or --list-presets)");
  }
  std::error_code ec;
  if (std::filesystem::equivalent(f.in_path, f.out_path, ec)) {
    throw CLI::ValidationError("--out must not be the --in log");
  }
  const DegradeSpec spec = spec_from(f);
  validate(spec);
  const hand::HandModel hand = load_hand_model(f.hand_config);
  const hand::GloveLog log = hand::read_glove_log(f.in_path, hand);
  DegradeReport report;
  const auto rows = degrade(log.samples, hand, spec, &report);
  std::vector<std::string> comments;
  for (const auto& c : log.comments) {
    if (c.rfind("hand:", 0) != 0 && c != "vcockpit glove log") comments.push_back(c);
  }
  comments.push_back("degraded from " + std::filesystem::path(f.in_path).filename().string() +
                     ": " + describe(spec));
  write_degraded_log(f.out_path, rows, log.left_hand, comments);
  std::printf("%s: %zu rows (%zu dropouts, %zu gaps, %d grip closures sped up, %zu joint values "
              "past range) from %zu\n",
              f.out_path.c_str(), report.rows, report.dropouts, report.gaps.size(),
              report.grip_closures_sped_up, report.values_past_range, log.samples.size());
  return 0;
}

}  // namespace
}  // namespace vcockpit::degrade

int main(int argc, char** argv) {
  using namespace vcockpit;
  CLI::App app("glove_degrade: degrades a glove log the way real gloves and trackers do "
               "(sample rate, jitter, noise, quantisation, range, dropouts, gaps, fast grips)");
  degrade::Flags flags;
  degrade::add_flags(app, flags);
  CLI11_PARSE(app, argc, argv);
  try {
    return degrade::run(flags);
  } catch (const CLI::Error& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glove_degrade: error: %s\n", e.what());
    return 1;
  }
}
