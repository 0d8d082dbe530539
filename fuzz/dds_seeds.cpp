// Writes the seed payloads of the topic fuzz targets, serialised by the topics' own type support:
//   fuzz_dds_seeds fuzz/corpus
// hand_sample/: a right and a left hand's sample and a flagged one; control_command/: a command
// the bundled cockpit carries out and one naming no control.

#include <cstdio>
#include <fstream>
#include <string>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "fuzz/fuzz_support.hpp"
#include "idl/topics/hand_sample_convert.hpp"
#include "idl/topics/topic_traits.hpp"

namespace {

using namespace vcockpit;

template <class T>
void write_seed(const std::string& path, T sample) {
  typename TopicTraits<T>::PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&sample)());
  if (!type.serialize(&sample, &payload)) throw std::runtime_error("cannot serialise " + path);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(payload.data), payload.length);
  std::printf("%s: %u bytes\n", path.c_str(), payload.length);
}

cockpit::ControlCommand command(uint32_t control, uint32_t position) {
  cockpit::ControlCommand c;
  c.seq(1);
  c.control_id(control);
  c.position(position);
  c.source("instructor");
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_dds_seeds CORPUS_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  hand::GloveSample glove;
  glove.t_ns = 1'000'000;
  glove.p_MT_m = {0.10, 0.30, 0.90};
  glove.joints_rad = fuzz::default_hand().rest_pose();
  write_seed(dir + "/hand_sample/right.bin", to_hand_sample(glove, 0, 0, 5'000'000));
  write_seed(dir + "/hand_sample/left.bin", to_hand_sample(glove, 1, 7, 6'000'000));
  cockpit::HandSample flagged = to_hand_sample(glove, 0, 1, 7'000'000);
  flagged.valid(false);
  write_seed(dir + "/hand_sample/flagged.bin", flagged);
  write_seed(dir + "/control_command/first_control.bin", command(0, 1));
  write_seed(dir + "/control_command/no_such_control.bin", command(9999, 0));
  return 0;
}
