// hmd.yaml (image_generator/node/hmd_yaml.cpp): any text is either an HMD or a ConfigError.

#include "common/yaml_config.hpp"
#include "fuzz/fuzz_support.hpp"
#include "image_generator/node/hmd_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  try {
    const auto root = ConfigNode::load_string(std::string(fuzz::as_text(data, size)), "hmd.yaml");
    parse_hmd_config(root);
  } catch (const ConfigError&) {
  }
  return 0;
}
