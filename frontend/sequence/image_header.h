// The size an image file declares and whether its data is complete, read from the file's own
// structure before it is decoded: a PNG's IHDR and IEND chunks, a JPEG's SOF and EOI markers, a
// PNM's header. So an image of the wrong size (a decompression bomb among them) is refused without
// decoding it, and a truncated JPEG, which libjpeg decodes with a warning and grey rows, is refused.
#pragma once

#include <string>

namespace sfm {

struct ImageHeader {
  std::string format;  // "PNG", "JPEG", "PNM", or "" when the format is not one of these
  int width = 0;       // pixels; 0 when not found
  int height = 0;
  std::string problem;  // "" or what is wrong ("JPEG is truncated: no end-of-image marker")
};

// Reads `data`, the whole content of an image file.
ImageHeader ReadImageHeader(const std::string& data);

}  // namespace sfm
