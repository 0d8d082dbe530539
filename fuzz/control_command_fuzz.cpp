// cockpit/control_command as the physics node receives it: the payload deserialised and handed to
// the world of the bundled cockpit, which refuses a control or position it does not have
// (physics::World::command_control). Any bytes are refused or carried out, never a crash.

#include "fuzz/dds_payload.hpp"
#include "fuzz/fuzz_support.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/physics/world.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  static physics::World world(load_scene(fuzz::config_dir() + "/cockpit.yaml"));
  cockpit::ControlCommand command;
  if (!fuzz::deserialize_payload(data, size, command)) return 0;
  // as the node loop reads it (physics_node/node/node_loop.cpp, take_commands)
  const int control = static_cast<int>(command.control_id());
  const int position = static_cast<int>(command.position());
  if (world.command_control(control, position)) {
    const auto& c = world.scene().controls.at(static_cast<std::size_t>(control));
    (void)c.positions.at(static_cast<std::size_t>(position)).name;
  }
  return 0;
}
