// Small helpers for writing JSON text by hand (the project writes a few fixed-shape files).
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace sfm {

// A number as JSON: shortest round-trip form; NaN and infinities become null (JSON has neither).
std::string JsonNumber(double value);
std::string JsonNumber(const std::optional<double>& value);  // nullopt -> null
// A string as JSON, quoted, with ", \ and control characters escaped. JSON text is UTF-8: a byte
// that is not part of a valid UTF-8 sequence is written as \ufffd (the replacement character), so
// the file stays valid JSON whatever the input.
std::string JsonString(const std::string& value);

// Whether `text` is valid UTF-8 (RFC 3629: no overlong forms, no surrogates, at most U+10FFFF).
bool IsValidUtf8(const std::string& text);

// The length of the valid UTF-8 sequence that starts at text[at], or 0 when none does.
size_t Utf8SequenceLength(const std::string& text, size_t at);

}  // namespace sfm
