#include "glove_driver/degrade/degrade.hpp"

#include <cmath>
#include <cstdio>

#include "common/pose.hpp"
#include "glove_driver/degrade/grip_closure.hpp"
#include "glove_driver/degrade/joint_noise.hpp"
#include "glove_driver/degrade/resample.hpp"

namespace vcockpit::degrade {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw DegradeError(what);
}

bool finite_nonnegative(double v) { return std::isfinite(v) && v >= 0; }

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

void validate(const DegradeSpec& spec) {
  if (spec.grip_closure_s) {
    require(std::isfinite(*spec.grip_closure_s) && *spec.grip_closure_s > 0,
            "grip closure duration must be a positive number of seconds");
  }
  if (spec.resample_hz) {
    require(std::isfinite(*spec.resample_hz) && *spec.resample_hz >= 1 &&
                *spec.resample_hz <= 100'000,
            "resample rate must be in [1, 100000] Hz");
  }
  require(finite_nonnegative(spec.jitter.sigma_m) && finite_nonnegative(spec.jitter.sigma_rad),
          "tracker jitter sigmas must be finite and >= 0");
  require(finite_nonnegative(spec.joint_noise_rad), "joint noise sigma must be finite and >= 0");
  require(finite_nonnegative(spec.calibration.offset_rad),
          "calibration offset must be finite and >= 0");
  require(finite_nonnegative(spec.calibration.gain) && spec.calibration.gain < 1,
          "calibration gain error must be in [0, 1)");
  require(spec.quantize_bits >= 0 && spec.quantize_bits <= 24,
          "quantisation bits must be in [1, 24] (0: none)");
  require(spec.gaps.count >= 0, "gap count must be >= 0");
  if (spec.gaps.count > 0 || !spec.gaps.at_s.empty()) {
    require(std::isfinite(spec.gaps.min_s) && std::isfinite(spec.gaps.max_s) &&
                spec.gaps.min_s > 0 && spec.gaps.max_s >= spec.gaps.min_s,
            "gap lengths need 0 < min <= max seconds");
    for (double t : spec.gaps.at_s) {
      require(std::isfinite(t) && t > 0, "gap start times must be positive seconds");
    }
  }
  require(std::isfinite(spec.dropout_rate) && spec.dropout_rate >= 0 && spec.dropout_rate < 1,
          "dropout rate must be in [0, 1)");
}

std::vector<DegradedRow> degrade(std::vector<hand::GloveSample> samples,
                                 const hand::HandModel& hand, const DegradeSpec& spec,
                                 DegradeReport* report) {
  validate(spec);
  require(!samples.empty(), "no samples to degrade");
  DegradeReport local;
  DegradeReport& r = report ? *report : local;
  r = DegradeReport{};
  if (spec.grip_closure_s) {
    r.grip_closures_sped_up = speed_up_grip_closures(samples, hand, *spec.grip_closure_s);
  }
  if (spec.resample_hz) samples = resample(samples, *spec.resample_hz);
  if (spec.jitter.sigma_m > 0 || spec.jitter.sigma_rad > 0) {
    add_tracker_jitter(samples, spec.jitter, spec.seed);
  }
  if (spec.joint_noise_rad > 0) add_joint_noise(samples, spec.joint_noise_rad, spec.seed);
  if (spec.calibration.offset_rad > 0 || spec.calibration.gain > 0) {
    apply_calibration_error(samples, hand, spec.calibration, spec.seed);
  }
  if (spec.quantize_bits > 0) quantize_joints(samples, hand, spec.quantize_bits);
  r.gaps = cut_gaps(samples, spec.gaps, spec.seed);
  std::vector<DegradedRow> rows = mark_dropouts(samples, spec.dropout_rate, spec.seed);
  r.rows = rows.size();
  for (const DegradedRow& row : rows) {
    if (!row.valid) {
      ++r.dropouts;
      continue;
    }
    for (int j = 0; j < hand::kJointCount; ++j) {
      const double q = row.sample.joints_rad[j];
      if (q < hand.joints[j].min_rad || q > hand.joints[j].max_rad) ++r.values_past_range;
    }
  }
  return rows;
}

std::string describe(const DegradeSpec& spec) {
  std::string out;
  auto add = [&](const std::string& part) { out += (out.empty() ? "" : ", ") + part; };
  if (spec.grip_closure_s) add("grip closures in " + number(*spec.grip_closure_s) + " s");
  if (spec.resample_hz) add("resampled to " + number(*spec.resample_hz) + " Hz");
  if (spec.jitter.sigma_m > 0 || spec.jitter.sigma_rad > 0) {
    add("tracker jitter " + number(spec.jitter.sigma_m * 1e3) + " mm " +
        number(rad_to_deg(spec.jitter.sigma_rad)) + " deg");
  }
  if (spec.joint_noise_rad > 0) add("joint noise " + number(rad_to_deg(spec.joint_noise_rad)) + " deg");
  if (spec.calibration.offset_rad > 0 || spec.calibration.gain > 0) {
    add("calibration error +-" + number(rad_to_deg(spec.calibration.offset_rad)) + " deg +-" +
        number(spec.calibration.gain * 100) + " % gain");
  }
  if (spec.quantize_bits > 0) add(std::to_string(spec.quantize_bits) + "-bit joints");
  if (!spec.gaps.at_s.empty()) {
    std::string at;
    for (double t : spec.gaps.at_s) at += (at.empty() ? "" : " ") + number(t);
    add("gaps of " + number(spec.gaps.min_s) + "-" + number(spec.gaps.max_s) + " s at " + at + " s");
  } else if (spec.gaps.count > 0) {
    add(std::to_string(spec.gaps.count) + " gaps of " + number(spec.gaps.min_s) + "-" +
        number(spec.gaps.max_s) + " s");
  }
  if (spec.dropout_rate > 0) add("dropouts " + number(spec.dropout_rate * 100) + " %");
  if (out.empty()) return "none";
  return out + "; seed " + std::to_string(spec.seed);
}

}  // namespace vcockpit::degrade
