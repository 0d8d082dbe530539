// degrade(): the stages in the signal's order, presets, validation, determinism.

#include <gtest/gtest.h>

#include "glove_driver/degrade/degrade.hpp"
#include "glove_driver/degrade/grip_closure.hpp"
#include "tests/unit/degrade_samples.hpp"

namespace vcockpit::degrade {
namespace {

bool same_rows(const std::vector<DegradedRow>& a, const std::vector<DegradedRow>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].valid != b[i].valid || a[i].sample.t_ns != b[i].sample.t_ns ||
        a[i].sample.p_MT_m != b[i].sample.p_MT_m ||
        a[i].sample.q_MT.coeffs() != b[i].sample.q_MT.coeffs() ||
        a[i].sample.joints_rad != b[i].sample.joints_rad) {
      return false;
    }
  }
  return true;
}

TEST(Degrade, SameSpecSameRowsOtherSeedOtherRows) {
  const auto hand = test::default_hand();
  const auto clean = test::grip_log(hand);
  DegradeSpec spec;
  apply_preset("harsh", spec);
  spec.seed = 42;
  const auto a = degrade(clean, hand, spec);
  const auto b = degrade(clean, hand, spec);
  EXPECT_TRUE(same_rows(a, b));
  spec.seed = 43;
  EXPECT_FALSE(same_rows(a, degrade(clean, hand, spec)));
}

TEST(Degrade, NothingAskedChangesNothing) {
  const auto hand = test::default_hand();
  const auto clean = test::grip_log(hand);
  DegradeReport report;
  const auto rows = degrade(clean, hand, DegradeSpec{}, &report);
  ASSERT_EQ(rows.size(), clean.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_TRUE(rows[i].valid);
    EXPECT_EQ(rows[i].sample.joints_rad, clean[i].joints_rad);
    EXPECT_EQ(rows[i].sample.p_MT_m, clean[i].p_MT_m);
  }
  EXPECT_EQ(report.dropouts, 0u);
  EXPECT_EQ(describe(DegradeSpec{}), "none");
}

TEST(Degrade, StagesComeInTheSignalsOrder) {
  const auto hand = test::default_hand();
  const auto clean = test::grip_log(hand);
  DegradeSpec spec;
  for (const char* p : {"dropouts", "glove_noise", "30hz", "grip250ms"}) apply_preset(p, spec);
  DegradeReport report;
  const auto rows = degrade(clean, hand, spec, &report);
  // resampled (4 s at 30 Hz: 121 rows), then quantised: every valid value on the 8-bit grid
  ASSERT_EQ(rows.size(), 121u);
  EXPECT_EQ(report.dropouts, static_cast<std::size_t>(std::llround(0.02 * 120)));
  EXPECT_EQ(report.grip_closures_sped_up, 1) << "the closure is found in the clean 1 kHz input";
  for (const auto& row : rows) {
    if (!row.valid) continue;
    for (int j = 0; j < hand::kJointCount; ++j) {
      const auto& range = hand.joints[j];
      const double k = (row.sample.joints_rad[j] - range.min_rad) / ((range.max_rad - range.min_rad) / 255.0);
      EXPECT_NEAR(k, std::round(k), 1e-9);
    }
  }
  const std::string text = describe(spec);
  for (const char* part : {"grip closures in 0.25 s", "resampled to 30 Hz", "joint noise 0.5 deg",
                           "8-bit joints", "dropouts 2 %", "seed 1"}) {
    EXPECT_NE(text.find(part), std::string::npos) << text;
  }
}

TEST(Degrade, OverrangeIsCountedAsValuesPastTheRange) {
  const auto hand = test::default_hand();
  DegradeSpec spec;
  apply_preset("overrange", spec);
  DegradeReport report;
  const auto rows = degrade(test::sweep_log(hand), hand, spec, &report);
  std::size_t past = 0;
  for (const auto& row : rows) {
    for (int j = 0; j < hand::kJointCount; ++j) {
      const double q = row.sample.joints_rad[j];
      past += (q < hand.joints[j].min_rad || q > hand.joints[j].max_rad) ? 1 : 0;
    }
  }
  EXPECT_EQ(report.values_past_range, past);
  // each channel reaches both ends of its range: one with a negative offset reads below it
  EXPECT_GT(past, rows.size() / 100);
}

TEST(Degrade, PresetsAndBadParametersAreNamed) {
  DegradeSpec spec;
  for (const Preset& p : presets()) {
    DegradeSpec one;
    apply_preset(p.name, one);
    EXPECT_NO_THROW(validate(one)) << p.name;
    EXPECT_NE(describe(one), "none") << p.name;
  }
  try {
    apply_preset("40hz", spec);
    FAIL() << "no error";
  } catch (const DegradeError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown preset '40hz'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("30hz"), std::string::npos) << "lists the known ones";
  }
  auto error_of = [](DegradeSpec s) -> std::string {
    try {
      validate(s);
    } catch (const DegradeError& e) {
      return e.what();
    }
    return "(no error)";
  };
  DegradeSpec bad;
  bad.resample_hz = 0.5;
  EXPECT_NE(error_of(bad).find("resample rate"), std::string::npos);
  bad = {};
  bad.dropout_rate = 1.0;
  EXPECT_NE(error_of(bad).find("dropout rate"), std::string::npos);
  bad = {};
  bad.jitter.sigma_m = std::nan("");
  EXPECT_NE(error_of(bad).find("jitter"), std::string::npos);
  bad = {};
  bad.grip_closure_s = 0.0;
  EXPECT_NE(error_of(bad).find("grip closure"), std::string::npos);
  bad = {};
  bad.quantize_bits = 25;
  EXPECT_NE(error_of(bad).find("quantisation bits"), std::string::npos);
}

}  // namespace
}  // namespace vcockpit::degrade
