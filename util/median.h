// The median of a sample, for the robust statistics of the back end.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

namespace sfm {

// The middle value (the mean of the two middle values for an even count); NaN for no value.
inline double Median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  const double upper = values[middle];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + middle));
}

}  // namespace sfm
