#include "core/texture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>

#include <stb/stb_image.h>

#include "core/check.h"
#include "core/mapped_file.h"
#include "core/radiance_check.h"

namespace tessera {

std::string image_failure_reason() {
  const std::string reason = stbi_failure_reason() ? stbi_failure_reason() : "";
  if (reason == "outofdata") return "the data ends early (a truncated file?)";
  return reason;
}

std::optional<glm::uvec2> oversized_image(std::span<const unsigned char> bytes, uint32_t max_side) {
  int w = 0, h = 0, channels = 0;
  glm::uvec2 size;
  static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (bytes.size() <= size_t(INT32_MAX) &&
      stbi_info_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels)) {
    size = glm::uvec2(uint32_t(w), uint32_t(h));
  } else if (bytes.size() >= 24 && std::memcmp(bytes.data(), kPng, 8) == 0 &&
             std::memcmp(bytes.data() + 12, "IHDR", 4) == 0) {
    // stb_image refuses a PNG header whose image would take 2^30 bytes or more (100000 x 100000,
    // say) and then tries the other formats, so that it says "unknown image type": the size is
    // read from the IHDR chunk instead, which comes first, width and height as big-endian 32-bit
    // numbers at bytes 16 and 20 (PNG, ISO/IEC 15948, 5.2, 5.3 and 11.2.2).
    const auto big_endian = [&](size_t at) {
      return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 |
             uint32_t(bytes[at + 2]) << 8 | uint32_t(bytes[at + 3]);
    };
    size = glm::uvec2(big_endian(16), big_endian(20));
  } else {
    return std::nullopt;
  }
  if (size.x > max_side || size.y > max_side) return size;
  return std::nullopt;
}

Texture load_texture(const std::string& path, bool srgb) {
  // stb_image reads at most 2 GiB from memory.
  const MappedFile file = map_file(path, uint64_t(INT32_MAX));
  const auto too_large = [&](glm::uvec2 size) {
    return Error("texture '" + path + "' is " + std::to_string(size.x) + "x" +
                 std::to_string(size.y) + ", over the largest side of " +
                 std::to_string(kMaxTextureSide));
  };
  if (const auto size = oversized_image({file.data(), file.size()}, kMaxTextureSide)) {
    throw too_large(*size);
  }
  // stb_image decodes a Radiance file whatever its name, and hangs on a corrupt one.
  if (const std::string fault = radiance_fault(file.data(), file.size()); !fault.empty())
    throw Error("texture '" + path + "' " + fault);
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> data(
      stbi_load_from_memory(file.data(), int(file.size()), &w, &h, &channels, 4), stbi_image_free);
  if (!data) throw Error("cannot read texture '" + path + "': " + image_failure_reason());
  if (uint32_t(w) > kMaxTextureSide || uint32_t(h) > kMaxTextureSide) {
    throw too_large(glm::uvec2(uint32_t(w), uint32_t(h)));
  }
  Texture t;
  t.width = uint32_t(w);
  t.height = uint32_t(h);
  t.srgb = srgb;
  const auto* texels = reinterpret_cast<const glm::u8vec4*>(data.get());
  t.texels.assign(texels, texels + size_t(w) * h);
  return t;
}

double srgb_to_linear(uint8_t value) {
  const double c = value / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

MipChain build_mip_chain(const Texture& texture) {
  TESSERA_CHECK(texture.width > 0 && texture.height > 0 &&
                texture.texels.size() == size_t(texture.width) * texture.height);
  MipChain chain;
  chain.wrap_u = texture.wrap_u;
  chain.wrap_v = texture.wrap_v;
  // srgb_to_linear of each byte value, computed once: a pow per channel and texel was most of
  // a chain's time.
  static const std::array<float, 256> kLinear = [] {
    std::array<float, 256> table{};
    for (int v = 0; v < 256; ++v) table[size_t(v)] = float(srgb_to_linear(uint8_t(v)));
    return table;
  }();
  MipChain::Level base{texture.width, texture.height, {}};
  base.texels.reserve(texture.texels.size());
  for (const glm::u8vec4& t : texture.texels) {
    glm::vec4 c = glm::vec4(t) / 255.0f;
    if (texture.srgb) {
      for (int k = 0; k < 3; ++k) c[k] = kLinear[t[k]];
    }
    base.texels.push_back(c);
  }
  chain.levels.push_back(std::move(base));
  while (chain.levels.back().width > 1 || chain.levels.back().height > 1) {
    const MipChain::Level& src = chain.levels.back();
    MipChain::Level dst{std::max(1u, src.width / 2), std::max(1u, src.height / 2), {}};
    dst.texels.resize(size_t(dst.width) * dst.height);
    for (uint32_t y = 0; y < dst.height; ++y) {
      for (uint32_t x = 0; x < dst.width; ++x) {
        glm::dvec4 sum(0.0);
        int count = 0;
        // A side of 1 keeps its single row or column; odd sides drop their last one.
        for (uint32_t dy = 0; dy < (src.height > 1 ? 2u : 1u); ++dy) {
          for (uint32_t dx = 0; dx < (src.width > 1 ? 2u : 1u); ++dx) {
            sum += glm::dvec4(src.texels[size_t(2 * y + dy) * src.width + (2 * x + dx)]);
            ++count;
          }
        }
        dst.texels[size_t(y) * dst.width + x] = glm::vec4(sum / double(count));
      }
    }
    chain.levels.push_back(std::move(dst));
  }
  return chain;
}

namespace {

int64_t wrap(int64_t i, int64_t n) {
  const int64_t r = i % n;
  return r < 0 ? r + n : r;
}

// A coordinate folded as shaders/texture.glsl does before a bilinear lookup: mirrored repeat
// into [0, 1] (period 2), clamp to edge clamped to [0, 1] (beyond, every lookup reads the edge
// texel alike); repeat is left, its texel indices wrap instead.
double fold(double u, TextureWrap mode) {
  if (mode == TextureWrap::mirrored_repeat) {
    const double t = u - 2.0 * std::floor(0.5 * u);
    return t > 1.0 ? 2.0 - t : t;
  }
  return mode == TextureWrap::clamp_to_edge ? std::clamp(u, 0.0, 1.0) : u;
}

// Texel index i of a level n texels wide: repeat wraps; the others stay within one texel of
// [0, n) after fold, where mirroring and clamping both read the edge texel.
int64_t texel_index(int64_t i, int64_t n, TextureWrap mode) {
  return mode == TextureWrap::repeat ? wrap(i, n) : std::clamp<int64_t>(i, 0, n - 1);
}

glm::dvec4 bilinear(const MipChain& chain, const MipChain::Level& level, glm::dvec2 uv) {
  uv = {fold(uv.x, chain.wrap_u), fold(uv.y, chain.wrap_v)};
  const double x = uv.x * level.width - 0.5, y = uv.y * level.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  auto at = [&](double xi, double yi) {
    const int64_t ix = texel_index(int64_t(xi), level.width, chain.wrap_u);
    const int64_t iy = texel_index(int64_t(yi), level.height, chain.wrap_v);
    return glm::dvec4(level.texels[size_t(iy) * level.width + size_t(ix)]);
  };
  return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx),
                  glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
}

glm::dvec4 trilinear(const MipChain& chain, glm::dvec2 uv, double lod) {
  const double top = double(chain.levels.size() - 1);
  lod = std::clamp(lod, 0.0, top);
  const double l0 = std::floor(lod);
  const size_t i0 = size_t(l0), i1 = std::min(i0 + 1, chain.levels.size() - 1);
  return glm::mix(bilinear(chain, chain.levels[i0], uv), bilinear(chain, chain.levels[i1], uv),
                  lod - l0);
}

}  // namespace

