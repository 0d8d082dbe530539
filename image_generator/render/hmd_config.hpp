#pragma once
// The head-mounted display: two eyes an IPD apart, each with its own asymmetric field of view
// (OpenXR XrFovf angles), the per-eye image size and the depth range. Constant after start-up.

#include <array>
#include <optional>

namespace vcockpit::render {

enum class Eye { kLeft, kRight };

inline int eye_index(Eye eye) {
  return eye == Eye::kLeft ? 0 : 1;
}

// OpenXR XrFovf convention, radians from the eye's optical axis: left_rad < 0 < right_rad,
// down_rad < 0 < up_rad. Unequal magnitudes make the frustum asymmetric (off-axis).
struct EyeFov {
  double left_rad = 0.0;
  double right_rad = 0.0;
  double up_rad = 0.0;
  double down_rad = 0.0;
};

// A typical headset: each eye sees further outwards (temporal) than inwards (nasal).
EyeFov default_fov(Eye eye);

// What the pilot sees beyond the glazing (outside_view.hpp).
struct OutsideView {
  // The ground's depth below the cockpit frame's z = 0 (its floor): about 1.5 m for an aircraft
  // on its wheels, hundreds of metres in flight. The horizon is level (G is level flight).
  double ground_depth_m = 300.0;
};

struct HmdConfig {
  double ipd_m = 0.063;  // inter-pupillary distance
  std::array<EyeFov, 2> fov{default_fov(Eye::kLeft), default_fov(Eye::kRight)};  // [kLeft, kRight]
  int width_px = 1280;                                                           // per eye
  int height_px = 720;
  double near_m = 0.05;
  double far_m = 20.0;
  // none: the background colour where nothing is drawn (a dark room round the cockpit)
  std::optional<OutsideView> outside;

  const EyeFov& eye_fov(Eye eye) const { return fov[eye_index(eye)]; }

  // Throws std::invalid_argument naming the field and its bad value: ipd outside (0, 0.1] m,
  // angles not left < 0 < right and down < 0 < up or beyond 85 deg, sizes outside [1, 8192] px,
  // near <= 0 or far <= near, an outside view's ground depth not finite or outside
  // [0.1, 20000] m.
  void validate() const;
};

}  // namespace vcockpit::render
