// The grasp matrix: every loose object of the default cockpit, picked up and set down elsewhere by
// its gesture (config/gestures/<object>_pick_place.yaml), by hands of three sizes, from glove input
// degraded the ways real devices degrade it (glove_driver/degrade). Each cell is its own test and
// checks, over the whole run (grasp_scenario.hpp):
//   1. the object is grasped and released (at least one GRASP and one RELEASE, the last event a
//      RELEASE), and nothing else is;
//   2. it was carried: while held it rose at least 5 cm above where it lay;
//   3. it ends within 3 cm of where the gesture sets it down;
//   4. it never moves faster than 0.5 m/s before the grasp (the closing fingers do not knock it);
//   5. no link of the drawn hand is ever more than 1 mm inside a static object (computed here with
//      FCL, independently of the physics' own hand-static contacts).
//
// The matrix: every object x size with the clean gesture and the presets `typical` and `harsh`;
// every object with the 50th-percentile hand under each single degradation (degradations()).
// Cells that fail today are listed in known_failing() with the reason, and skipped; set
// VCOCKPIT_GRASP_MATRIX_ALL=1 to run them too. A cell that starts to pass should leave the list.
//
// Also: the recorded logs in config/glove_logs/ are exactly what their scripts produce.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "hand/glove_log.hpp"
#include "hand/config/hand_yaml.hpp"
#include "physics_node/config/scene_config.hpp"
#include "tests/scenario/grasp_matrix/grasp_cells.hpp"
#include "tests/scenario/grasp_matrix/grasp_scenario.hpp"

