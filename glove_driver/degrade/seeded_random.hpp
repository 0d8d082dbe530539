#pragma once
// The degradations' randomness: seeded only, and the same numbers on every platform. The engine
// is std::mt19937_64, whose output the standard fixes; the distributions are written here
// because the standard library's are implementation-defined (libstdc++ and libc++ differ).
//
// Each degradation draws from its own stream (the seed mixed with the stage's name), so adding
// or removing one degradation leaves the numbers of the others unchanged.

#include <cstdint>
#include <random>
#include <string_view>

namespace vcockpit::degrade {

class SeededRandom {
 public:
  SeededRandom(uint64_t seed, std::string_view stream);

  double uniform();                     // [0, 1)
  double uniform(double lo, double hi);  // [lo, hi)
  double normal();                      // mean 0, standard deviation 1 (Box-Muller)
  uint64_t below(uint64_t n);           // [0, n), n > 0, without modulo bias

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool have_spare_ = false;
};

}  // namespace vcockpit::degrade
