// A crashing node says where: the signal and the stack on stderr, and still the signal's death
// (the exit status the rig reports, 128+N).

#include <gtest/gtest.h>

#include <csignal>

#include "common/crash_backtrace.hpp"

namespace vcockpit {
namespace {

TEST(CrashBacktrace, AFatalSignalWritesTheStackAndStillEndsTheProcessBySignal) {
  if (!crash_backtrace_available()) GTEST_SKIP() << "the sanitizers report crashes themselves";
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        install_crash_backtrace();
        std::raise(SIGSEGV);
      },
      ::testing::KilledBySignal(SIGSEGV), "fatal signal 11; the stack:\n(.|\n)*common_test\\(");
  EXPECT_EXIT(
      {
        install_crash_backtrace();
        std::abort();
      },
      ::testing::KilledBySignal(SIGABRT), "fatal signal 6; the stack:");
}

}  // namespace
}  // namespace vcockpit
