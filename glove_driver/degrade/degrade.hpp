#pragma once
// Degrades a clean glove log the way real devices do, for test input that looks like a pilot's:
// every degradation optional, each with its parameters, composable, seeded (the same spec and
// seed give the same rows on every machine). They apply in the order the signal meets them:
//
//   1. grip_closure_s    the person: grip closures time-warped to this duration (grip_closure.hpp)
//   2. resample_hz       the device's sample rate (resample.hpp)
//   3. jitter            the wrist tracker's noise (tracker_jitter.hpp)
//   4. joint_noise_rad   the bend sensors' noise (joint_noise.hpp)
//   5. calibration       readings past the calibrated range (calibration_error.hpp)
//   6. quantize_bits     the glove's A/D converter over the calibrated range (joint_noise.hpp)
//   7. gaps              stretches without rows (data_loss.hpp)
//   8. dropout_rate      rows without valid data (data_loss.hpp)
//
// Named presets (presets()) set typical values; later presets and explicit values override.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "glove_driver/degrade/calibration_error.hpp"
#include "glove_driver/degrade/data_loss.hpp"
#include "glove_driver/degrade/degrade_error.hpp"
#include "glove_driver/degrade/tracker_jitter.hpp"
#include "hand/glove_sample.hpp"
#include "hand/hand_model.hpp"

namespace vcockpit::degrade {

struct DegradeSpec {
  uint64_t seed = 1;
  std::optional<double> grip_closure_s;
  std::optional<double> resample_hz;
  TrackerJitter jitter;
  double joint_noise_rad = 0.0;
  CalibrationError calibration;
  int quantize_bits = 0;  // 0: none
  Gaps gaps;
  double dropout_rate = 0.0;
};

// What degrade() did, for the log's comments and the tests.
struct DegradeReport {
  int grip_closures_sped_up = 0;
  std::vector<PlacedGap> gaps;
  std::size_t rows = 0;
  std::size_t dropouts = 0;
  std::size_t values_past_range = 0;  // joint values of valid rows outside [min, max]
};

// Throws DegradeError naming the parameter that is out of its range.
void validate(const DegradeSpec& spec);

// samples: sorted by strictly increasing time, at least one. Throws DegradeError.
std::vector<DegradedRow> degrade(std::vector<hand::GloveSample> samples,
                                 const hand::HandModel& hand, const DegradeSpec& spec,
                                 DegradeReport* report = nullptr);

// One line naming every degradation applied and its parameters ("none" for none).
std::string describe(const DegradeSpec& spec);

struct Preset {
  std::string_view name;
  std::string_view description;
  void (*apply)(DegradeSpec& spec);
};

const std::vector<Preset>& presets();
// Throws DegradeError listing the known names.
void apply_preset(std::string_view name, DegradeSpec& spec);

}  // namespace vcockpit::degrade
