// core/statistics.h: medians and spreads of repeated measurements, against values worked out by
// hand.
#include <gtest/gtest.h>

#include "core/statistics.h"

namespace tessera {
namespace {

TEST(Statistics, MedianOfAnOddCountIsTheMiddleValue) {
  EXPECT_EQ(median({5.0}), 5.0);
  EXPECT_EQ(median({9.0, 1.0, 4.0}), 4.0);
  // A slow first frame does not move it.
  EXPECT_EQ(median({2578.0, 80.0, 81.0, 79.0, 82.0}), 81.0);
}

TEST(Statistics, MedianOfAnEvenCountIsTheMeanOfTheMiddleTwo) {
  EXPECT_EQ(median({1.0, 3.0}), 2.0);
  EXPECT_EQ(median({10.0, 1.0, 4.0, 2.0}), 3.0);  // sorted 1 2 4 10: (2 + 4) / 2
  EXPECT_EQ(median({7.0, 7.0, 7.0, 7.0}), 7.0);
}

TEST(Statistics, EmptyIsZero) {
  EXPECT_EQ(median({}), 0.0);
  const Summary s = summarize({});
  EXPECT_EQ(s.count, 0u);
  EXPECT_EQ(s.median, 0.0);
  EXPECT_EQ(s.min, 0.0);
  EXPECT_EQ(s.max, 0.0);
}

TEST(Statistics, SummaryHasMedianMinMaxAndCount) {
  const Summary s = summarize({3.5, -1.0, 8.0, 2.5});
  EXPECT_EQ(s.count, 4u);
  EXPECT_EQ(s.median, 3.0);  // sorted -1 2.5 3.5 8
  EXPECT_EQ(s.min, -1.0);
  EXPECT_EQ(s.max, 8.0);
}

}  // namespace
}  // namespace tessera
