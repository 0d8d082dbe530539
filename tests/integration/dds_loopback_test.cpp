// Two real processes on a test-unique domain over the loopback-only default profile exchange
// 1,000 HandSamples at 1 kHz under the reliable profile: none lost, byte-identical, in order,
// and no /dev/shm file of theirs left behind.

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>

#include "tests/support/hand_sample_pattern.hpp"
#include "tests/support/process.hpp"
#include "tests/support/process_test.hpp"
#include "tests/support/test_env.hpp"

namespace vcockpit::test {
namespace {

TEST(DdsLoopback, ThousandHandSamplesAtOneKilohertzReliableNoneLost) {
  constexpr int kCount = 1000;
  const std::string dir = make_temp_dir("dds_loopback");
  const std::string out = dir + "/received.bin";
  const auto shm_before = list_dds_shm();
  const auto env = dds_test_env();

  ChildProcess sub({bin_dir() + "/test_hand_sample_sub", "--count", std::to_string(kCount),
                    "--out", out, "--timeout-s", "30"},
                   env, dir + "/sub.log");
  ChildProcess pub({bin_dir() + "/test_hand_sample_pub", "--count", std::to_string(kCount),
                    "--rate-hz", "1000"},
                   env, dir + "/pub.log");
  EXPECT_EQ(pub.wait(40'000'000'000), 0) << "publisher failed, see " << dir << "/pub.log";
  EXPECT_EQ(sub.wait(40'000'000'000), 0) << "subscriber failed, see " << dir << "/sub.log";

  const auto records = read_records(out);
  ASSERT_EQ(records.size(), static_cast<std::size_t>(kCount));
  for (int i = 0; i < kCount; ++i) {
    auto expected = hand_sample_pattern(static_cast<uint64_t>(i));
    ASSERT_EQ(records[i], serialize(expected)) << "sample " << i << " differs";
  }

  const auto leftovers = new_entries(shm_before, list_dds_shm());
  remove_dds_shm(leftovers);
  EXPECT_TRUE(leftovers.empty()) << "left in /dev/shm: " << leftovers.size() << " files, first "
                                 << (leftovers.empty() ? "" : leftovers.front());
}

}  // namespace
}  // namespace vcockpit::test
