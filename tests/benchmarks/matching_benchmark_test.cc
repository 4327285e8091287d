// The list parsing of benchmark_matching (matching_benchmark.h): exact values, bad input refused.
#include "benchmarks/matching/matching_benchmark.h"

#include <gtest/gtest.h>

namespace sfm {
namespace {

TEST(MatchingBenchmarkTest, ListsParse) {
  EXPECT_EQ(SplitCommaList("a,,b,"), (std::vector<std::string>{"a", "b"}));
  std::vector<double> values;
  ASSERT_TRUE(ParseNumberList("4,6,10.5", &values));
  EXPECT_EQ(values, (std::vector<double>{4, 6, 10.5}));
  EXPECT_FALSE(ParseNumberList("4,x", &values));
  EXPECT_FALSE(ParseNumberList("", &values));
  EXPECT_FALSE(ParseNumberList("inf", &values));
}

TEST(MatchingBenchmarkTest, FramePairsAreTwoDifferentFrames) {
  int a = -1, b = -1;
  ASSERT_TRUE(ParseFramePair("10,11", &a, &b));
  EXPECT_EQ(a, 10);
  EXPECT_EQ(b, 11);
  for (const char* text : {"1,1", "1.5,2", "-1,2", "1,2,3", "1"})
    EXPECT_FALSE(ParseFramePair(text, &a, &b)) << text;
}

}  // namespace
}  // namespace sfm
