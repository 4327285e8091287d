// Small helpers for writing JSON text by hand (the project writes a few fixed-shape files).
#pragma once

#include <optional>
#include <string>

namespace sfm {

// A number as JSON: shortest round-trip form; NaN and infinities become null (JSON has neither).
std::string JsonNumber(double value);
std::string JsonNumber(const std::optional<double>& value);  // nullopt -> null
// A string as JSON, quoted, with ", \ and control characters escaped.
std::string JsonString(const std::string& value);

}  // namespace sfm
