#include "core/radiance_check.h"

#include <cstdint>
#include <cstdio>

namespace tessera {

bool looks_like_radiance(const unsigned char* data, size_t size) {
  return size >= 2 && data[0] == '#' && data[1] == '?';
}

std::string radiance_fault(const unsigned char* data, size_t size) {
  if (!looks_like_radiance(data, size)) return "";
  size_t at = 0;
  // The next line, without its newline; false at the end of the data (stb_image then refuses
  // the header by itself).
  const auto next_line = [&](std::string& text) {
    text.clear();
    while (at < size && data[at] != '\n') text += char(data[at++]);
    if (at >= size) return false;
    ++at;
    return true;
  };
  std::string text;
  do {
    if (!next_line(text)) return "";
  } while (!text.empty());  // the header ends at an empty line
  int height = 0, width = 0;
  if (!next_line(text) || std::sscanf(text.c_str(), "-Y %d +X %d", &height, &width) != 2 ||
      width <= 0 || height <= 0) {
    return "";  // an orientation or size stb_image refuses by itself
  }
  const uint64_t w = uint64_t(width), h = uint64_t(height);
  const std::string truncated = "is truncated: its " + std::to_string(w) + "x" + std::to_string(h) +
                                " texels need more than its " + std::to_string(size) + " bytes";
  const auto has = [&](uint64_t bytes) { return size - at >= bytes; };
  // Whether `rows` rows of flat 4-byte texels follow `at` (the image read to its end).
  const auto flat = [&](uint64_t rows) {
    // w * rows <= (size - at) / 4, without the product (up to 2^62).
    return (size - at) / 4 / w >= rows ? std::string() : truncated;
  };
  if (w < 8 || w >= 32768) return flat(h);
  for (uint64_t j = 0; j < h; ++j) {
    if (!has(4)) return truncated;
    if (data[at] != 2 || data[at + 1] != 2 || (data[at + 2] & 0x80) != 0) {
      // Not a run-length scanline: stb_image takes these 4 bytes as the image's first texel
      // and reads every texel from there, flat, from the first row again.
      return flat(h);
    }
    if ((uint64_t(data[at + 2]) << 8 | data[at + 3]) != w) return "";  // stb_image refuses it
    at += 4;
    for (int channel = 0; channel < 4; ++channel) {
      for (uint64_t i = 0; i < w;) {
        if (!has(1)) return truncated;
        uint64_t count = data[at++];
        const bool run = count > 128;  // a run of count - 128 copies of the next byte
        if (run) count -= 128;
        if (count == 0) {  // a dump of no bytes: stb_image's decoder would not advance
          return "has a run-length count of 0 in scanline " + std::to_string(j) +
                 " (corrupt: the decoder would never finish)";
        }
        if (count > w - i) return "";  // stb_image refuses it ("bad RLE data")
        const uint64_t bytes = run ? 1 : count;
        if (!has(bytes)) return truncated;
        at += bytes;
        i += count;
      }
    }
  }
  return "";
}

}  // namespace tessera
