// Grasp events in words: the exact strings the world wrote before events became data (the
// offline events.jsonl and the grasp_event topic's reason depend on them).

#include "physics_node/io/grasp_event_text.hpp"

#include <gtest/gtest.h>

#include <string>

namespace vcockpit::physics_io {
namespace {

physics::GraspEvent event(bool grasp, physics::GraspReason reason) {
  physics::GraspEvent e;
  e.grasp = grasp;
  e.reason = reason;
  e.contacts = 3;
  e.thumb_touching = true;
  e.min_thumb_angle_deg = 152.6;
  e.residual_force_N = 2.366657;
  e.residual_torque_Nm = 0.096307;
  return e;
}

TEST(GraspEventText, GraspNamesTheLinksThumbAngleAndResiduals) {
  EXPECT_EQ(grasp_event_text(event(true, physics::GraspReason::kStableGrasp)),
            "stable grasp: 3 links, thumb opposed at 153 deg, |F| 2.37 N, |M| 0.096 N m");
}

TEST(GraspEventText, ReleaseNamesItsReasonAndTheFiguresBehindIt) {
  physics::GraspEvent e = event(false, physics::GraspReason::kTooFewContacts);
  e.contacts = 0;
  e.thumb_touching = false;
  e.min_thumb_angle_deg = 180.0;
  e.residual_force_N = 1.962;
  e.residual_torque_Nm = 0.0;
  EXPECT_EQ(grasp_event_text(e),
            "too few contacts: 0 links, thumb off, min thumb angle 180 deg, "
            "|F| 1.96 N, |M| 0.000 N m");
  EXPECT_EQ(grasp_event_text(event(false, physics::GraspReason::kForceResidual)),
            "force residual too large: 3 links, thumb touching, min thumb angle 153 deg, "
            "|F| 2.37 N, |M| 0.096 N m");
}

TEST(GraspEventText, AHoldLostForOppositionNamesTheBestOpposition) {
  physics::GraspEvent e = event(false, physics::GraspReason::kFingersNotOpposed);
  e.best_opposition_deg = 93.4;
  EXPECT_EQ(grasp_event_text(e),
            "fingers not opposed to the thumb: 3 links, thumb touching, best opposition 93 deg, "
            "|F| 2.37 N, |M| 0.096 N m");
}

TEST(GraspEventText, LostGloveIsJustThat) {
  EXPECT_EQ(grasp_event_text(event(false, physics::GraspReason::kGloveLost)), "glove lost");
}

TEST(GraspEventText, NeverLongerThanTheTopicsReason) {
  physics::GraspEvent e = event(false, physics::GraspReason::kFingersNotOpposed);
  e.residual_force_N = 1e300;
  EXPECT_LE(grasp_event_text(e).size(), 127u);
}

}  // namespace
}  // namespace vcockpit::physics_io
