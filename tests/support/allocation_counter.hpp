#pragma once
// Counts heap allocations (operator new) while g_count_allocations is set, so a test can prove a
// hot path allocates nothing. A test binary that includes this must compile
// support/allocation_counter.cpp, which replaces the global operator new/delete.

#include <atomic>

namespace vcockpit::test {

extern std::atomic<bool> g_count_allocations;
extern std::atomic<int> g_allocations;

}  // namespace vcockpit::test
