#include "physics_node/io/grasp_event_text.hpp"

#include <array>
#include <cstdio>

namespace vcockpit::physics_io {

std::string grasp_event_text(const physics::GraspEvent& e) {
  std::array<char, 128> text{};
  if (e.grasp) {
    std::snprintf(text.data(), text.size(),
                  "stable grasp: %d links, %s opposed at %.0f deg, |F| %.2f N, |M| %.3f N m",
                  e.contacts, e.palm_opposes ? "palm" : "thumb", e.min_thumb_angle_deg, e.residual_force_N, e.residual_torque_Nm);
  } else if (e.reason == physics::GraspReason::kGloveLost ||
             e.reason == physics::GraspReason::kReset) {
    std::snprintf(text.data(), text.size(), "%s", physics::grasp_reason_name(e.reason));
  } else if (e.reason == physics::GraspReason::kFingersNotOpposed) {
    std::snprintf(text.data(), text.size(),
                  "%s: %d links, thumb %s, best opposition %.0f deg, |F| %.2f N, |M| %.3f N m",
                  physics::grasp_reason_name(e.reason), e.contacts,
                  e.thumb_touching ? "touching" : "off", e.best_opposition_deg, e.residual_force_N,
                  e.residual_torque_Nm);
  } else {
    std::snprintf(text.data(), text.size(),
                  "%s: %d links, thumb %s, min thumb angle %.0f deg, |F| %.2f N, |M| %.3f N m",
                  physics::grasp_reason_name(e.reason), e.contacts,
                  e.thumb_touching ? "touching" : "off", e.min_thumb_angle_deg, e.residual_force_N,
                  e.residual_torque_Nm);
  }
  return text.data();
}

}  // namespace vcockpit::physics_io
