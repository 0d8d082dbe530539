// Glove logs (hand/glove_log_reader.cpp): any bytes are either a log or a GloveLogError.

#include <cmath>

#include "fuzz/fuzz_support.hpp"
#include "hand/glove_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  const hand::HandModel& hand = fuzz::default_hand();
  const fuzz::MemFile file(fuzz::as_text(data, size));
  try {
    hand::glove_log_left_hand(file.path());
  } catch (const hand::GloveLogError&) {
  }
  try {
    const hand::GloveLog log = hand::read_glove_log(file.path(), hand);
    hand::glove_log_warnings(log);
    // what the format promises (hand/glove_log.hpp)
    fuzz::require(!log.samples.empty(), "a log has samples");
    for (std::size_t i = 0; i < log.samples.size(); ++i) {
      const hand::GloveSample& s = log.samples[i];
      fuzz::require(i == 0 || s.t_ns > log.samples[i - 1].t_ns, "time increases");
      fuzz::require(s.p_MT_m.allFinite() && s.q_MT.coeffs().allFinite(), "finite wrist");
      fuzz::require(std::abs(s.q_MT.norm() - 1.0) <= 1e-3, "unit quaternion");
      for (int j = 0; j < hand::kJointCount; ++j) {
        const double q = s.joints_rad[j];
        fuzz::require(q >= hand.joints[j].min_rad && q <= hand.joints[j].max_rad,
                      "joints within their limits");
      }
    }
  } catch (const hand::GloveLogError&) {
  }
  return 0;
}
