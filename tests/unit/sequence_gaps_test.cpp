// SequenceGaps: what a recorder counts as lost from its writers' sequence numbers.

#include "glove_driver/node/sequence_gaps.hpp"

#include <gtest/gtest.h>

namespace vcockpit::glove {
namespace {

WriterId writer(uint8_t n) {
  WriterId id{};
  id[15] = n;
  return id;
}

TEST(SequenceGaps, CountsTheSamplesMissingBetweenTwoReceivedOnes) {
  SequenceGaps gaps;
  for (uint64_t seq : {1, 2, 3, 7, 8, 10}) EXPECT_TRUE(gaps.add(writer(1), seq)) << seq;
  EXPECT_EQ(gaps.missing(), 4u);  // 4, 5, 6 and 9
  EXPECT_EQ(gaps.duplicates(), 0u);
}

TEST(SequenceGaps, WhatAWriterSentBeforeTheFirstReceivedSampleIsNotMissing) {
  SequenceGaps gaps;
  EXPECT_TRUE(gaps.add(writer(1), 5000));  // matched a writer that had been running
  EXPECT_TRUE(gaps.add(writer(1), 5001));
  EXPECT_EQ(gaps.missing(), 0u);
}

TEST(SequenceGaps, ASampleSeenTwiceOrOlderIsRefusedAndCounted) {
  SequenceGaps gaps;
  EXPECT_TRUE(gaps.add(writer(1), 1));
  EXPECT_TRUE(gaps.add(writer(1), 2));
  EXPECT_FALSE(gaps.add(writer(1), 2));  // the other reader's copy
  EXPECT_FALSE(gaps.add(writer(1), 1));
  EXPECT_EQ(gaps.duplicates(), 2u);
  EXPECT_EQ(gaps.missing(), 0u);
}

TEST(SequenceGaps, WritersAreCountedApart) {
  SequenceGaps gaps;
  // a glove driver restarted after kill -9 is a new writer numbering from 1 again
  for (uint64_t seq : {1, 2, 4}) gaps.add(writer(1), seq);
  for (uint64_t seq : {1, 3, 4, 5}) gaps.add(writer(2), seq);
  EXPECT_EQ(gaps.writers(), 2u);
  EXPECT_EQ(gaps.missing_of(writer(1)), 1u);
  EXPECT_EQ(gaps.missing_of(writer(2)), 1u);
  EXPECT_EQ(gaps.missing_of(writer(3)), 0u);
  EXPECT_EQ(gaps.missing(), 2u);
  EXPECT_EQ(gaps.duplicates(), 0u);
}

}  // namespace
}  // namespace vcockpit::glove
