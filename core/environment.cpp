#include "core/environment.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

#include <stb/stb_image.h>

#include "core/check.h"
#include "core/file_extension.h"
#include "core/mapped_file.h"
#include "core/radiance_check.h"

namespace tessera {
namespace {

constexpr double kPi = std::numbers::pi;

// Largest Radiance file read (a 16384 x 8192 map, uncompressed, is 512 MiB).
constexpr uint64_t kMaxHdrBytes = uint64_t(1) << 30;

}  // namespace

void validate_environment(const Environment& env) {
  const ImageF& r = env.radiance;
  if (r.width > 0 && r.width < 2 && r.pixels.size() == size_t(r.width) * r.height) {
    // One texel across cannot wrap around the horizon (bilinear lookups need two).
    throw Error("environment map of " + std::to_string(r.width) + "x" + std::to_string(r.height) +
                " texels is too narrow: it needs at least 2 texels across");
  }
  if (r.width < 2 || r.height < 1 || r.pixels.size() != size_t(r.width) * r.height) {
    throw Error("environment map of " + std::to_string(r.width) + "x" + std::to_string(r.height) +
                " texels is empty or inconsistent");
  }
  const double aspect = double(r.width) / r.height;
  if (aspect < 0.5 || aspect > 4.0) {
    throw Error("environment map of " + std::to_string(r.width) + "x" + std::to_string(r.height) +
                " is not equirectangular (width should be about twice the height)");
  }
  if (r.width > 16384 || r.height > 16384) {
    throw Error("environment map of " + std::to_string(r.width) + "x" + std::to_string(r.height) +
                " is over the largest side of 16384");
  }
  for (size_t i = 0; i < r.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const float v = r.pixels[i][c];
      if (!std::isfinite(v) || v < 0.0f) {
        throw Error("environment map texel (" + std::to_string(i % r.width) + ", " +
                    std::to_string(i / r.width) + ") has a NaN, infinite or negative radiance");
      }
    }
  }
}

Environment load_environment(const std::string& path) {
  // Before it is opened: a FIFO would block the open until a writer came.
  require_regular_file(path);
  Environment env;
  if (has_extension(path, ".pfm")) {
    env.radiance = read_pfm(path);
  } else if (has_extension(path, ".hdr")) {
    std::error_code ec;
    // stb_image's own reason ("can't fopen") would not say which.
    if (!std::filesystem::is_regular_file(path, ec))
      throw Error("cannot read environment '" + path + "': no such file");
    const MappedFile file = map_file(path, kMaxHdrBytes);
    // stb_image reads a truncated file's missing texels as black without a word, and loops for
    // ever on a run-length count of 0: checked first (core/radiance_check.h).
    if (const std::string fault = radiance_fault(file.data(), file.size()); !fault.empty())
      throw Error("Radiance .hdr '" + path + "' " + fault);
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<float, void (*)(void*)> data(
        stbi_loadf_from_memory(file.data(), int(file.size()), &w, &h, &channels, 4),
        stbi_image_free);
    if (!data) {
      const std::string reason = stbi_failure_reason();
      // A Radiance header whose size overflows stb_image's limits: a Radiance file, too large.
      if (reason == "too large") {
        throw Error("cannot read environment '" + path +
                    "': its size is too large to decode (environment maps have at most 16384 "
                    "texels a side)");
      }
      throw Error("cannot read environment '" + path + "': not a Radiance .hdr image (" + reason +
                  ")");
    }
    env.radiance.width = uint32_t(w);
    env.radiance.height = uint32_t(h);
    const auto* texels = reinterpret_cast<const glm::vec4*>(data.get());
    env.radiance.pixels.assign(texels, texels + size_t(w) * h);
  } else {
    throw Error("environment '" + path + "' is neither a Radiance .hdr nor a .pfm file");
  }
  for (glm::vec4& p : env.radiance.pixels) p.a = 1.0f;
  try {
    validate_environment(env);
  } catch (const Error& e) {
    throw Error("environment '" + path + "': " + e.what());
  }
  return env;
}

glm::dvec2 equirect_uv(glm::dvec3 d) {
  const double u = 0.5 + std::atan2(d.x, -d.z) / (2.0 * kPi);
  const double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi;
  return {u - std::floor(u), v};
}

glm::dvec3 equirect_direction(glm::dvec2 uv) {
  const double phi = 2.0 * kPi * (uv.x - 0.5), theta = kPi * uv.y;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

glm::dvec3 environment_radiance(const Environment& env, glm::dvec3 d) {
  const ImageF& r = env.radiance;
  const glm::dvec2 uv = equirect_uv(d);
  const double x = uv.x * r.width - 0.5, y = uv.y * r.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  auto at = [&](double xi, double yi) {
    int64_t ix = int64_t(xi) % int64_t(r.width);
    if (ix < 0) ix += r.width;
    const int64_t iy = std::clamp<int64_t>(int64_t(yi), 0, int64_t(r.height) - 1);
    return glm::dvec3(r.at(uint32_t(ix), uint32_t(iy)));
  };
  return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx),
                  glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
}

Environment make_sky_environment(uint32_t width) {
  if (width < 4 || width > 16384)
    throw Error("sky width " + std::to_string(width) + " is outside 4..16384");
  Environment env;
  ImageF& r = env.radiance;
  r.width = width;
  r.height = width / 2;
  r.pixels.resize(size_t(r.width) * r.height);
  const glm::dvec3 sun_dir = glm::normalize(glm::dvec3(0.5, 0.45, -0.6));
  const glm::dvec3 zenith(0.15, 0.3, 0.8), horizon(0.9, 0.95, 1.0), ground(0.12, 0.1, 0.08);
  const glm::dvec3 sun(8.0, 7.2, 6.0);
  for (uint32_t y = 0; y < r.height; ++y) {
    for (uint32_t x = 0; x < r.width; ++x) {
      const glm::dvec3 d = equirect_direction({(x + 0.5) / r.width, (y + 0.5) / r.height});
      glm::dvec3 c;
      if (d.y >= 0.0) {
        c = glm::mix(horizon, zenith, std::pow(d.y, 0.5));
      } else {
        // Ground fades in over a few degrees so the horizon stays smooth.
        c = glm::mix(horizon * 0.5, ground, std::min(1.0, -d.y * 8.0));
      }
      // Smooth sun lobe: cos^64 falls to half at about 8.4 degrees, wide enough for the
      // stratified Monte Carlo reference to resolve (a sun disk would need light sampling).
      c += sun * std::pow(std::max(glm::dot(d, sun_dir), 0.0), 64.0);
      r.at(x, y) = glm::vec4(glm::vec3(c), 1.0f);
    }
  }
  return env;
}

Environment make_uniform_environment(glm::vec3 radiance) {
  Environment env;
  env.radiance = {16, 8, std::vector<glm::vec4>(16 * 8, glm::vec4(radiance, 1.0f))};
  return env;
}

}  // namespace tessera
