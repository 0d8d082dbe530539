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
  EXPECT_EQ(gaps.of(writer(1)).in_gaps, 4u);  // 4, 5, 6 and 9
  EXPECT_EQ(gaps.of(writer(1)).at_start(), 0u);
  EXPECT_EQ(gaps.of(writer(1)).missing(), 4u);
  EXPECT_EQ(gaps.duplicates(), 0u);
}

TEST(SequenceGaps, WhatAWriterSentBeforeTheFirstReceivedSampleIsMissedAtTheStart) {
  SequenceGaps gaps;
  // a first sample numbered 455: 454 were sent before the recorder matched the writer
  EXPECT_TRUE(gaps.add(writer(1), 455));
  EXPECT_TRUE(gaps.add(writer(1), 456));
  EXPECT_TRUE(gaps.add(writer(1), 458));
  const SequenceGaps::Track t = gaps.of(writer(1));
  EXPECT_EQ(t.first, 455u);
  EXPECT_EQ(t.at_start(), 454u);
  EXPECT_EQ(t.in_gaps, 1u);
  EXPECT_EQ(t.missing(), 455u);
  EXPECT_EQ(t.newest, 458u);  // 458 sent: 3 received, 455 missing
}

TEST(SequenceGaps, ASampleSeenTwiceOrOlderIsRefusedAndCounted) {
  SequenceGaps gaps;
  EXPECT_TRUE(gaps.add(writer(1), 1));
  EXPECT_TRUE(gaps.add(writer(1), 2));
  EXPECT_FALSE(gaps.add(writer(1), 2));  // the other reader's copy
  EXPECT_FALSE(gaps.add(writer(1), 1));
  EXPECT_EQ(gaps.duplicates(), 2u);
  EXPECT_EQ(gaps.of(writer(1)).missing(), 0u);
}

TEST(SequenceGaps, WritersAreCountedApart) {
  SequenceGaps gaps;
  // a glove driver restarted after kill -9 is a new writer numbering from 1 again
  for (uint64_t seq : {1, 2, 4}) gaps.add(writer(1), seq);
  for (uint64_t seq : {3, 4, 5}) gaps.add(writer(2), seq);
  EXPECT_EQ(gaps.writers(), 2u);
  EXPECT_EQ(gaps.of(writer(1)).missing(), 1u);
  EXPECT_EQ(gaps.of(writer(2)).missing(), 2u);
  EXPECT_EQ(gaps.of(writer(2)).at_start(), 2u);
  EXPECT_EQ(gaps.of(writer(3)).missing(), 0u) << "a writer never seen sent nothing we know of";
  EXPECT_EQ(gaps.duplicates(), 0u);
}

}  // namespace
}  // namespace vcockpit::glove
