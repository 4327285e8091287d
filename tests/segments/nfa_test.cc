#include "frontend/segments/nfa.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sfm {
namespace {

double BruteForceTail(int n, int k, double p) {
  double sum = 0;
  for (int i = k; i <= n; ++i) {
    sum += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0)) * std::pow(p, i) *
           std::pow(1 - p, n - i);
  }
  return sum;
}

TEST(NfaTest, BinomialTailMatchesTheSumOfTerms) {
  for (const int n : {1, 10, 57, 300}) {
    for (const int k : {0, 1, n / 8, n / 2, n}) {
      const double expected = BruteForceTail(n, k, 0.125);
      EXPECT_NEAR(Log10BinomialTail(n, k, 0.125), std::log10(expected), 1e-9) << n << " " << k;
    }
  }
}

// With (512*512)^2 tests and precision 1/8, 12 fully aligned samples give NFA = 512^4 / 8^12 = 1
// exactly: 11 are not meaningful, 13 are.
TEST(NfaTest, ShortestMeaningfulAlignedSegment) {
  EXPECT_NEAR(Log10Nfa(12, 12, 0.125, 512, 512), 0, 1e-9);
  EXPECT_GT(Log10Nfa(11, 11, 0.125, 512, 512), 0.5);
  EXPECT_LT(Log10Nfa(13, 13, 0.125, 512, 512), -0.5);
  EXPECT_GT(Log10Nfa(20, 10, 0.125, 512, 512), 0);
}

// The number of tests may be given: (512*512)^2 tests is the image form; fewer tests, fewer samples.
TEST(NfaTest, GivenNumberOfTests) {
  EXPECT_NEAR(Log10Nfa(15, 13, 0.125, 4 * std::log10(512.0)), Log10Nfa(15, 13, 0.125, 512, 512), 1e-12);
  EXPECT_NEAR(Log10Nfa(8, 8, 0.125, 8 * std::log10(8.0)), 0, 1e-9);
  EXPECT_GT(Log10Nfa(7, 7, 0.125, 8 * std::log10(8.0)), 0.5);
}

}  // namespace
}  // namespace sfm
