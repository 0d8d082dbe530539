#include <string>

#include "common/pose.hpp"
#include "glove_driver/degrade/degrade.hpp"

namespace vcockpit::degrade {

const std::vector<Preset>& presets() {
  static const std::vector<Preset> kPresets = {
      {"30hz", "resample to 30 Hz (a camera-based tracker)",
       [](DegradeSpec& s) { s.resample_hz = 30.0; }},
      {"60hz", "resample to 60 Hz", [](DegradeSpec& s) { s.resample_hz = 60.0; }},
      {"100hz", "resample to 100 Hz (a CyberGlove over serial)",
       [](DegradeSpec& s) { s.resample_hz = 100.0; }},
      {"120hz", "resample to 120 Hz (a magnetic tracker)",
       [](DegradeSpec& s) { s.resample_hz = 120.0; }},
      {"jitter", "wrist tracker jitter 0.5 mm, 0.2 deg (1 sigma, per axis)",
       [](DegradeSpec& s) { s.jitter = {0.5e-3, deg_to_rad(0.2)}; }},
      {"glove_noise", "joint noise 0.5 deg (1 sigma), then 8-bit quantisation",
       [](DegradeSpec& s) {
         s.joint_noise_rad = deg_to_rad(0.5);
         s.quantize_bits = 8;
       }},
      {"overrange", "calibration off by up to 5 deg and 10 % gain per channel: values past range",
       [](DegradeSpec& s) { s.calibration = {deg_to_rad(5.0), 0.10}; }},
      {"dropouts", "2 % of the rows without valid data",
       [](DegradeSpec& s) { s.dropout_rate = 0.02; }},
      {"gaps", "two stretches of 0.1-0.7 s without rows",
       [](DegradeSpec& s) { s.gaps = Gaps{2, 0.1, 0.7, {}}; }},
      {"grip500ms", "grip closures in 0.5 s", [](DegradeSpec& s) { s.grip_closure_s = 0.5; }},
      {"grip250ms", "grip closures in 0.25 s", [](DegradeSpec& s) { s.grip_closure_s = 0.25; }},
      {"typical", "60hz + jitter + glove_noise + 1 % dropouts: a good rig on a good day",
       [](DegradeSpec& s) {
         s.resample_hz = 60.0;
         s.jitter = {0.5e-3, deg_to_rad(0.2)};
         s.joint_noise_rad = deg_to_rad(0.5);
         s.quantize_bits = 8;
         s.dropout_rate = 0.01;
       }},
      {"harsh", "30hz + jitter + glove_noise + overrange + dropouts + gaps + grip250ms",
       [](DegradeSpec& s) {
         s.grip_closure_s = 0.25;
         s.resample_hz = 30.0;
         s.jitter = {0.5e-3, deg_to_rad(0.2)};
         s.joint_noise_rad = deg_to_rad(0.5);
         s.calibration = {deg_to_rad(5.0), 0.10};
         s.quantize_bits = 8;
         s.gaps = Gaps{2, 0.1, 0.7, {}};
         s.dropout_rate = 0.02;
       }},
  };
  return kPresets;
}

void apply_preset(std::string_view name, DegradeSpec& spec) {
  std::string known;
  for (const Preset& p : presets()) {
    if (p.name == name) {
      p.apply(spec);
      return;
    }
    known += (known.empty() ? "" : ", ") + std::string(p.name);
  }
  throw DegradeError("unknown preset '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace vcockpit::degrade
