// The junctions file of one frame, junctions/<NNNNNN>.json (SPEC section 3).
#pragma once

#include <string>

#include "frontend/junctions/junction.h"
#include "util/status.h"

namespace sfm {

// The content of one junctions file.
struct JunctionsFile {
  int frame = 0;
  std::string image;  // image path as listed in images.txt
  int width = 0, height = 0;
  Junctions junctions;  // line_segment is not stored in the file: -1 after reading
};

// SPEC section 3 layout: {"frame", "image", "width", "height", "junctions": [{"id", "x", "y",
// "type", "score", "segments": [[x, y], ...]}]}, one junction per line. Coordinates in pixels with
// three decimals (a thousandth of a pixel, far below the detector's accuracy), score with six
// significant digits; locale-independent. CHECK-fails on a non-finite number (JSON has none).
std::string JunctionsToJson(int frame, const std::string& image, int width, int height,
                            const Junctions& junctions);

// Reads a file written by JunctionsToJson, or any JSON of the same shape (key order free, unknown
// keys ignored). On error, a one-line message naming `source` (a file name, for messages) and what
// is wrong.
Status JunctionsFromJson(const std::string& json, const std::string& source, JunctionsFile* file);

}  // namespace sfm
