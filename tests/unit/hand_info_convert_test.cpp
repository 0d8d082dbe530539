// hand::HandModel <-> cockpit::HandInfo (idl/topics/hand_info_convert): the geometry survives the
// trip both ways, in link order, for the shipped right hand and its left mirror image, and the
// type is fixed-size; malformed sizes are caught.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cockpitPubSubTypes.h"
#include "hand/config/hand_yaml.hpp"
#include "idl/topics/hand_info_convert.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit {
namespace {

using hand::HandModel;
using hand::Link;

const HandModel& shipped_hand() {
  static const HandModel model = load_hand_model(test::source_dir() + "/config/hand.yaml");
  return model;
}

void expect_same_geometry(const HandModel& a, const HandModel& b) {
  EXPECT_EQ(a.left, b.left);
  for (int l = 0; l < hand::kLinkCount; ++l) {
    EXPECT_EQ(a.capsules[l].radius_m, b.capsules[l].radius_m) << "link " << l;
    EXPECT_EQ(a.capsules[l].length_m, b.capsules[l].length_m) << "link " << l;
  }
  EXPECT_EQ(a.palm_size_m, b.palm_size_m);
  // the palm pose travels as position + quaternion: exact position, rotation to rounding
  EXPECT_EQ(a.X_HP.translation(), b.X_HP.translation());
  EXPECT_TRUE(a.X_HP.linear().isApprox(b.X_HP.linear(), 1e-14))
      << a.X_HP.linear() << "\n" << b.X_HP.linear();
}

TEST(HandInfoConvert, TypeIsFixedSizeAndKeyed) {
  cockpit::HandInfoPubSubType type;
  EXPECT_TRUE(type.is_bounded());
  EXPECT_TRUE(type.m_isGetKeyDefined);
  EXPECT_EQ(cockpit::HandInfo().capsules().size(), static_cast<std::size_t>(hand::kLinkCount));
}

TEST(HandInfoConvert, ShippedRightHandRoundTrips) {
  const HandModel& model = shipped_hand();
  ASSERT_FALSE(model.left);
  const cockpit::HandInfo info = to_hand_info(model, 0);
  EXPECT_EQ(info.hand_id(), 0u);
  EXPECT_FALSE(info.left());
  // link order is hand::Link's (= cockpit::LinkIndex)
  EXPECT_EQ(info.capsules()[cockpit::INDEX_MIDDLE].radius_m(),
            model.capsules[static_cast<int>(Link::kIndexMiddle)].radius_m);
  EXPECT_EQ(info.capsules()[cockpit::LITTLE_DISTAL].length_m(),
            model.capsules[static_cast<int>(Link::kLittleDistal)].length_m);
  EXPECT_GT(info.capsules()[cockpit::THUMB_PROXIMAL].radius_m(), 0.0);
  EXPECT_EQ(info.palm_size_m().x(), model.palm_size_m.x());
  EXPECT_TRUE(hand_info_sizes_valid(info));

  const HandModel back = from_hand_info(info);
  expect_same_geometry(model, back);
  EXPECT_TRUE(back.fingers[0].rows.empty()) << "geometry only: no chains";
}

TEST(HandInfoConvert, LeftHandRoundTrips) {
  const HandModel left = hand::mirrored(shipped_hand());
  ASSERT_TRUE(left.left);
  const cockpit::HandInfo info = to_hand_info(left, 1);
  EXPECT_EQ(info.hand_id(), 1u);
  EXPECT_TRUE(info.left());
  // mirrored in the xz plane: the palm box centre's y changes sign
  EXPECT_DOUBLE_EQ(info.X_HP().position_m().y(), -shipped_hand().X_HP.translation().y());
  expect_same_geometry(left, from_hand_info(info));
}

TEST(HandInfoConvert, InfoToModelToInfoKeepsEveryField) {
  cockpit::HandInfo info;
  info.hand_id(1);
  info.left(true);
  for (int l = 1; l < hand::kLinkCount; ++l) {
    info.capsules()[l].radius_m(0.001 * l);
    info.capsules()[l].length_m(0.002 * l + 1.0 / 3.0);
  }
  info.X_HP().position_m().x(0.05);
  info.X_HP().position_m().y(-0.003);
  info.X_HP().position_m().z(-0.0151);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  info.X_HP().orientation().w(q.w());
  info.X_HP().orientation().x(q.x());
  info.X_HP().orientation().y(q.y());
  info.X_HP().orientation().z(q.z());
  info.palm_size_m().x(0.1);
  info.palm_size_m().y(0.08);
  info.palm_size_m().z(0.03);

  const cockpit::HandInfo back = to_hand_info(from_hand_info(info), 1);
  EXPECT_EQ(back.hand_id(), 1u);
  EXPECT_TRUE(back.left());
  for (int l = 0; l < hand::kLinkCount; ++l) {
    EXPECT_EQ(back.capsules()[l].radius_m(), info.capsules()[l].radius_m()) << l;
    EXPECT_EQ(back.capsules()[l].length_m(), info.capsules()[l].length_m()) << l;
  }
  EXPECT_EQ(back.X_HP().position_m().x(), 0.05);
  EXPECT_EQ(back.X_HP().position_m().y(), -0.003);
  EXPECT_EQ(back.X_HP().position_m().z(), -0.0151);
  EXPECT_NEAR(back.X_HP().orientation().w(), q.w(), 1e-15);
  EXPECT_NEAR(back.X_HP().orientation().x(), q.x(), 1e-15);
  EXPECT_NEAR(back.X_HP().orientation().y(), q.y(), 1e-15);
  EXPECT_NEAR(back.X_HP().orientation().z(), q.z(), 1e-15);
  EXPECT_EQ(back.palm_size_m().x(), 0.1);
  EXPECT_EQ(back.palm_size_m().y(), 0.08);
  EXPECT_EQ(back.palm_size_m().z(), 0.03);
}

TEST(HandInfoConvert, MalformedSizesAreNotValid) {
  const cockpit::HandInfo good = to_hand_info(shipped_hand(), 0);
  ASSERT_TRUE(hand_info_sizes_valid(good));
  cockpit::HandInfo bad = good;
  bad.capsules()[cockpit::INDEX_DISTAL].radius_m(std::numeric_limits<double>::quiet_NaN());
  EXPECT_FALSE(hand_info_sizes_valid(bad));
  bad = good;
  bad.capsules()[cockpit::RING_PROXIMAL].length_m(-0.01);
  EXPECT_FALSE(hand_info_sizes_valid(bad));
  bad = good;
  bad.palm_size_m().y(0.0);
  EXPECT_FALSE(hand_info_sizes_valid(bad));
  bad = good;
  bad.X_HP().orientation().w(0.0);
  bad.X_HP().orientation().x(0.0);
  bad.X_HP().orientation().y(0.0);
  bad.X_HP().orientation().z(0.0);
  EXPECT_FALSE(hand_info_sizes_valid(bad));
  bad = good;
  bad.X_HP().position_m().z(std::numeric_limits<double>::infinity());
  EXPECT_FALSE(hand_info_sizes_valid(bad));
}

}  // namespace
}  // namespace vcockpit
