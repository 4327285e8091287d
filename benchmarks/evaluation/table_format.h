// Number formatting for the markdown tables the benchmark programs print.
#pragma once

#include <cstdio>
#include <string>

namespace sfm {

// `value` with `digits` decimals.
inline std::string Fixed(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
  return buffer;
}

// "12.3 %" for part/whole, "-" when whole is 0.
inline std::string Percent(int part, int whole) {
  return whole > 0 ? Fixed(100.0 * part / whole, 1) + " %" : "-";
}

}  // namespace sfm
