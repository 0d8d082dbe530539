#include "image_generator/render/hmd_config.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

namespace vcockpit::render {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kMaxAngleRad = 85.0 * kDegToRad;
constexpr double kMaxIpdM = 0.1;
constexpr int kMaxSizePx = 8192;

[[noreturn]] void fail(const std::string& field, const std::string& rule, double value) {
  std::ostringstream message;
  message << "HmdConfig: " << field << " " << rule << ", got " << value;
  throw std::invalid_argument(message.str());
}

// negated comparisons so that NaN fails every check
void check_angle(const std::string& field, double angle_rad, bool positive) {
  const bool sign_ok = positive ? angle_rad > 0.0 : angle_rad < 0.0;
  if (!sign_ok) fail(field, positive ? "must be > 0 rad" : "must be < 0 rad", angle_rad);
  if (!(std::abs(angle_rad) <= kMaxAngleRad)) fail(field, "must be within +-85 deg", angle_rad);
}

void check_fov(const std::string& eye, const EyeFov& fov) {
  check_angle("fov[" + eye + "].left_rad", fov.left_rad, false);
  check_angle("fov[" + eye + "].right_rad", fov.right_rad, true);
  check_angle("fov[" + eye + "].up_rad", fov.up_rad, true);
  check_angle("fov[" + eye + "].down_rad", fov.down_rad, false);
}

void check_size(const std::string& field, int size_px) {
  if (size_px <= 0 || size_px > kMaxSizePx) fail(field, "must be in [1, 8192] px", size_px);
}

}  // namespace

EyeFov default_fov(Eye eye) {
  const double outer_rad = 52.0 * kDegToRad, inner_rad = 45.0 * kDegToRad;
  const double up_rad = 42.0 * kDegToRad, down_rad = -48.0 * kDegToRad;
  if (eye == Eye::kLeft) return {-outer_rad, inner_rad, up_rad, down_rad};
  return {-inner_rad, outer_rad, up_rad, down_rad};
}

void HmdConfig::validate() const {
  if (!(ipd_m > 0.0 && ipd_m <= kMaxIpdM)) fail("ipd_m", "must be in (0, 0.1] m", ipd_m);
  check_fov("left", fov[0]);
  check_fov("right", fov[1]);
  check_size("width_px", width_px);
  check_size("height_px", height_px);
  if (!(near_m > 0.0)) fail("near_m", "must be > 0 m", near_m);
  if (!(far_m > near_m) || !std::isfinite(far_m))
    fail("far_m", "must be finite and > near_m", far_m);
  if (outside && !(outside->ground_depth_m >= 0.1 && outside->ground_depth_m <= 20000.0))
    fail("outside.ground_depth_m", "must be in [0.1, 20000] m", outside->ground_depth_m);
}

}  // namespace vcockpit::render
