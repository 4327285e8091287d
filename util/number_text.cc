#include "util/number_text.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace sfm {

std::string ShortestNumberText(double value) {
  if (!std::isfinite(value)) return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  if (value == 0) value = 0;  // turns -0 into +0
  char buffer[32];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

}  // namespace sfm
