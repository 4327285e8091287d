#include "util/number_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace sfm {

std::string ShortestNumberText(double value) {
  if (!std::isfinite(value)) return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  if (value == 0) value = 0;  // turns -0 into +0
  // No precision below the shortest round-trip representation's digit count can round-trip, so the
  // search starts there (std::to_chars gives that count without the snprintf/strtod trials).
  char shortest[32];
  const char* end = std::to_chars(shortest, shortest + sizeof(shortest), value, std::chars_format::scientific).ptr;
  const char* mantissa_end = std::find(static_cast<const char*>(shortest), end, 'e');
  const int digits = static_cast<int>(
      std::count_if(static_cast<const char*>(shortest), mantissa_end, [](char c) { return c >= '0' && c <= '9'; }));
  char buffer[32];
  for (int precision = std::max(6, digits); precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

}  // namespace sfm
