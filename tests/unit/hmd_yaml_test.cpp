// The HMD file (config/hmd.yaml): the bundled one reads, and a bad outside view is an error
// naming the file, the line and the field.

#include <gtest/gtest.h>

#include <string>

#include "common/config_error.hpp"
#include "common/yaml_config.hpp"
#include "image_generator/node/hmd_yaml.hpp"
#include "tests/support/test_files.hpp"

namespace vcockpit::test {
namespace {

TEST(HmdYaml, TheBundledFileHasAnOutsideView) {
  const HmdSetup setup = load_hmd_config(source_dir() + "/config/hmd.yaml");
  ASSERT_TRUE(setup.hmd.outside.has_value());
  EXPECT_GT(setup.hmd.outside->ground_depth_m, 0.0);
}

TEST(HmdYaml, WithoutOutsideThereIsNone) {
  const HmdSetup setup = parse_hmd_config(ConfigNode::load_string("ipd_m: 0.063\n", "hmd.yaml"));
  EXPECT_FALSE(setup.hmd.outside.has_value());
}

TEST(HmdYaml, ABadOutsideViewNamesTheFileLineAndField) {
  struct Case {
    const char* text;
    const char* expected;  // in the message
  };
  const Case cases[] = {
      {"ipd_m: 0.063\noutside: {ground_depth_m: -3}\n", "hmd.yaml:2"},
      {"ipd_m: 0.063\noutside: {ground_depth_m: 0}\n", "ground_depth_m"},
      {"ipd_m: 0.063\noutside: {ground_depth_m: .nan}\n", "ground_depth_m"},
      {"ipd_m: 0.063\noutside: {ground_depth_m: 30000}\n", "ground_depth_m"},
      {"ipd_m: 0.063\noutside: {ground_depth_m: high}\n", "ground_depth_m"},
      {"ipd_m: 0.063\noutside: {ground: 300}\n", "ground"},
  };
  for (const Case& bad : cases) {
    try {
      parse_hmd_config(ConfigNode::load_string(bad.text, "hmd.yaml"));
      ADD_FAILURE() << "accepted " << bad.text;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(bad.expected), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace vcockpit::test
