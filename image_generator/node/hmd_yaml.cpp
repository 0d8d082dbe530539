#include "image_generator/node/hmd_yaml.hpp"

#include "common/pose.hpp"
#include "common/yaml_config.hpp"

namespace vcockpit {
namespace {

render::EyeFov parse_fov(const ConfigNode& node) {
  node.expect_keys({"left", "right", "up", "down"});
  render::EyeFov fov;
  fov.left_rad = deg_to_rad(node.get_double("left"));
  fov.right_rad = deg_to_rad(node.get_double("right"));
  fov.up_rad = deg_to_rad(node.get_double("up"));
  fov.down_rad = deg_to_rad(node.get_double("down"));
  return fov;
}

}  // namespace

HmdSetup parse_hmd_config(const ConfigNode& root) {
  root.expect_keys(
      {"ipd_m", "width_px", "height_px", "near_m", "far_m", "fov_deg", "head", "refresh_hz", "outside"});
  HmdSetup setup;
  render::HmdConfig& hmd = setup.hmd;
  hmd.ipd_m = root.get_double("ipd_m", hmd.ipd_m);
  hmd.width_px = static_cast<int>(root.get_int("width_px", hmd.width_px));
  hmd.height_px = static_cast<int>(root.get_int("height_px", hmd.height_px));
  hmd.near_m = root.get_double("near_m", hmd.near_m);
  hmd.far_m = root.get_double("far_m", hmd.far_m);
  setup.refresh_hz = root.get_double("refresh_hz", setup.refresh_hz);
  if (!(setup.refresh_hz >= 1.0 && setup.refresh_hz <= 1000.0))
    root["refresh_hz"].fail("must be in 1..1000 (frames a second)");
  if (auto fov = root.find("fov_deg")) {
    fov->expect_keys({"left_eye", "right_eye"});
    hmd.fov[0] = parse_fov((*fov)["left_eye"]);
    hmd.fov[1] = parse_fov((*fov)["right_eye"]);
  }
  if (auto head = root.find("head")) {
    head->expect_keys({"position", "rpy_deg"});
    setup.X_GHead = pose_from_position_rpy_deg(
        (*head)["position"].as_doubles<3>(),
        head->has("rpy_deg") ? (*head)["rpy_deg"].as_doubles<3>() : std::array<double, 3>{0, 0, 0});
  }
  if (auto outside = root.find("outside")) {
    outside->expect_keys({"ground_depth_m"});
    hmd.outside = render::OutsideView{};
    hmd.outside->ground_depth_m = outside->get_double("ground_depth_m", hmd.outside->ground_depth_m);
    if (!(hmd.outside->ground_depth_m >= 0.1 && hmd.outside->ground_depth_m <= 20000.0))
      (*outside)["ground_depth_m"].fail("must be in 0.1..20000 (m below the cockpit's floor)");
  }
  try {
    hmd.validate();
  } catch (const std::invalid_argument& e) {
    root.fail(e.what());
  }
  return setup;
}

HmdSetup load_hmd_config(const std::string& path) {
  return parse_hmd_config(ConfigNode::load_file(path));
}

}  // namespace vcockpit
