// Every YAML error names the file, the line and the key.

#include <gtest/gtest.h>

#include <fstream>
#include <functional>

#include "common/yaml_config.hpp"
#include "tests/support/process.hpp"

namespace vcockpit {
namespace {

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = test::make_temp_dir("yaml_config_test") + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(YamlConfig, MalformedFileNamesFileLineAndColumn) {
  const auto path = write_file("malformed.yaml", "gravity: [0, 0, -9.81]\nobjects:\n  - name: [a\n");
  const std::string msg = error_of([&] { ConfigNode::load_file(path); });
  EXPECT_NE(msg.find(path + ":"), std::string::npos) << msg;
  EXPECT_NE(msg.find("syntax"), std::string::npos) << msg;
  // the parser stops at line 4 (end of input inside the flow list)
  EXPECT_TRUE(msg.find(path + ":3:") != std::string::npos ||
              msg.find(path + ":4:") != std::string::npos)
      << msg;
}

TEST(YamlConfig, UnknownKeyNamesFileLineAndKey) {
  const auto path = write_file("unknown.yaml", "step_s: 0.001\ngravty: [0, 0, -9.81]\n");
  const auto root = ConfigNode::load_file(path);
  const std::string msg = error_of([&] { root.expect_keys({"step_s", "gravity"}); });
  EXPECT_NE(msg.find(path + ":2:1: gravty: unknown key 'gravty'"), std::string::npos) << msg;
}

TEST(YamlConfig, NestedUnknownKeyHasFullKeyPath) {
  const auto path =
      write_file("nested.yaml", "objects:\n  - name: cup\n    shape: {cylindr: [0.04, 0.1]}\n");
  const auto root = ConfigNode::load_file(path);
  const auto shape = root["objects"].at(0)["shape"];
  const std::string msg = error_of([&] { shape.expect_keys({"box", "cylinder"}); });
  EXPECT_NE(msg.find(path + ":3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("objects[0].shape.cylindr"), std::string::npos) << msg;
}

TEST(YamlConfig, MissingKeyNamesTheMapAndTheKey) {
  const auto root = ConfigNode::load_string("hand:\n  side: right\n", "mem.yaml");
  const std::string msg = error_of([&] { root["hand"]["scale"]; });
  EXPECT_NE(msg.find("mem.yaml:2:3: hand: missing required key 'scale'"), std::string::npos) << msg;
}

TEST(YamlConfig, DuplicateKeyIsAnError) {
  const auto root = ConfigNode::load_string("a: 1\nb: 2\na: 3\n", "dup.yaml");
  const std::string msg = error_of([&] { root.expect_keys({"a", "b"}); });
  EXPECT_NE(msg.find("dup.yaml:3:1: a: duplicate key 'a'"), std::string::npos) << msg;
}

TEST(YamlConfig, BadNumbersAreErrorsWithTheirKey) {
  const auto root = ConfigNode::load_string("mass: heavy\nk: nan\nv: [1, 2]\n", "n.yaml");
  EXPECT_NE(error_of([&] { root.get_double("mass"); }).find("n.yaml:1:7: mass: expected a number, found 'heavy'"),
            std::string::npos);
  EXPECT_NE(error_of([&] { root.get_double("k"); }).find("k: expected a finite number"),
            std::string::npos);
  EXPECT_NE(error_of([&] { root["v"].as_doubles<3>(); }).find("v: expected a list of 3 numbers"),
            std::string::npos);
  EXPECT_EQ((root["v"].as_doubles<2>()), (std::array<double, 2>{1.0, 2.0}));
}

TEST(YamlConfig, EmptyAndUnreadableFilesAreErrors) {
  EXPECT_NE(error_of([] { ConfigNode::load_string("", "empty.yaml"); }).find("empty.yaml:1:1"),
            std::string::npos);
  EXPECT_NE(error_of([] { ConfigNode::load_file("/nonexistent/x.yaml"); })
                .find("/nonexistent/x.yaml: cannot open file"),
            std::string::npos);
}

TEST(YamlConfig, ReadsValuesAndFallbacks) {
  const auto root = ConfigNode::load_string("a: 2.5\nb: 7\nc: true\nd: text\n", "ok.yaml");
  EXPECT_DOUBLE_EQ(root.get_double("a"), 2.5);
  EXPECT_EQ(root.get_int("b", 0), 7);
  EXPECT_TRUE(root.get_bool("c", false));
  EXPECT_EQ(root.get_string("d"), "text");
  EXPECT_DOUBLE_EQ(root.get_double("missing", 1.5), 1.5);
  EXPECT_EQ(root.keys(), (std::vector<std::string>{"a", "b", "c", "d"}));
}

}  // namespace
}  // namespace vcockpit
