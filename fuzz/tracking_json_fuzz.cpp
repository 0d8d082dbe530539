// Hand trackers' recordings (hand/tracking/leapjs_import.cpp, mediapipe_import.cpp): any bytes
// are either frames or a JointsLogError, never a crash; what is imported is finite and in time.

#include "fuzz/fuzz_support.hpp"
#include "hand/tracking/leapjs_import.hpp"
#include "hand/tracking/mediapipe_import.hpp"

namespace {

void check(const std::vector<vcockpit::hand::tracking::JointsFrame>& frames) {
  using namespace vcockpit;
  fuzz::require(!frames.empty(), "frames with a hand");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    for (const auto& j : frames[i].joints) fuzz::require(!j.valid || j.p_m.allFinite(), "finite joints");
    for (std::size_t k = i; k-- > 0;) {
      if (frames[k].left_hand != frames[i].left_hand) continue;
      fuzz::require(frames[i].t_ns > frames[k].t_ns, "time increases for each hand");
      break;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit::hand::tracking;
  const vcockpit::fuzz::MemFile file(vcockpit::fuzz::as_text(data, size));
  try {
    check(import_leapjs(file.path()).frames);
  } catch (const JointsLogError&) {
  }
  try {
    check(import_mediapipe(file.path()).frames);
  } catch (const JointsLogError&) {
  }
  return 0;
}
