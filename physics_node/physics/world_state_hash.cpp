#include "physics_node/physics/world_state_hash.hpp"

#include <bit>
#include <type_traits>

#include "physics_node/physics/world_state_fields.hpp"

namespace vcockpit::physics {
namespace {

class Fnv1a64 {
 public:
  uint64_t value() const { return h_; }

  // the visitor of visit_world_state (world_state_fields.hpp): every number as 8 bytes
  template <class T>
  void num(const T& x) {
    if constexpr (std::is_floating_point_v<T>) {
      u64(std::bit_cast<uint64_t>(static_cast<double>(x)));
    } else if constexpr (std::is_same_v<T, bool>) {
      u64(x ? 1u : 0u);
    } else if constexpr (std::is_signed_v<T>) {
      u64(static_cast<uint64_t>(static_cast<int64_t>(x)));
    } else {
      u64(static_cast<uint64_t>(x));
    }
  }
  template <class Vec>
  void count(const Vec& v) { u64(v.size()); }
  template <class Vec>
  void var_count(const Vec& v) { u64(v.size()); }
  void fixed(std::size_t n) { u64(n); }

 private:
  void u64(uint64_t v) {
    for (int byte = 0; byte < 8; ++byte) {
      h_ ^= (v >> (8 * byte)) & 0xffu;
      h_ *= kPrime;
    }
  }

  static constexpr uint64_t kOffset = 14695981039346656037ull;
  static constexpr uint64_t kPrime = 1099511628211ull;
  uint64_t h_ = kOffset;
};

}  // namespace

uint64_t hash_world_state(const WorldState& s) {
  Fnv1a64 h;
  visit_world_state(h, s);
  return h.value();
}

}  // namespace vcockpit::physics
