#pragma once
// CPU-side images and their files. Rows are stored top to bottom, pixels left to right.

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tessera {

/// Linear HDR image, RGBA 32-bit float per channel.
struct ImageF {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<glm::vec4> pixels;  // width * height
  glm::vec4& at(uint32_t x, uint32_t y) { return pixels[size_t(y) * width + x]; }
  const glm::vec4& at(uint32_t x, uint32_t y) const { return pixels[size_t(y) * width + x]; }
};

/// Display image, RGBA 8 bits per channel, sRGB-encoded.
struct Image8 {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<glm::u8vec4> pixels;  // width * height
  glm::u8vec4& at(uint32_t x, uint32_t y) { return pixels[size_t(y) * width + x]; }
  const glm::u8vec4& at(uint32_t x, uint32_t y) const { return pixels[size_t(y) * width + x]; }
};

/// Writes `image` as PNG. Throws Error naming the path if it cannot be written.
void write_png(const std::string& path, const Image8& image);

/// Reads a PNG (any channel count, 8 bits; converted to RGBA). Throws Error naming the path
/// and the reason if it cannot be read.
Image8 read_png(const std::string& path);

/// Writes the RGB channels of `image` as a little-endian PFM (portable float map, bit-exact)
/// or Radiance .hdr (RGBE, 8-bit shared exponent), chosen by the extension `.pfm` or `.hdr`.
/// Throws Error for another extension or an unwritable path.
void write_hdr_image(const std::string& path, const ImageF& image);

/// Reads a PFM written by write_hdr_image (alpha set to 1). Throws Error on a malformed file.
ImageF read_pfm(const std::string& path);

/// Why no file could be written at `path` ("it is a folder", "folder 'out' does not exist",
/// "no permission to write in folder 'out'", ...), or "" if one could: it is writable, or it
/// does not exist and its folder does and is writable. Creates nothing.
std::string unwritable_reason(const std::string& path);

}  // namespace tessera
