// Stick anchors of kept pairs: a held object and a hand link left out of a substep's contacts
// keep their friction anchors, so the stick spring on the next substep that sees them pulls from
// where sticking began; pairs not kept start over.
#include <gtest/gtest.h>

#include <vector>

#include "physics_node/physics/contact_forces.hpp"

namespace vcockpit::physics {
namespace {

constexpr double kStiffness_Npm = 2.0e4;  // both bodies: the pair's k = 1e4
constexpr double kDepth_m = 1.0e-3;
constexpr double kSlide_m = 2.0e-4;       // the link moves this far across the contact
constexpr double kDt_s = 1.0e-3;          // the substep

struct Rig {
  Material material{kStiffness_Npm, 0.7, 0.6, 0.4};
  std::vector<ContactBody> bodies = std::vector<ContactBody>(2);  // 0: held object, 1: link
  std::vector<Eigen::Vector3d> F_G = std::vector<Eigen::Vector3d>(2, Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> M_G = std::vector<Eigen::Vector3d>(2, Eigen::Vector3d::Zero());
  std::vector<AppliedContact> applied;
  std::vector<uint8_t> held{1};
  ContactForceModel model{1e-3};

  Rig() {
    for (ContactBody& b : bodies) b.material = &material;  // both immovable: held and hand
  }
  // one substep; returns the friction force on the link (x), 0 without contacts
  double substep(bool with_contact, bool keep) {
    std::vector<ContactPoint> contacts;
    if (with_contact) contacts.push_back({0, 1, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), kDepth_m});
    KeptPairs kept;
    if (keep) kept = {&held, 1};
    model.apply(contacts, bodies, kDt_s, F_G, M_G, applied, kept);
    return applied.empty() ? 0.0 : applied.front().F_on_b_G.x();
  }
};

TEST(ContactForceAnchors, KeptPairCarriesItsAnchorAcrossASubstepWithoutIt) {
  Rig rig;
  EXPECT_DOUBLE_EQ(rig.substep(true, false), 0.0);  // anchored where it touched
  rig.bodies[1].X_GB.translation().x() = kSlide_m;
  EXPECT_DOUBLE_EQ(rig.substep(false, true), 0.0);  // left out, kept
  // the stick spring pulls the link back from where sticking began: -k dx (k = 1e4 N/m, below
  // mu_s N = 0.6 * 10 N, so it sticks)
  EXPECT_NEAR(rig.substep(true, false), -1.0e4 * kSlide_m, 1e-9);
}

TEST(ContactForceAnchors, PairNotKeptStartsOverWithoutAnAnchor) {
  Rig rig;
  rig.substep(true, false);
  rig.bodies[1].X_GB.translation().x() = kSlide_m;
  rig.substep(false, false);                         // left out, not kept: the anchor is gone
  EXPECT_DOUBLE_EQ(rig.substep(true, false), 0.0);   // anchored afresh where it is
}

TEST(ContactForceAnchors, KeptAnchorsStayInPairOrderAmongNewOnes) {
  // object 0 held and kept with link 3, object 1 touching link 3 in every substep, object 2 with
  // link 3 kept too: the carried anchors still match on the substep that sees all three
  Material material{kStiffness_Npm, 0.7, 0.6, 0.4};
  std::vector<ContactBody> bodies(4);
  for (ContactBody& b : bodies) b.material = &material;
  std::vector<Eigen::Vector3d> F(4, Eigen::Vector3d::Zero()), M(4, Eigen::Vector3d::Zero());
  std::vector<AppliedContact> applied;
  const std::vector<uint8_t> held{1, 0, 1};
  ContactForceModel model(1e-3);
  const auto contact = [](int a) {
    return ContactPoint{a, 3, Eigen::Vector3d(0.1 * a, 0, 0), Eigen::Vector3d::UnitZ(), kDepth_m};
  };
  model.apply({contact(0), contact(1), contact(2)}, bodies, kDt_s, F, M, applied);
  bodies[3].X_GB.translation().x() = kSlide_m;
  model.apply({contact(1)}, bodies, kDt_s, F, M, applied, {&held, 3});
  model.apply({contact(0), contact(1), contact(2)}, bodies, kDt_s, F, M, applied);
  ASSERT_EQ(applied.size(), 3u);
  EXPECT_NEAR(applied[0].F_on_b_G.x(), -1.0e4 * kSlide_m, 1e-9);  // carried: pulls back
  EXPECT_NEAR(applied[1].F_on_b_G.x(), -1.0e4 * kSlide_m, 1e-9);  // seen every substep
  EXPECT_NEAR(applied[2].F_on_b_G.x(), -1.0e4 * kSlide_m, 1e-9);  // carried: pulls back
}

}  // namespace
}  // namespace vcockpit::physics
