// glTF metallic-roughness materials, their textures, samplers and texture transforms.

#include <cmath>
#include <memory>

#include <stb/stb_image.h>

#include "core/check.h"
#include "core/gltf_detail.h"
#include "core/parallel.h"
#include "core/radiance_check.h"
#include "core/texture.h"

namespace tessera::gltf {
namespace {

using nlohmann::json;

// glTF 2.0 sampler wrap modes (section 5.26, the OpenGL enum values).
constexpr int kRepeat = 10497;
constexpr int kClampToEdge = 33071;
constexpr int kMirroredRepeat = 33648;

// The TextureWrap of `samplers[sampler].key` ("wrapS" or "wrapT"); fails on any other value.
TextureWrap wrap_mode(const Context& ctx, const json& sampler, const char* key,
                      const std::string& where) {
  const json& v = sampler.contains(key) ? sampler[key] : json(kRepeat);
  if (v == kRepeat) return TextureWrap::repeat;
  if (v == kClampToEdge) return TextureWrap::clamp_to_edge;
  if (v == kMirroredRepeat) return TextureWrap::mirrored_repeat;
  ctx.fail(where + "." + key, "is " + v.dump() +
                                  "; glTF allows 10497 (REPEAT), 33071 (CLAMP_TO_EDGE) and "
                                  "33648 (MIRRORED_REPEAT)");
}

// Decodes images[index] (from its file, data uri or buffer view) to RGBA8, refusing sides over
// options.max_texture_side before decoding.
Texture decode_image(const Context& ctx, const tinygltf::Model& model, int index) {
  const tinygltf::Image& image = model.images[index];
  const std::string where = at("images", index);
  const unsigned char* bytes = image.image.data();
  size_t size = image.image.size();
  if (image.bufferView >= 0) {
    std::tie(bytes, size) = buffer_view_bytes(ctx, model, image.bufferView, where + ".bufferView");
  }
  if (size == 0) ctx.fail(where, "has no image data (its file could not be read)");
  if (size > uint64_t(INT32_MAX)) ctx.fail(where, "is over 2 GiB, more than stb_image reads");
  const uint32_t largest = ctx.options.max_texture_side;
  const auto too_large = [&](glm::uvec2 side) {
    ctx.fail(where, "is " + std::to_string(side.x) + "x" + std::to_string(side.y) +
                        ", over the largest texture side of " + std::to_string(largest));
  };
  if (const auto side = oversized_image({bytes, size}, largest)) too_large(*side);
  // stb_image decodes a Radiance file whatever its mime type, and hangs on a corrupt one.
  if (const std::string fault = radiance_fault(bytes, size); !fault.empty()) ctx.fail(where, fault);
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> data(
      stbi_load_from_memory(bytes, int(size), &w, &h, &channels, 4), stbi_image_free);
  if (!data) {
    // Name the image file where there is one: the path alone says only which image it is.
    const bool file = !image.uri.empty() && image.uri.rfind("data:", 0) != 0;
    ctx.fail(where, (file ? "'" + image.uri + "' " : std::string()) +
                        "cannot be decoded: " + image_failure_reason());
  }
  if (uint32_t(w) > largest || uint32_t(h) > largest) too_large(glm::uvec2(w, h));
  Texture t;
  t.width = uint32_t(w);
  t.height = uint32_t(h);
  const auto* texels = reinterpret_cast<const glm::u8vec4*>(data.get());
  t.texels.assign(texels, texels + size_t(w) * h);
  return t;
}

const Texture& decoded_image(const Context& ctx, const tinygltf::Model& model, int index,
                             MaterialTable& table) {
  if (auto it = table.images.find(index); it != table.images.end()) return it->second;
  return table.images.emplace(index, decode_image(ctx, model, index)).first->second;
}

// What textures[index] refers to: an image and its sampler's wrap modes.
struct TextureSource {
  int image = 0;
  TextureWrap wrap_u = TextureWrap::repeat, wrap_v = TextureWrap::repeat;
};

// textures[index], referenced from `where`, after checking the texture and its sampler.
TextureSource texture_source(const Context& ctx, const json& doc, const tinygltf::Model& model,
                             int index, const std::string& where) {
  const json& textures = member(doc, "textures");
  check_index(ctx, where + ".index", index, textures.size(), "textures");
  const json& texture = textures[index];
  const std::string name = at("textures", index);
  if (!texture.contains("source")) {
    ctx.fail(name,
             "has no source image (images of extensions such as KHR_texture_basisu or "
             "EXT_texture_webp are not supported)");
  }
  TextureSource source;
  source.image = texture["source"].get<int>();
  check_index(ctx, name + ".source", source.image, model.images.size(), "images");
  if (texture.contains("sampler")) {
    const int sampler = texture["sampler"].get<int>();
    const json& samplers = member(doc, "samplers");
    check_index(ctx, name + ".sampler", sampler, samplers.size(), "samplers");
    source.wrap_u = wrap_mode(ctx, samplers[sampler], "wrapS", at("samplers", sampler));
    source.wrap_v = wrap_mode(ctx, samplers[sampler], "wrapT", at("samplers", sampler));
  }
  return source;
}

// Scene::textures index for textures[index] read as colour (srgb) or data. An occlusion map
// with strength s != 1 gets its own copy with R' = 1 + s (R - 1), glTF's blend, because
// Tessera multiplies by R.
uint32_t texture_index(const Context& ctx, const json& doc, const tinygltf::Model& model, int index,
                       const std::string& where, bool srgb, float strength, MaterialTable& table,
                       Scene& scene) {
  const TextureSource source = texture_source(ctx, doc, model, index, where);
  const auto key =
      std::make_tuple(source.image, srgb, strength, int(source.wrap_u) | int(source.wrap_v) << 2);
  if (auto it = table.textures.find(key); it != table.textures.end()) return it->second;
  Texture t = decoded_image(ctx, model, source.image, table);
  t.srgb = srgb;
  t.wrap_u = source.wrap_u;
  t.wrap_v = source.wrap_v;
  if (strength != 1.0f) {
    for (glm::u8vec4& texel : t.texels) {
      texel.r = uint8_t(std::lround(255.0 * (1.0 + strength * (texel.r / 255.0 - 1.0))));
    }
  }
  scene.textures.push_back(std::move(t));
  return table.textures[key] = uint32_t(scene.textures.size() - 1);
}

// float_number of `object`.`key`, at `where`.`key`; `fallback` where absent.
float factor(const Context& ctx, const json& object, const char* key, float fallback,
             const std::string& where, double lo = -HUGE_VAL, double hi = HUGE_VAL) {
  const auto it = object.find(key);
  return it == object.end() ? fallback : float_number(ctx, *it, where + "." + key, lo, hi);
}

// The colour factor `object`.`key` of `components` numbers (the schema has checked how many),
// each in [0, 1]; `fallback` where absent.
glm::vec4 colour_factor(const Context& ctx, const json& object, const char* key, int components,
                        glm::vec4 fallback, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) return fallback;
  for (int k = 0; k < components; ++k) {
    fallback[k] = float_number(ctx, (*it)[size_t(k)],
                               where + "." + key + "[" + std::to_string(k) + "]", 0.0, 1.0);
  }
  return fallback;
}

// KHR_texture_transform as a 3x3 uv matrix: translation * rotation * scale, as the extension
// specifies (rotation counter-clockwise in uv space, about the origin). Its texCoord, if
// given, overrides the textureInfo's. Offset and scale must fit a float, as the matrix's terms
// do then (the rotation is taken in double).
glm::mat3 uv_transform(const Context& ctx, const json& info, const std::string& where,
                       int& tex_coord) {
  const json* ext = nullptr;
  if (info.contains("extensions") && info["extensions"].contains("KHR_texture_transform")) {
    ext = &info["extensions"]["KHR_texture_transform"];
  }
  if (!ext) return glm::mat3(1.0f);
  const std::string ext_where = where + ".extensions.KHR_texture_transform";
  tex_coord = ext->value("texCoord", tex_coord);
  glm::dvec2 offset(0.0), scale(1.0);
  for (auto [key, out] : {std::pair{"offset", &offset}, {"scale", &scale}}) {
    if (!ext->contains(key)) continue;
    for (int k = 0; k < 2; ++k) {
      (*out)[k] =
          float_number(ctx, (*ext)[key][k], ext_where + "." + key + "[" + std::to_string(k) + "]");
    }
  }
  const double rotation = ext->value("rotation", 0.0);
  const double c = std::cos(rotation), s = std::sin(rotation);
  const glm::dmat3 t(1, 0, 0, 0, 1, 0, offset[0], offset[1], 1);  // columns
  const glm::dmat3 r(c, -s, 0, s, c, 0, 0, 0, 1);
  const glm::dmat3 sc(scale[0], 0, 0, 0, scale[1], 0, 0, 0, 1);
  return glm::mat3(t * r * sc);
}

}  // namespace

