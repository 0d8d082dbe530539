// hand.yaml (hand/hand_yaml.cpp): any text is either a hand model or a ConfigError.

#include "common/yaml_config.hpp"
#include "fuzz/fuzz_support.hpp"
#include "hand/config/hand_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  try {
    const auto root = ConfigNode::load_string(std::string(fuzz::as_text(data, size)), "hand.yaml");
    const hand::HandModel model = parse_hand_model(root);
    // the model must be usable: the rest pose through the kinematics
    hand::HandLinkPoses poses;
    hand::forward_kinematics(model, model.rest_pose(), poses);
  } catch (const ConfigError&) {
  }
  return 0;
}