glm::dvec4 sample_texture(const MipChain& chain, glm::dvec2 uv, glm::dvec2 duv_dx,
                          glm::dvec2 duv_dy, uint32_t max_anisotropy) {
  // uv far outside [0, 1] lose their fraction in float on the GPU; wrap first, like it does.
  if (chain.wrap_u == TextureWrap::repeat) uv.x -= std::floor(uv.x);
  if (chain.wrap_v == TextureWrap::repeat) uv.y -= std::floor(uv.y);
  const glm::dvec2 size(chain.levels[0].width, chain.levels[0].height);
  const double lx = glm::length(duv_dx * size), ly = glm::length(duv_dy * size);
  const double major = std::max(lx, ly), minor = std::min(lx, ly);
  if (!std::isfinite(major)) return trilinear(chain, uv, double(chain.levels.size() - 1));
  double probes = 1.0;
  if (max_anisotropy > 1 && major > minor) {
    probes = std::min(std::ceil(major / std::max(minor, 1e-20)), double(max_anisotropy));
  }
  const double lod = std::log2(major / probes);  // -inf for a zero footprint: clamped to 0
  const glm::dvec2 axis = lx >= ly ? duv_dx : duv_dy;
  glm::dvec4 sum(0.0);
  for (int i = 0; i < int(probes); ++i) {
    sum += trilinear(chain, uv + axis * ((i + 0.5) / probes - 0.5), lod);
  }
  return sum / probes;
}

std::vector<glm::vec4> generate_tangents(const std::vector<glm::vec3>& positions,
                                         const std::vector<glm::vec3>& normals,
                                         const std::vector<glm::vec2>& uvs,
                                         const std::vector<uint32_t>& indices) {
  std::vector<glm::dvec3> tan(positions.size(), glm::dvec3(0.0)),
      bit(positions.size(), glm::dvec3(0.0));
  // Without uvs (all zero) no triangle has a uv gradient.
  for (size_t t = 0; !uvs.empty() && t + 2 < indices.size(); t += 3) {
    const uint32_t i[3] = {indices[t], indices[t + 1], indices[t + 2]};
    const glm::dvec3 e1 = glm::dvec3(positions[i[1]]) - glm::dvec3(positions[i[0]]);
    const glm::dvec3 e2 = glm::dvec3(positions[i[2]]) - glm::dvec3(positions[i[0]]);
    const glm::dvec2 d1 = glm::dvec2(uvs[i[1]]) - glm::dvec2(uvs[i[0]]);
    const glm::dvec2 d2 = glm::dvec2(uvs[i[2]]) - glm::dvec2(uvs[i[0]]);
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (det == 0.0 || !std::isfinite(1.0 / det)) continue;  // no uv gradient on this triangle
    // Area-weighted: unnormalised, so larger triangles count more.
    const glm::dvec3 s = (e1 * d2.y - e2 * d1.y) / det;
    const glm::dvec3 b = (e2 * d1.x - e1 * d2.x) / det;
    for (uint32_t k : i) {
      tan[k] += s;
      bit[k] += b;
    }
  }
  std::vector<glm::vec4> out(positions.size());
  for (size_t v = 0; v < positions.size(); ++v) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(normals[v]));
    glm::dvec3 t = tan[v] - n * glm::dot(n, tan[v]);  // Gram-Schmidt
    if (glm::dot(t, t) < 1e-24) {
      // Any unit vector orthogonal to n: cross with the axis least aligned with it.
      const glm::dvec3 axis = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
      t = glm::cross(n, axis);
    }
    t = glm::normalize(t);
    const double w = glm::dot(glm::cross(n, t), bit[v]) < 0.0 ? -1.0 : 1.0;
    out[v] = glm::vec4(glm::vec3(t), float(w));
  }
  return out;
}

}  // namespace tessera
