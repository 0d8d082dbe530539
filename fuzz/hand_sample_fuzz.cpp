// cockpit/hand_sample as the physics node receives it: the payload deserialised, converted and
// checked by the sample gate (physics_node/node/sample_gate.cpp), an accepted sample turned into
// the hand's input. Any bytes are rejected or accepted, never a crash.

#include "fuzz/dds_payload.hpp"
#include "fuzz/fuzz_support.hpp"
#include "physics_node/io/hand_input.hpp"
#include "physics_node/node/sample_gate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  const hand::HandModel& hand = fuzz::default_hand();
  cockpit::HandSample sample;
  if (!fuzz::deserialize_payload(data, size, sample)) return 0;
  physics_node::SampleGate gate(hand);
  for (int repeat = 0; repeat < 2; ++repeat) {  // the second time it is stale
    hand::GloveSample glove;
    if (gate.accept(sample, glove)) physics_io::hand_input_from_glove(hand, glove);
  }
  return 0;
}
