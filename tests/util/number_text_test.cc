// ShortestNumberText against its definition: the shortest "%.{6..17}g" text that reads back to the
// same double, found here by trying every precision from 6.
#include "util/number_text.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

namespace sfm {
namespace {

std::string ByDefinition(double value) {
  if (value == 0) value = 0;
  char buffer[32];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

// Figure protected: the same text as the definition for every one of 80000 doubles (uniform,
// log-uniform over 1e-300..1e300 of both signs, powers of two, whole and decimal numbers).
TEST(NumberTextTest, ShortestNumberTextIsTheShortestRoundTripPrecisionFromSix) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-1, 1), exponent(-300, 300);
  std::uniform_int_distribution<int> whole(-100000, 100000);
  for (int k = 0; k < 20000; ++k) {
    const double values[] = {unit(rng), std::copysign(std::pow(10.0, exponent(rng)), unit(rng)),
                             std::ldexp(1.0, whole(rng) % 1000), whole(rng) / 100.0};
    for (const double value : values) ASSERT_EQ(ShortestNumberText(value), ByDefinition(value)) << value;
  }
  EXPECT_EQ(ShortestNumberText(0.1), "0.1");
  EXPECT_EQ(ShortestNumberText(-0.0), "0");
  EXPECT_EQ(ShortestNumberText(1.0 / 3), "0.3333333333333333");
  EXPECT_EQ(ShortestNumberText(std::numeric_limits<double>::denorm_min()), ByDefinition(4.9406564584124654e-324));
  EXPECT_EQ(ShortestNumberText(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(ShortestNumberText(-std::numeric_limits<double>::infinity()), "-inf");
}

}  // namespace
}  // namespace sfm
