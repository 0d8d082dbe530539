#pragma once
// VCOCKPIT_ASSERT(cond, "message"): an invariant of the code (Box2D's b2Assert), kept on in every
// build, NDEBUG or not: a broken invariant in a RelWithDebInfo run must stop there, with where and
// why, not corrupt the physics silently. For the code's own invariants only (contacts sorted,
// indices in range); bad user input gets an exception with a message, bad run-time samples a
// counter. Header-only, no dependencies but the C library.

#include <cstdio>
#include <cstdlib>

namespace vcockpit::detail {

[[noreturn]] inline void assert_failed(const char* file, int line, const char* condition,
                                       const char* message) {
  std::fprintf(stderr, "%s:%d: assertion failed: %s: %s\n", file, line, condition, message);
  std::fflush(stderr);
  std::abort();
}

}  // namespace vcockpit::detail

#define VCOCKPIT_ASSERT(cond, message)                                         \
  do {                                                                         \
    if (!(cond)) [[unlikely]]                                                  \
      ::vcockpit::detail::assert_failed(__FILE__, __LINE__, #cond, (message)); \
  } while (false)