void decode_images(const Context& ctx, const tinygltf::Model& model, MaterialTable& table) {
  std::vector<int> sources;
  for (const tinygltf::Texture& t : model.textures) {
    if (t.source >= 0 && size_t(t.source) < model.images.size()) sources.push_back(t.source);
  }
  std::sort(sources.begin(), sources.end());
  sources.erase(std::unique(sources.begin(), sources.end()), sources.end());
  std::vector<std::optional<Texture>> decoded(sources.size());
  parallel_for(sources.size(), [&](size_t i) {
    try {
      decoded[i] = decode_image(ctx, model, sources[i]);
    } catch (const Error&) {
      // Left out: decoded_image fails the same way where a material uses the image.
    }
  });
  for (size_t i = 0; i < sources.size(); ++i) {
    if (decoded[i]) table.images.emplace(sources[i], std::move(*decoded[i]));
  }
}

uint32_t material_index(const Context& ctx, const json& doc, const tinygltf::Model& model,
                        int index, MaterialTable& table, Scene& scene) {
  if (auto it = table.materials.find(index); it != table.materials.end()) return it->second;
  const json& materials = member(doc, "materials");
  Material mat;
  PrimitiveOptions uv;
  if (index < 0) {
    // The glTF default material (specification 3.9.6): white, fully metallic and rough.
    mat.base_color = glm::vec3(1.0f);
    mat.metallic = 1.0f;
    mat.roughness = 1.0f;
  } else {
    const json& m = materials[index];
    const std::string where = at("materials", index);
    const json& pbr = member_object(m, "pbrMetallicRoughness");
    const std::string pbr_where = where + ".pbrMetallicRoughness";
    mat.base_color = colour_factor(ctx, pbr, "baseColorFactor", 4, glm::vec4(1.0f), pbr_where);
    mat.metallic = factor(ctx, pbr, "metallicFactor", 1.0f, pbr_where, 0.0, 1.0);
    mat.roughness = factor(ctx, pbr, "roughnessFactor", 1.0f, pbr_where, 0.0, 1.0);
    float strength = 1.0f;
    if (m.contains("extensions") && m["extensions"].contains("KHR_materials_emissive_strength")) {
      strength = factor(ctx, m["extensions"]["KHR_materials_emissive_strength"], "emissiveStrength",
                        1.0f, where + ".extensions.KHR_materials_emissive_strength", 0.0);
    }
    mat.emissive =
        glm::vec3(colour_factor(ctx, m, "emissiveFactor", 3, glm::vec4(0.0f), where)) * strength;

    const std::string alpha = m.value("alphaMode", "OPAQUE");
    if (alpha == "MASK") {
      ctx.fail(where + ".alphaMode", "is MASK (alpha testing), which Tessera does not support");
    } else if (alpha == "BLEND") {
      ctx.warn(where + ".alphaMode", "is BLEND; rendered opaque (Tessera has no transparency)");
    } else if (alpha != "OPAQUE") {
      ctx.fail(where + ".alphaMode", "is '" + alpha + "', not OPAQUE, MASK or BLEND");
    }
    mat.double_sided = m.value("doubleSided", false);

    // Each texture, its uv set (TEXCOORD_0 or _1) and its uv transform.
    struct Slot {
      const json* info;
      std::string where;
      uint32_t bit;  // TS_MAP_*
      int tex_coord = 0;
      glm::mat3 transform{1.0f};
    };
    std::vector<Slot> slots;
    auto slot = [&](const json& parent, const char* key, const std::string& parent_where,
                    uint32_t bit) {
      if (!parent.contains(key)) return -1;
      Slot s{&parent[key], parent_where + "." + key, bit};
      if (!s.info->contains("index")) ctx.fail(s.where + ".index", "is missing");
      s.tex_coord = s.info->value("texCoord", 0);
      s.transform = uv_transform(ctx, *s.info, s.where, s.tex_coord);
      if (s.tex_coord > 1) {
        ctx.fail(s.where + ".texCoord",
                 "is " + std::to_string(s.tex_coord) +
                     "; Tessera reads two uv sets, TEXCOORD_0 and TEXCOORD_1 (texCoord 0 or 1)");
      }
      if (s.tex_coord == 1) mat.uv1_maps |= bit;
      slots.push_back(s);
      return (*s.info)["index"].get<int>();
    };
    const int base_map = slot(pbr, "baseColorTexture", pbr_where, TS_MAP_BASE_COLOR);
    if (base_map >= 0) {
      mat.base_color_map =
          texture_index(ctx, doc, model, base_map, slots.back().where, true, 1.0f, table, scene);
    }
    const int mr_map = slot(pbr, "metallicRoughnessTexture", pbr_where, TS_MAP_METALLIC_ROUGHNESS);
    if (mr_map >= 0) {
      mat.metallic_roughness_map =
          texture_index(ctx, doc, model, mr_map, slots.back().where, false, 1.0f, table, scene);
    }
    const int normal_map = slot(m, "normalTexture", where, TS_MAP_NORMAL);
    if (normal_map >= 0) {
      mat.normal_map =
          texture_index(ctx, doc, model, normal_map, slots.back().where, false, 1.0f, table, scene);
      mat.normal_scale = factor(ctx, m["normalTexture"], "scale", 1.0f, where + ".normalTexture");
    }
    const int occlusion_map = slot(m, "occlusionTexture", where, TS_MAP_OCCLUSION);
    if (occlusion_map >= 0) {
      const float s = factor(ctx, m["occlusionTexture"], "strength", 1.0f,
                             where + ".occlusionTexture", 0.0, 1.0);
      mat.occlusion_map =
          texture_index(ctx, doc, model, occlusion_map, slots.back().where, false, s, table, scene);
    }
    const int emissive_map = slot(m, "emissiveTexture", where, TS_MAP_EMISSIVE);
    if (emissive_map >= 0) {
      mat.emissive_map = texture_index(ctx, doc, model, emissive_map, slots.back().where, true,
                                       1.0f, table, scene);
    }

    // The transform is applied to the uvs of a set when they are read, so the textures of one
    // set share the transform of the first of them.
    uv.uv1 = mat.uv1_maps != 0u;
    uv.tangents = mat.normal_map != kNoTexture;
    if (uv.tangents && (mat.uv1_maps & TS_MAP_NORMAL) != 0u) uv.tangent_set = 1;
    uv.material_where = where;
    for (int set = 0; set < 2; ++set) {
      const Slot* first = nullptr;
      for (const Slot& s : slots) {
        if (s.tex_coord != set) continue;
        if (!first) {
          first = &s;
          uv.uv_transform[set] = s.transform;
        } else if (s.transform != first->transform) {
          ctx.warn(where, "its textures on TEXCOORD_" + std::to_string(set) +
                              " have different KHR_texture_transform transforms; all use the " +
                              "one of " + first->where);
          break;
        }
      }
    }
  }
  scene.materials.push_back(mat);
  table.uv_options[index] = uv;
  return table.materials[index] = uint32_t(scene.materials.size() - 1);
}

}  // namespace tessera::gltf
