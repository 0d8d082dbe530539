#pragma once
// config/hmd.yaml -> the HMD the image generator renders for, and the design eye point.
// Every bad value is a ConfigError naming file, line and key.

#include <Eigen/Geometry>

#include <string>

#include "common/config_error.hpp"
#include "image_generator/render/hmd_config.hpp"

namespace vcockpit {

struct HmdSetup {
  render::HmdConfig hmd;
  Eigen::Isometry3d X_GHead = Eigen::Isometry3d::Identity();  // design eye point
  double refresh_hz = 90.0;  // the display's: the image generator paces its frames to it
};

HmdSetup load_hmd_config(const std::string& path);
HmdSetup parse_hmd_config(const ConfigNode& root);

}  // namespace vcockpit
