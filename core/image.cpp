#include "core/image.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

#include <unistd.h>

#include "core/check.h"
#include "core/file_extension.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

namespace tessera {

void write_png(const std::string& path, const Image8& image) {
  TESSERA_CHECK(image.pixels.size() == size_t(image.width) * image.height);
  errno = 0;
  if (!stbi_write_png(path.c_str(), int(image.width), int(image.height), 4, image.pixels.data(),
                      int(image.width * 4))) {
    // stb opens and writes with stdio, which leave the reason (no space, no permission) here.
    throw Error("cannot write PNG '" + path + "'" +
                (errno ? std::string(": ") + std::strerror(errno) : std::string()));
  }
}

Image8 read_png(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load(path.c_str(), &w, &h, &channels, 4),
                                                 stbi_image_free);
  if (!data) throw Error("cannot read PNG '" + path + "': " + stbi_failure_reason());
  Image8 image{uint32_t(w), uint32_t(h), std::vector<glm::u8vec4>(size_t(w) * h)};
  std::memcpy(image.pixels.data(), data.get(), image.pixels.size() * 4);
  return image;
}

void write_hdr_image(const std::string& path, const ImageF& image) {
  TESSERA_CHECK(image.pixels.size() == size_t(image.width) * image.height);
  std::vector<float> rgb(size_t(image.width) * image.height * 3);
  if (has_extension(path, ".hdr")) {
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = image.pixels[i][c];
    }
    if (!stbi_write_hdr(path.c_str(), int(image.width), int(image.height), 3, rgb.data())) {
      throw Error("cannot write HDR image '" + path + "'");
    }
    return;
  }
  if (!has_extension(path, ".pfm")) {
    throw Error("HDR output '" + path + "' must end in .pfm or .hdr");
  }
  // PFM stores rows bottom to top; a negative scale means little-endian.
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) {
      const glm::vec4& p = image.at(x, image.height - 1 - y);
      float* out = &rgb[(size_t(y) * image.width + x) * 3];
      out[0] = p.r;
      out[1] = p.g;
      out[2] = p.b;
    }
  }
  std::ofstream file(path, std::ios::binary);
  file << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
  file.write(reinterpret_cast<const char*>(rgb.data()), std::streamsize(rgb.size() * 4));
  if (!file) throw Error("cannot write PFM '" + path + "'");
}

ImageF read_pfm(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error("cannot open PFM '" + path + "'");
  std::string magic;
  long width = 0, height = 0;
  double scale = 0;
  file >> magic >> width >> height >> scale;
  file.get();  // the single whitespace after the header
  if (magic != "PF" || width <= 0 || height <= 0 || scale >= 0 || width > 65536 || height > 65536) {
    throw Error("'" + path + "' is not a little-endian RGB PFM file");
  }
  ImageF image{uint32_t(width), uint32_t(height), {}};
  std::vector<float> rgb(size_t(width) * height * 3);
  file.read(reinterpret_cast<char*>(rgb.data()), std::streamsize(rgb.size() * 4));
  if (!file) throw Error("PFM '" + path + "' is truncated");
  image.pixels.resize(size_t(width) * height);
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) {
      const float* in = &rgb[(size_t(image.height - 1 - y) * width + x) * 3];
      image.at(x, y) = glm::vec4(in[0], in[1], in[2], 1.0f);
    }
  }
  return image;
}

std::string unwritable_reason(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path p(path);
  if (p.filename().empty()) return "the path names no file";
  if (fs::is_directory(p, ec)) return "it is a folder";
  if (fs::exists(p, ec)) {
    return ::access(path.c_str(), W_OK) == 0 ? "" : "no permission to write the file";
  }
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  // Appended rather than built with operator+: GCC 12 warns (-Wrestrict, a false positive)
  // on a literal + std::string there.
  const std::string quoted = std::string("'").append(dir.string()).append("'");
  if (!fs::exists(dir, ec)) return std::string("folder ").append(quoted).append(" does not exist");
  if (!fs::is_directory(dir, ec)) return std::string(quoted).append(" is not a folder");
  if (::access(dir.c_str(), W_OK) != 0)
    return std::string("no permission to write in folder ").append(quoted);
  return "";
}

}  // namespace tessera
