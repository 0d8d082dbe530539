// The real Leap Motion "grab" (tests/data/real/README.md) on its bar, degraded the ways other
// devices deliver a hand (glove_driver/degrade: a camera tracker's 30 Hz, a serial glove's 100 Hz,
// wrist jitter, bend-sensor noise and quantisation, calibration past the range, dropouts, gaps,
// faster closures), each preset with seeds of its own. Whatever the device, what a user expects
// of the recorded fist stays the same:
//   - the first GRASP by 0.30 s (the fist closes at about 0.18 s; the recording closes a second
//     time at about 1.3 s, and may take the bar again where it fell);
//   - held until the hand opens: the first RELEASE between 0.70 and 1.00 s, for the hand opening;
//   - no link more than 1 mm inside the bar or any static object, at any step (a thumb wedged
//     between the pedestal and the held bar was bent out of the pedestal 1.9-5.0 mm into the bar
//     in one step, with noise, calibration error or gaps: ProxyHand::bend_out now keeps the
//     finger's other contacts at their limits, and bends out of panels alone at most 0.02 rad a
//     step);
//   - a free bar (before the grasp, until 0.3 s after the release) never faster than 0.5 m/s
//     horizontally.
// Not here: `harsh`, whose 0.1-0.7 s gaps can take the whole closure away (seed 3 grasps at
// 0.70 s, when the samples resume with the fist already closed round the bar), and the bar's
// place after the release (real_leap_grab_test prints it: the closing fist carries the bar off
// its 18 mm pedestal).

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <string>
#include <vector>

#include "glove_driver/degrade/degrade.hpp"
#include "hand/glove_log.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/grip_replay.hpp"
#include "tests/scenario/real_grip/real_grip_run.hpp"

namespace vcockpit {
namespace {

std::string source_dir() { return std::getenv("VCOCKPIT_SOURCE_DIR"); }

struct DegradedCase {
  const char* preset;
  uint64_t seed;
};

void PrintTo(const DegradedCase& c, std::ostream* out) { *out << c.preset << " seed " << c.seed; }

std::string case_name(const ::testing::TestParamInfo<DegradedCase>& info) {
  return std::string(info.param.preset) + "_seed" + std::to_string(info.param.seed);
}

std::vector<DegradedCase> cases() {
  std::vector<DegradedCase> out;
  // deterministic: one seed
  for (const char* preset : {"30hz", "60hz", "100hz", "120hz", "grip500ms", "grip250ms"})
    out.push_back({preset, 1});
  // random draws: three seeds each
  for (const char* preset : {"jitter", "glove_noise", "overrange", "dropouts", "gaps", "typical"})
    for (uint64_t seed = 1; seed <= 3; ++seed) out.push_back({preset, seed});
  return out;
}

class RealLeapDegraded : public ::testing::TestWithParam<DegradedCase> {};

TEST_P(RealLeapDegraded, TheFistHoldsTheBarUntilItOpensAndNoLinkSinksIn) {
  const physics::Scene scene = load_scene(source_dir() + "/tests/data/real/leap_grab_scene.yaml");
  const int bar = scene.find_object("bar");
  const int pedestal = scene.find_object("pedestal");
  ASSERT_GE(bar, 0);
  ASSERT_GE(pedestal, 0);
  const hand::GloveLog log =
      hand::read_glove_log(source_dir() + "/tests/data/real/leap_grab.csv", scene.hands.at(0));

  degrade::DegradeSpec spec;
  spec.seed = GetParam().seed;
  degrade::apply_preset(GetParam().preset, spec);
  std::vector<hand::GloveSample> samples;
  for (const degrade::DegradedRow& row : degrade::degrade(log.samples, scene.hands.at(0), spec))
    if (row.valid) samples.push_back(row.sample);  // a dropout row is read as no sample
  ASSERT_GT(samples.size(), 50u);  // 3 s, at 30 Hz and up

  const real_grip::SettlingRun settling = real_grip::replay_settling(scene, samples, bar, pedestal);
  const physics_io::GripReplay& run = settling.run;
  const double fastest_free_settling_mps = settling.fastest_free_settling_mps;
  std::printf("%s seed %llu: %sdeepest link in the bar %.2f mm (at %.3f s), in a static object "
              "%.2f mm; fastest free until 0.3 s after the release %.3f m/s\n",
              GetParam().preset, static_cast<unsigned long long>(GetParam().seed),
              run.events.c_str(), run.deepest_link_in_object_m * 1e3,
              run.deepest_link_in_object_at_s, run.deepest_link_in_static_m * 1e3,
              fastest_free_settling_mps);

  ASSERT_GE(run.grasp_s, 0.0) << "the closing fist never grasped the bar";
  EXPECT_LE(run.grasp_s, 0.30) << run.events;
  ASSERT_GE(run.release_s, 0.0) << "never let go";
  EXPECT_GE(run.release_s, 0.70) << run.events;
  EXPECT_LE(run.release_s, 1.00) << run.events;
  EXPECT_EQ(run.release_reason, physics::GraspReason::kHandOpened)
      << physics::grasp_reason_name(run.release_reason);
  EXPECT_LE(run.deepest_link_in_object_m, 1e-3) << "at " << run.deepest_link_in_object_at_s << " s";
  EXPECT_LE(run.deepest_link_in_static_m, 1e-3);
  EXPECT_LE(fastest_free_settling_mps, 0.5);
}

INSTANTIATE_TEST_SUITE_P(Presets, RealLeapDegraded, ::testing::ValuesIn(cases()), case_name);

}  // namespace
}  // namespace vcockpit
