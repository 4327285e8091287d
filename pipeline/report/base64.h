// Base64 (RFC 4648 section 4, standard alphabet, '=' padding), for the data URIs of report.html.
//
// Written here rather than taken from a library: it is thirty lines, the project's dependencies
// (OpenCV, Eigen, glog, gflags) expose none (OpenCV's base64 lives in its private persistence
// code), and adding a package for it would cost more than the code.
#pragma once

#include <string>
#include <string_view>

namespace sfm {

// The base64 text of `bytes` (no line breaks).
std::string Base64Encode(std::string_view bytes);

// Decodes base64 text as Base64Encode writes it (padding required, no whitespace). Returns false,
// leaving `bytes` unspecified, on a character outside the alphabet, a length not a multiple of 4
// or misplaced padding.
bool Base64Decode(std::string_view text, std::string* bytes);

}  // namespace sfm
