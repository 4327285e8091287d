#include "frontend/sequence/image_header.h"

#include <cctype>
#include <cstdint>
#include <cstring>

namespace sfm {
namespace {

uint32_t BigEndian32(const std::string& d, size_t at) {
  return (uint32_t(uint8_t(d[at])) << 24) | (uint32_t(uint8_t(d[at + 1])) << 16) |
         (uint32_t(uint8_t(d[at + 2])) << 8) | uint32_t(uint8_t(d[at + 3]));
}

uint32_t BigEndian16(const std::string& d, size_t at) {
  return (uint32_t(uint8_t(d[at])) << 8) | uint8_t(d[at + 1]);
}

int ClampedSize(uint32_t value) { return value > 0x7fffffffu ? 0x7fffffff : static_cast<int>(value); }

// PNG (ISO/IEC 15948): the 8-byte signature, IHDR first (width, height big-endian), chunks of
// length + type + data + CRC, IEND last.
void ReadPng(const std::string& d, ImageHeader* header) {
  header->format = "PNG";
  if (d.size() < 24 || d.compare(12, 4, "IHDR") != 0) {
    header->problem = "PNG is truncated or damaged: no IHDR chunk";
    return;
  }
  header->width = ClampedSize(BigEndian32(d, 16));
  header->height = ClampedSize(BigEndian32(d, 20));
  for (size_t at = 8; at + 12 <= d.size();) {
    const uint64_t length = BigEndian32(d, at);
    if (d.compare(at + 4, 4, "IEND") == 0) return;
    at += 12 + length;
  }
  header->problem = "PNG is truncated: no IEND chunk";
}

// JPEG (ITU T.81, annex B): markers FF xx; SOFn holds the size; each SOS is followed by
// entropy-coded data in which FF is always followed by 00 (stuffing) or a restart marker D0-D7,
// so the next other marker ends the scan; the image ends at EOI (FF D9).
void ReadJpeg(const std::string& d, ImageHeader* header) {
  header->format = "JPEG";
  size_t at = 2;
  while (at + 1 < d.size()) {
    if (uint8_t(d[at]) != 0xFF) {
      header->problem = "JPEG is damaged: a marker was expected at byte " + std::to_string(at);
      return;
    }
    const uint8_t marker = uint8_t(d[at + 1]);
    if (marker == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0xD9) return;  // EOI: complete
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) {
      at += 2;
      continue;
    }
    if (at + 4 > d.size()) break;
    const size_t length = BigEndian16(d, at + 2);
    if (length < 2 || at + 2 + length > d.size()) break;
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof && length >= 7 && header->width == 0) {
      header->height = static_cast<int>(BigEndian16(d, at + 5));
      header->width = static_cast<int>(BigEndian16(d, at + 7));
    }
    at += 2 + length;
    if (marker == 0xDA) {  // SOS: skip the entropy-coded data
      while (at + 1 < d.size()) {
        if (uint8_t(d[at]) == 0xFF) {
          const uint8_t next = uint8_t(d[at + 1]);
          if (next != 0x00 && !(next >= 0xD0 && next <= 0xD7) && next != 0xFF) break;
        }
        ++at;
      }
    }
  }
  header->problem = "JPEG is truncated: no end-of-image marker";
}

// PNM (P1-P6): magic, then width and height as decimal text, with '#' comments between.
void ReadPnm(const std::string& d, ImageHeader* header) {
  header->format = "PNM";
  size_t at = 2;
  int values[2] = {0, 0};
  for (int& value : values) {
    for (;;) {
      while (at < d.size() && std::isspace(static_cast<unsigned char>(d[at]))) ++at;
      if (at < d.size() && d[at] == '#') {
        while (at < d.size() && d[at] != '\n') ++at;
        continue;
      }
      break;
    }
    long long read = 0;
    const size_t start = at;
    while (at < d.size() && std::isdigit(static_cast<unsigned char>(d[at])) && read <= 0x7fffffff) {
      read = read * 10 + (d[at++] - '0');
    }
    if (at == start) {
      header->problem = "PNM header is truncated or damaged";
      return;
    }
    value = read > 0x7fffffff ? 0x7fffffff : static_cast<int>(read);
  }
  header->width = values[0];
  header->height = values[1];
}

}  // namespace

ImageHeader ReadImageHeader(const std::string& data) {
  ImageHeader header;
  if (data.size() >= 8 && std::memcmp(data.data(), "\x89PNG\r\n\x1a\n", 8) == 0) {
    ReadPng(data, &header);
  } else if (data.size() >= 3 && uint8_t(data[0]) == 0xFF && uint8_t(data[1]) == 0xD8 &&
             uint8_t(data[2]) == 0xFF) {
    ReadJpeg(data, &header);
  } else if (data.size() >= 3 && data[0] == 'P' && data[1] >= '1' && data[1] <= '6' &&
             std::isspace(static_cast<unsigned char>(data[2]))) {
    ReadPnm(data, &header);
  }
  return header;
}

}  // namespace sfm
