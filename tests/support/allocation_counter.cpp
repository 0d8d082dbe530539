#include "tests/support/allocation_counter.hpp"

#include <cstdlib>
#include <new>

namespace vcockpit::test {

std::atomic<bool> g_count_allocations{false};
std::atomic<int> g_allocations{0};

}  // namespace vcockpit::test

// noinline: GCC otherwise inlines these into gtest's factories and flags malloc/free as a
// mismatched new/delete pair.
[[gnu::noinline]] void* operator new(std::size_t size) {
  if (vcockpit::test::g_count_allocations.load()) vcockpit::test::g_allocations.fetch_add(1);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void* operator new[](std::size_t size) { return ::operator new(size); }
// the nothrow forms too (std::stable_sort's temporary buffer uses them): every form a plain
// delete may free comes from malloc, so ASan sees no new/free mismatch
[[gnu::noinline]] void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  if (vcockpit::test::g_count_allocations.load()) vcockpit::test::g_allocations.fetch_add(1);
  return std::malloc(size == 0 ? 1 : size);
}
[[gnu::noinline]] void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
  return ::operator new(size, tag);
}
[[gnu::noinline]] void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
