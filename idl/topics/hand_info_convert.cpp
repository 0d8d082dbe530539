#include "idl/topics/hand_info_convert.hpp"

#include <cmath>

#include "idl/topics/pose_convert.hpp"

namespace vcockpit {

cockpit::HandInfo to_hand_info(const hand::HandModel& model, uint32_t hand_id) {
  cockpit::HandInfo out;
  out.hand_id(hand_id);
  out.left(model.left);
  for (int l = 0; l < hand::kLinkCount; ++l) {
    out.capsules()[l].radius_m(model.capsules[l].radius_m);
    out.capsules()[l].length_m(model.capsules[l].length_m);
  }
  out.X_HP(to_idl(model.X_HP));
  out.palm_size_m(to_idl(model.palm_size_m));
  return out;
}

hand::HandModel from_hand_info(const cockpit::HandInfo& info) {
  hand::HandModel out;
  out.left = info.left();
  for (int l = 0; l < hand::kLinkCount; ++l) {
    out.capsules[l].radius_m = info.capsules()[l].radius_m();
    out.capsules[l].length_m = info.capsules()[l].length_m();
  }
  out.X_HP = to_eigen(info.X_HP());
  out.palm_size_m = to_eigen(info.palm_size_m());
  return out;
}

bool hand_info_sizes_valid(const cockpit::HandInfo& info) {
  for (const cockpit::CapsuleSize& c : info.capsules()) {
    if (!std::isfinite(c.radius_m()) || !std::isfinite(c.length_m())) return false;
    if (c.radius_m() < 0.0 || c.length_m() < 0.0) return false;
  }
  const cockpit::Vec3& s = info.palm_size_m();
  for (double v : {s.x(), s.y(), s.z()}) {
    if (!std::isfinite(v) || !(v > 0.0)) return false;
  }
  const cockpit::Pose& X = info.X_HP();
  const cockpit::Quat& q = X.orientation();
  for (double v : {X.position_m().x(), X.position_m().y(), X.position_m().z(), q.w(), q.x(), q.y(),
                   q.z()}) {
    if (!std::isfinite(v)) return false;
  }
  return q.w() * q.w() + q.x() * q.x() + q.y() * q.y() + q.z() * q.z() > 0.0;
}

}  // namespace vcockpit
