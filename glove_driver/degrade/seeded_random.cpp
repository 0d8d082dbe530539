#include "glove_driver/degrade/seeded_random.hpp"

#include <cmath>

#include "common/assert.hpp"

namespace vcockpit::degrade {
namespace {

// FNV-1a of the stream name, then splitmix64 of seed ^ that: nearby seeds and similar names
// give unrelated engine states.
uint64_t stream_seed(uint64_t seed, std::string_view stream) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : stream) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  uint64_t z = seed ^ h;
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

SeededRandom::SeededRandom(uint64_t seed, std::string_view stream)
    : engine_(stream_seed(seed, stream)) {}

double SeededRandom::uniform() {
  return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

double SeededRandom::uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

double SeededRandom::normal() {
  if (have_spare_) {
    have_spare_ = false;
    return spare_;
  }
  const double u1 = 1.0 - uniform();  // (0, 1]: log is finite
  const double u2 = uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double phi = 2.0 * M_PI * u2;
  spare_ = r * std::sin(phi);
  have_spare_ = true;
  return r * std::cos(phi);
}

uint64_t SeededRandom::below(uint64_t n) {
  VCOCKPIT_ASSERT(n > 0, "below(0)");
  const uint64_t limit = UINT64_MAX - UINT64_MAX % n;  // reject the biased top
  uint64_t x = engine_();
  while (x >= limit) x = engine_();
  return x % n;
}

}  // namespace vcockpit::degrade
