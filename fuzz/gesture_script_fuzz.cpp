// Gesture scripts (glove_driver/glove/gesture_script.cpp): any text is either a script or a
// ConfigError; a script gives a finite-time sample anywhere in its span.

#include "fuzz/fuzz_support.hpp"
#include "glove_driver/glove/gesture_script.hpp"
#include "common/yaml_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  const hand::HandModel& hand = fuzz::default_hand();
  try {
    const auto root = ConfigNode::load_string(std::string(fuzz::as_text(data, size)), "script.yaml");
    const auto script = glove::GestureScript::parse(root, hand);
    // keyframe times start at 0 or later and increase (gesture_script.hpp)
    const auto& frames = script.keyframes();
    fuzz::require(!frames.empty() && frames.front().t_ns >= 0, "the script starts at 0 or later");
    for (std::size_t i = 1; i < frames.size(); ++i)
      fuzz::require(frames[i].t_ns > frames[i - 1].t_ns, "keyframe times increase");
    // a few points of the span, not every sample (a long script at a high rate has millions)
    const int64_t end_ns = script.duration_ns();
    for (int64_t t_ns : {int64_t{0}, end_ns / 3, end_ns / 2, end_ns - 1, end_ns})
      script.sample_at(t_ns);
    for (const auto& k : script.keyframes()) script.sample_at(k.t_ns);
  } catch (const ConfigError&) {
  }
  return 0;
}
