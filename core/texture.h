#pragma once
// Texture maps: RGBA8 images as a material reads them, their mip chains, and the filtering the
// compute path's shading pass does (shaders/texture.glsl), written here in double for the
// reference renderer. Both sides filter by hand, from the same mip chain, with the same level
// of detail, so the reference checks the GPU's arithmetic and not a driver's sampler.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tessera {

/// One texture map as loaded: RGBA8, rows top to bottom. `srgb` marks colour data (base
/// colour), decoded to linear before filtering; data maps (metallic-roughness, normal,
/// occlusion) are linear.
/// How lookups outside [0, 1] wrap, per axis: OpenGL's (and glTF 2.0's) REPEAT, CLAMP_TO_EDGE
/// and MIRRORED_REPEAT (OpenGL 4.6 specification, section 8.14.2).
enum class TextureWrap : uint8_t { repeat, clamp_to_edge, mirrored_repeat };

struct Texture {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<glm::u8vec4> texels;  // width * height
  bool srgb = false;
  TextureWrap wrap_u = TextureWrap::repeat;  // along rows
  TextureWrap wrap_v = TextureWrap::repeat;  // along columns
  bool operator==(const Texture&) const = default;
};

/// Largest texture side: the GPU descriptor stores at most TS_MAX_TEXTURE_LEVELS levels.
constexpr uint32_t kMaxTextureSide = 16384;

/// Reads an image file with stb_image (PNG, JPEG, TGA, BMP, PSD, GIF, HDR as 8-bit, PIC, PNM)
/// as RGBA8. Throws Error naming the path and stb_image's reason if it cannot be read, for
/// what is not a regular file (map_file), and for sides above kMaxTextureSide (oversized_image
/// first).
Texture load_texture(const std::string& path, bool srgb);

/// The width and height in the header of the encoded image `bytes` (any format load_texture
/// reads), read without decoding it, where either is over `max_side`; nullopt where both are
/// within it or no header is recognized (decoding then says what is wrong). The loaders of
/// textures (scene files, glTF, MTL) ask this before decoding one: decoding a 17000 x 17000 PNG
/// took 7 s and 1.4 GB before it was refused (a fresh user's trial).
std::optional<glm::uvec2> oversized_image(std::span<const unsigned char> bytes, uint32_t max_side);

/// stb_image's reason for its last failure (stbi_failure_reason), in words where its own is a
/// tag: "outofdata" is "the data ends early (a truncated file?)". Others are returned as they are.
std::string image_failure_reason();

/// Linear RGBA of each mip level, level 0 first. Level l is max(1, width >> l) by
/// max(1, height >> l); each texel of level l + 1 is the mean of the (up to) 2 x 2 texels of
/// level l it covers, averaged in linear space (sRGB texels decoded first).
struct MipChain {
  struct Level {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec4> texels;
  };
  std::vector<Level> levels;
  TextureWrap wrap_u = TextureWrap::repeat, wrap_v = TextureWrap::repeat;  // the texture's
};

/// Builds the full mip chain of `texture` (down to 1 x 1). Precondition: texture is non-empty
/// with width * height texels (validate_scene checks it).
MipChain build_mip_chain(const Texture& texture);

/// IEC 61966-2-1 sRGB decoding of one 8-bit value, in [0, 1].
double srgb_to_linear(uint8_t value);

/// Filtered lookup at `uv` (wrapping by the chain's modes; v = 0 is the top row) with the
/// screen-space uv derivatives duv_dx, duv_dy of one pixel step. Trilinear at lod log2 of the
/// longer footprint axis in level-0 texels; with max_anisotropy > 1, n = min(ceil(major / minor),
/// max_anisotropy) trilinear probes spread along the major axis at lod log2(major / n). Non-finite
/// derivatives (a triangle seen edge-on) select the coarsest level.
glm::dvec4 sample_texture(const MipChain& chain, glm::dvec2 uv, glm::dvec2 duv_dx,
                          glm::dvec2 duv_dy, uint32_t max_anisotropy);

/// Tangents for normal mapping (Lengyel 2001): per vertex, the uv-aligned tangent of the
/// adjacent triangles summed, made orthogonal to the normal, and w = +-1 the handedness of the
/// (tangent, bitangent) frame. Vertices whose triangles have no usable uv gradient get an
/// arbitrary unit vector orthogonal to the normal. Fills mesh-sized output.
std::vector<glm::vec4> generate_tangents(const std::vector<glm::vec3>& positions,
                                         const std::vector<glm::vec3>& normals,
                                         const std::vector<glm::vec2>& uvs,
                                         const std::vector<uint32_t>& indices);

}  // namespace tessera
