// control_frames.csv (systems/control_frames_file.cpp): any bytes are either frames whose
// positions are their controls' and whose times go up, or a ControlFramesError.

#include <cmath>

#include "common/atomic_file.hpp"
#include "fuzz/fuzz_support.hpp"
#include "systems/control_frames_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  const fuzz::MemFile file(fuzz::as_text(data, size));
  try {
    const systems::ControlFrames frames = systems::read_control_frames(file.path());
    int64_t last = -1;
    for (const systems::ControlFrame& f : frames.frames) {
      fuzz::require(f.time_ns > last, "frame times do not go up");
      last = f.time_ns;
      fuzz::require(f.position.size() == frames.controls.size(), "a frame of another size");
      for (std::size_t c = 0; c < f.position.size(); ++c) {
        fuzz::require(f.position[c] >= 0 &&
                          static_cast<std::size_t>(f.position[c]) < frames.controls[c].positions.size(),
                      "a position out of range");
        fuzz::require(std::isfinite(f.q[c]), "a coordinate not finite");
      }
    }
  } catch (const systems::ControlFramesError&) {
  } catch (const FileError&) {
  }
  return 0;
}
