// The rig file (launcher/rig_config.hpp): a node's restart_args are added only when it is started
// again, and a restart_args on a node that is never restarted is refused where it is written;
// {scene} is the rig file's scene.

#include "launcher/rig_config.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/yaml_config.hpp"

namespace vcockpit::rig {
namespace {

std::string write_rig(const std::string& name, const std::string& text) {
  const std::string dir = ::testing::TempDir() + "rig_config_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/qos.xml") << "<profiles/>\n";  // what the rig file points to must exist
  std::ofstream(dir + "/right.csv") << "\n";
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(RigConfig, RestartArgsAreAddedOnlyToARestartsCommand) {
  const std::string path = write_rig("restart.yaml",
                                     "domain: 9\nqos: qos.xml\nlog: right.csv\nnodes:\n"
                                     "  - name: physics_node\n"
                                     "    command: [physics_node, --checkpoint, '{out}/p.ckpt']\n"
                                     "    restart_delay_s: 0.2\n"
                                     "    restart_args: [--resume]\n");
  const RigConfig rig = load_rig_config(path);
  ASSERT_EQ(rig.nodes.size(), 1u);
  const std::vector<std::string> first = expand_command(rig.nodes[0], rig, "/out");
  const std::vector<std::string> again = expand_command(rig.nodes[0], rig, "/out", true);
  EXPECT_EQ(first, (std::vector<std::string>{"physics_node", "--checkpoint", "/out/p.ckpt"}));
  EXPECT_EQ(again, (std::vector<std::string>{"physics_node", "--checkpoint", "/out/p.ckpt",
                                             "--resume"}));
}

// {scene}: the rig file's scene (relative to it), cockpit.yaml beside it by default.
TEST(RigConfig, TheSceneIsTheRigFilesOrCockpitYamlBesideIt) {
  const auto expanded = [](const std::string& name, const std::string& scene_line) {
    const RigConfig rig = load_rig_config(write_rig(
        name, "domain: 9\nqos: qos.xml\n" + scene_line + "log: right.csv\nnodes:\n"
                  "  - name: physics_node\n    command: [physics_node, --scene, '{scene}']\n"));
    return expand_command(rig.nodes[0], rig, "/out").back();
  };
  const std::string dir = ::testing::TempDir() + "rig_config_test";
  EXPECT_EQ(expanded("default_scene.yaml", ""), dir + "/cockpit.yaml");
  EXPECT_EQ(expanded("own_scene.yaml", "scene: models/mine.yaml\n"), dir + "/models/mine.yaml");
}

TEST(RigConfig, RestartArgsOnANodeNeverRestartedAreRefusedWithTheirLine) {
  const std::string path = write_rig("no_restart.yaml",
                                     "domain: 9\nqos: qos.xml\nlog: right.csv\nnodes:\n"
                                     "  - name: physics_node\n"
                                     "    command: [physics_node]\n"
                                     "    restart_args: [--resume]\n");
  try {
    load_rig_config(path);
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path + ":7"), std::string::npos) << what;
    EXPECT_NE(what.find("never restarted"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace vcockpit::rig
