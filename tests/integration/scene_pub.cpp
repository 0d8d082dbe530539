// Test scene publisher: a few coloured boxes on cockpit/object_info + object_state (transient
// local, as the physics node publishes them), the hand's geometry on cockpit/hand_info (state,
// as the physics node publishes it) and a hand_state carrying a known source stamp, repeated at
// 100 Hz until a signal or --duration.
//   --box "r,g,b,x,y,z,size"   (repeatable) a cube of `size` m at (x, y, z) in world
//   --mesh "file,node,scale,r,g,b,x,y,z"   (repeatable) a static model part (MESH), its node's
//                              origin at (x, y, z), the file +y up
//   --hand-stamp NS            source_stamp_ns of the hand_state (its links sit far below the
//   floor)
//   --hand-config FILE         hand.yaml of the hand_info (default: config/hand.yaml)

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <sstream>
#include <thread>

#include "common/clock.hpp"
#include "common/logging.hpp"
#include "common/signals.hpp"
#include "dds/dds_participant.hpp"
#include "hand/config/hand_yaml.hpp"
#include "idl/topics/hand_info_convert.hpp"
#include "idl/topics/pose_convert.hpp"

int main(int argc, char** argv) {
  using namespace vcockpit;
  CLI::App app("scene_pub: publishes a test scene for the image generator");
  DdsFlags dds_flags;
  add_dds_flags(app, dds_flags);
  std::vector<std::string> boxes;
  std::vector<std::string> meshes;
  int64_t hand_stamp_ns = 0;
  double duration_s = 0;
  std::string hand_config = std::string(VCOCKPIT_CONFIG_DIR) + "/hand.yaml";
  app.add_option("--box", boxes, "r,g,b,x,y,z,size");
  app.add_option("--mesh", meshes, "file,node,scale,r,g,b,x,y,z");
  app.add_option("--hand-stamp", hand_stamp_ns);
  app.add_option("--duration", duration_s);
  app.add_option("--hand-config", hand_config)->check(CLI::ExistingFile);
  CLI11_PARSE(app, argc, argv);
  setup_logging("scene_pub");
  install_shutdown_handlers();
  try {
    DdsParticipant participant(resolve_dds_options(dds_flags), "scene_pub");
    auto info_writer = participant.make_writer<cockpit::ObjectInfo>("state");
    auto state_writer = participant.make_writer<cockpit::ObjectState>("state");
    auto hand_writer = participant.make_writer<cockpit::HandState>("stream");
    auto hand_info_writer = participant.make_writer<cockpit::HandInfo>("state");
    hand_info_writer.write(to_hand_info(load_hand_model(hand_config), 0));  // hand_state's hand_id
    std::vector<cockpit::ObjectState> states;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      std::vector<double> v;
      std::stringstream ss(boxes[i]);
      std::string item;
      while (std::getline(ss, item, ','))
        v.push_back(std::stod(item));
      if (v.size() != 7) throw std::invalid_argument("--box needs r,g,b,x,y,z,size: " + boxes[i]);
      cockpit::ObjectInfo info;
      info.object_id(static_cast<uint32_t>(i));
      info.name("box" + std::to_string(i));
      info.kind(cockpit::STATIC_OBJECT);
      info.shape(cockpit::BOX);
      info.dimensions_m({v[6], v[6], v[6]});
      info.color_rgba(
          {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]), 1.0f});
      info_writer.write(info);
      cockpit::ObjectState state;
      state.object_id(static_cast<uint32_t>(i));
      state.X_GO(to_idl(Eigen::Isometry3d(Eigen::Translation3d(v[3], v[4], v[5]))));
      state.held_by_hand_id(cockpit::kNoObject);
      state_writer.write(state);
      states.push_back(state);
    }
    for (std::size_t k = 0; k < meshes.size(); ++k) {
      std::vector<std::string> f;
      std::stringstream ss(meshes[k]);
      std::string item;
      while (std::getline(ss, item, ','))
        f.push_back(item);
      if (f.size() != 9)
        throw std::invalid_argument("--mesh needs file,node,scale,r,g,b,x,y,z: " + meshes[k]);
      const auto id = static_cast<uint32_t>(boxes.size() + k);
      cockpit::ObjectInfo info;
      info.object_id(id);
      info.name("mesh" + std::to_string(k));
      info.kind(cockpit::STATIC_OBJECT);
      info.shape(cockpit::MESH);
      info.dimensions_m({0.1, 0.1, 0.1});
      info.mesh_file(f[0]);
      info.mesh_node(f[1]);
      info.mesh_scale(std::stod(f[2]));
      info.mesh_z_up(false);
      info.mesh_origin_m(to_idl(Eigen::Vector3d::Zero()));
      info.mesh_center_m(to_idl(Eigen::Vector3d::Zero()));
      info.color_rgba({std::stof(f[3]), std::stof(f[4]), std::stof(f[5]), 1.0f});
      info_writer.write(info);
      cockpit::ObjectState state;
      state.object_id(id);
      state.X_GO(to_idl(Eigen::Isometry3d(
          Eigen::Translation3d(std::stod(f[6]), std::stod(f[7]), std::stod(f[8])))));
      state.held_by_hand_id(cockpit::kNoObject);
      state_writer.write(state);
      states.push_back(state);
    }
    cockpit::HandState hand;
    hand.hand_id(0);
    hand.source_stamp_ns(hand_stamp_ns);
    hand.sample_time_ns(hand_stamp_ns);
    hand.tracking(true);
    hand.grasped_object_id(cockpit::kNoObject);
    const auto far_below = to_idl(Eigen::Isometry3d(Eigen::Translation3d(0, 0, -50)));
    hand.X_GH(far_below);
    for (auto& link : hand.X_GL())
      link = far_below;
    const int64_t end_ns =
        duration_s > 0 ? monotonic_now_ns() + seconds_to_ns(duration_s) : INT64_MAX;
    while (!shutdown_requested() && monotonic_now_ns() < end_ns) {
      hand_writer.write(hand);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
