// World checkpoints (physics_node/io/world_checkpoint.cpp): a physics node resumes from a file
// that anything may have damaged. Any bytes are either a CheckpointError or a state a world
// steps from without stopping on an assertion and with finite bodies.
//
// The input patches a valid checkpoint rather than being one: each 12 bytes are a field's
// index (4 bytes) and a value (8) written over that field of a checkpoint of the small scene
// (fuzz/corpus/scene_yaml/small_scene.yaml) after 300 steps, and the checksum is made good
// again, so mutations reach the fields' checks instead of all stopping at the checksum. An
// empty input is the checkpoint as saved. A trailing remainder (under 12 bytes) truncates the
// file by that many 8-byte fields.

#include <algorithm>
#include <cmath>
#include <memory>
#include <cstring>
#include <string>

#include "common/yaml_config.hpp"
#include "fuzz/fuzz_support.hpp"
#include "physics_node/config/scene_config.hpp"
#include "physics_node/io/world_checkpoint.hpp"

namespace {

using namespace vcockpit;

struct Saved {
  std::unique_ptr<physics::World> fresh;  // the scene as it starts
  std::string bytes;
};

const Saved& saved() {
  static const Saved kSaved = [] {
    const auto root = ConfigNode::load_file(fuzz::config_dir() + "/../fuzz/corpus/scene_yaml/small_scene.yaml");
    physics::Scene scene = parse_scene(root, fuzz::config_dir());
    auto fresh = std::make_unique<physics::World>(scene);
    physics::World world(scene);
    for (int i = 0; i < 300; ++i) world.step();
    std::string bytes = physics_io::encode_checkpoint({world.state(), false},
                                                      physics_io::scene_fingerprint(*fresh));
    return Saved{std::move(fresh), std::move(bytes)};
  }();
  return kSaved;
}

uint64_t fnv1a64(const std::string& bytes, std::size_t n) {
  uint64_t h = 14695981039346656037ull;
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(bytes[i]);
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const Saved& s = saved();
  std::string bytes = s.bytes;
  const std::size_t fields = bytes.size() / 8 - 1;  // the checksum is not patched
  std::size_t at = 0;
  for (; at + 12 <= size; at += 12) {
    uint32_t index = 0;
    std::memcpy(&index, data + at, 4);
    std::memcpy(&bytes[(index % fields) * 8], data + at + 4, 8);
  }
  const std::size_t cut = std::min(size - at, fields);
  bytes.resize(bytes.size() - cut * 8);
  if (bytes.size() >= 8) {
    const uint64_t sum = fnv1a64(bytes, bytes.size() - 8);
    for (int b = 0; b < 8; ++b) bytes[bytes.size() - 8 + static_cast<std::size_t>(b)] = static_cast<char>(sum >> (8 * b));
  }
  physics_io::Checkpoint checkpoint;
  try {
    checkpoint = physics_io::decode_checkpoint(bytes, *s.fresh);
  } catch (const physics_io::CheckpointError&) {
    fuzz::require(size != 0, "the checkpoint as saved decodes");
    return 0;
  }
  physics::World world(s.fresh->scene());
  world.restore(checkpoint.world);
  for (int i = 0; i < 20; ++i) world.step();
  for (const physics::BodyState& b : world.bodies())
    fuzz::require(b.X_GO.matrix().allFinite() && b.v_G.allFinite() && b.w_G.allFinite(),
                  "finite bodies after stepping a resumed world");
  return 0;
}