namespace vcockpit::test {
namespace {

std::string source_dir() { return std::getenv("VCOCKPIT_SOURCE_DIR"); }

// ---- the cells that fail today, and why ----------------------------------------------------
// Measured (seed 7) with the proxy hand advancing evenly over each step's substeps, the
// interpolating replay, a 1 s glove timeout, the implicit gyroscopic term, rolling resistance,
// the closed shell, exact capsule contacts (segment_contact.hpp), the held object kept by an
// opposed pinch (exit_min_contacts) and let go when the glove opens (release_opening_deg),
// fingers that catch up with the glove at bounded speed and slide along panels, links that stand
// off what they let go until the glove is out of it, palm opposition, a held grip balanced
// between the thumb's side and the fingers', and a carried object whose hand closes its lag at
// the pushing speed, a set-down object leaving with the hand's mean velocity over 0.1 s, and the
// samples clamped to the hand's range as the offline runner does: every cell passes, and no
// cell sinks a link into a panel. On other noise (VCOCKPIT_GRASP_MATRIX_SEED 1-5) a few harsh
// cells of the flashlight and the checklist still fail (the calibration error of `harsh` and
// `overrange` on top of 30 Hz and a grip in 0.25 s); build/tests/grasp_cell_trace SOURCE_DIR CELL
// prints a cell's story. A cell that fails at the default seed goes in known_failing() with
// the checks that fail and the figures measured.
const std::map<std::string, std::string>& known_failing() {
  static const std::map<std::string, std::string> kCells = {};
  return kCells;
}

}  // namespace

// Printed by gtest for a failing cell.
void PrintTo(const Cell& cell, std::ostream* os) { *os << cell.name(); }

namespace {

class GraspMatrix : public ::testing::TestWithParam<Cell> {};

TEST_P(GraspMatrix, GraspedCarriedPlacedWithoutKnockingOrSinkingIntoThePanels) {
  const Cell& cell = GetParam();
  const char* all = std::getenv("VCOCKPIT_GRASP_MATRIX_ALL");
  const auto failing = known_failing().find(cell.name());
  if (failing != known_failing().end() && !(all && std::string(all) == "1")) {
    GTEST_SKIP() << "known to fail today: " << failing->second;
  }
  const ScenarioResult r =
      run_grasp_scenario(source_dir(), grasp_case(cell.object), hand_sizes().at(cell.size),
                         degradation_spec(cell.degradation));
  // one line per cell, for the table of results
  std::printf("CELL %s grasps %d releases %d other %d lift %.3f m | err %.4f m | v_before %.3f m/s "
              "| static %.4f m (link %d, object %d, %.2f s)\n",
              cell.name().c_str(), r.grasps, r.releases, r.other_events, r.max_lift_held_m,
              r.place_error_m, r.max_speed_before_grasp_mps, r.deepest_static.depth_m,
              r.deepest_static.link, r.deepest_static.object,
              static_cast<double>(r.deepest_static_ns) * 1e-9);
  EXPECT_GE(r.grasps, 1) << r.events;
  EXPECT_GE(r.releases, 1) << r.events;
  EXPECT_GT(r.first_release_ns, r.first_grasp_ns) << r.events;
  EXPECT_EQ(r.grasps, r.releases) << "the object must end released\n" << r.events;
  EXPECT_EQ(r.other_events, 0) << r.events;
  EXPECT_GE(r.max_lift_held_m, 0.05) << "carried, not left where it lay";
  EXPECT_LE(r.place_error_m, 0.03) << "ends at " << r.final_p_G.transpose();
  EXPECT_LE(r.max_speed_before_grasp_mps, 0.5) << "knocked while the fingers closed";
  EXPECT_LE(r.deepest_static.depth_m, 1e-3)
      << "link " << r.deepest_static.link << " inside object " << r.deepest_static.object
      << " at " << static_cast<double>(r.deepest_static_ns) * 1e-9 << " s";
}

std::vector<Cell> cells_that_are(bool variant) {
  std::vector<Cell> out;
  for (const Cell& c : grasp_cells())
    if (c.variant() == variant) out.push_back(c);
  return out;
}
std::string cell_name(const ::testing::TestParamInfo<Cell>& info) { return info.param.name(); }

INSTANTIATE_TEST_SUITE_P(Cells, GraspMatrix, ::testing::ValuesIn(cells_that_are(false)), cell_name);
INSTANTIATE_TEST_SUITE_P(VariantCells, GraspMatrix, ::testing::ValuesIn(cells_that_are(true)),
                         cell_name);

// The clearance check measures what it claims: a flat hand whose lowest point is 2 mm into the
// console's top reads 2 mm, in the console, by that link; 1 cm above it reads nothing.
TEST(GraspMatrixClearance, MeasuresHowDeepTheHandIsInAStaticObject) {
  physics::Scene scene = load_scene(source_dir() + "/config/cockpit.yaml");
  const hand::HandModel hand = scene.hands[0];
  HandStaticClearance clearance(scene, hand);
  hand::HandLinkPoses poses;
  hand::forward_kinematics(hand, hand::JointAngles{}, poses);
  // the lowest point of the flat, level hand in H, and its link
  double lowest_H = hand.X_HP.translation().z() - 0.5 * hand.palm_size_m.z();
  int lowest_link = static_cast<int>(hand::Link::kPalm);
  for (int l = 1; l < hand::kLinkCount; ++l) {
    const double z = capsule_lowest_z(hand, l, poses.X_HL[l]);
    if (z < lowest_H) {
      lowest_H = z;
      lowest_link = l;
    }
  }
  for (double gap_m : {-0.002, 0.01}) {
    Eigen::Isometry3d X_GH = Eigen::Isometry3d::Identity();
    X_GH.translation() = Eigen::Vector3d(0.30, -0.45, 0.70 + gap_m - lowest_H);
    std::array<Eigen::Isometry3d, hand::kLinkCount> X_GL;
    for (int l = 0; l < hand::kLinkCount; ++l) X_GL[l] = X_GH * poses.X_HL[l];
    const Penetration p = clearance.deepest(X_GL);
    if (gap_m < 0) {
      EXPECT_NEAR(p.depth_m, 0.002, 1e-4);
      EXPECT_EQ(p.link, lowest_link);
      EXPECT_EQ(p.object, scene.find_object("centre_console"));
    } else {
      EXPECT_EQ(p.depth_m, 0.0);
    }
  }
}

// Every cell in the list is a cell of the matrix (a renamed cell must not hide a failure).
TEST(GraspMatrixList, KnownFailingCellsExist) {
  std::map<std::string, int> names;
  for (const Cell& c : grasp_cells()) names[c.name()] = 1;
  for (const auto& [name, why] : known_failing()) {
    EXPECT_TRUE(names.count(name)) << name << " is not a cell of the matrix";
    EXPECT_FALSE(why.empty()) << name;
  }
}

// The bundled recordings are what their scripts publish: a script edited without re-recording
// its log (glove_driver --record, docs/glove_input.md "Glove logs") fails here.
TEST(GraspMatrixLogs, RecordedLogsMatchTheirScripts) {
  const hand::HandModel hand = load_hand_model(source_dir() + "/config/hand.yaml");
  for (const auto& o : grasp_objects()) {
    const std::string stem = o.script.substr(0, o.script.size() - 5);
    const auto log =
        hand::read_glove_log(source_dir() + "/config/glove_logs/" + stem + ".csv", hand);
    const auto expected = script_samples(source_dir() + "/config/gestures/" + o.script, hand);
    ASSERT_EQ(log.samples.size(), expected.size()) << stem;
    EXPECT_EQ(log.counts.clamped, 0u) << stem;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      const auto& a = log.samples[i];
      const auto& b = expected[i];
      ASSERT_EQ(a.t_ns, b.t_ns) << stem << " row " << i;
      ASSERT_LT((a.p_MT_m - b.p_MT_m).norm(), 1e-12) << stem << " row " << i;
      ASSERT_LT(a.q_MT.angularDistance(b.q_MT), 1e-9) << stem << " row " << i;
      for (int j = 0; j < hand::kJointCount; ++j) {
        ASSERT_NEAR(a.joints_rad[j], b.joints_rad[j], 1e-12) << stem << " row " << i;
      }
    }
  }
}

}  // namespace
}  // namespace vcockpit::test
