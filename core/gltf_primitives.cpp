// Mesh primitives into Tessera meshes: topology, attributes, generated normals and tangents.

#include <algorithm>
#include <bit>
#include <cmath>
#include <iterator>
#include <type_traits>
#include <vector>

#include "core/check.h"
#include "core/gltf_detail.h"
#include "core/memory_pages.h"
#include "core/texture.h"

namespace tessera::gltf {
namespace {

const char* mode_name(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return "POINTS";
    case TINYGLTF_MODE_LINE:
      return "LINES";
    case TINYGLTF_MODE_LINE_LOOP:
      return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP:
      return "LINE_STRIP";
    default:
      return "an unknown mode";
  }
}

// Fails naming the element if any value of an attribute is NaN or infinite.
void require_finite(const Context& ctx, const AccessorValues& v, const std::string& where) {
  if (!v.uints.empty()) return;
  visit(v, [&](auto values) {
    const size_t n = v.count * size_t(v.components);
    // A pass without an early exit, which the compiler vectorizes; the element is looked for
    // only when there is one.
    bool finite = true;
    for (size_t i = 0; i < n; ++i) finite &= std::isfinite(values[i]);
    if (finite) return;
    for (size_t i = 0; i < n; ++i) {
      if (!std::isfinite(values[i])) {
        ctx.fail(where, "element " + std::to_string(i / v.components) +
                            " has a NaN or infinite component");
      }
    }
  });
}

// The specification's name of componentType `type`, one read_accessor has accepted (5120 to
// 5126 but 5124).
const char* component_type_name(int type) {
  static const char* const kNames[] = {"BYTE", "UNSIGNED_BYTE", "SHORT", "UNSIGNED_SHORT",
                                       "INT",  "UNSIGNED_INT",  "FLOAT"};
  return kNames[type - TINYGLTF_COMPONENT_TYPE_BYTE];
}

// The component types an attribute may have (glTF 2.0 3.7.2.1, the table of attribute
// semantics; KHR_mesh_quantization's table), one bit per componentType and normalized flag.
constexpr uint32_t type_bit(int type, bool normalized) {
  return 1u << (2 * (type - TINYGLTF_COMPONENT_TYPE_BYTE) + int(normalized));
}
constexpr uint32_t kNormalizedSmall =
    type_bit(TINYGLTF_COMPONENT_TYPE_BYTE, true) | type_bit(TINYGLTF_COMPONENT_TYPE_SHORT, true);
constexpr uint32_t kNormalizedUnsigned = type_bit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, true) |
                                         type_bit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, true);
constexpr uint32_t kSmallIntegers = kNormalizedSmall | kNormalizedUnsigned |
                                    type_bit(TINYGLTF_COMPONENT_TYPE_BYTE, false) |
                                    type_bit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, false) |
                                    type_bit(TINYGLTF_COMPONENT_TYPE_SHORT, false) |
                                    type_bit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, false);
struct AttributeTypes {
  std::string_view semantic;  // TEXCOORD stands for every TEXCOORD_n
  uint32_t core;              // besides FLOAT, which every one allows
  uint32_t quantized;         // with KHR_mesh_quantization, besides FLOAT
  const char* core_names;
  const char* quantized_names;
};
constexpr AttributeTypes kAttributeTypes[] = {
    {"POSITION", 0, kSmallIntegers, "FLOAT (5126)",
     "FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT"},
    {"NORMAL", 0, kNormalizedSmall, "FLOAT (5126)", "FLOAT or normalized BYTE or SHORT"},
    {"TANGENT", 0, kNormalizedSmall, "FLOAT (5126)", "FLOAT or normalized BYTE or SHORT"},
    {"TEXCOORD", kNormalizedUnsigned, kSmallIntegers,
     "FLOAT (5126), normalized UNSIGNED_BYTE (5121) or normalized UNSIGNED_SHORT (5123)",
     "FLOAT, BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT"},
};

// Fails unless accessor `a`, accessors[index], the `name` attribute (POSITION, NORMAL, TANGENT or
// TEXCOORD_n) at `where`, has a component type kAttributeTypes allows it. read_accessor reads
// any type, so without this a file that needs KHR_mesh_quantization but does not declare it was
// drawn, where viewers that follow the specification refuse it.
void check_attribute_type(const Context& ctx, const tinygltf::Accessor& a, int index,
                          const std::string& name, const std::string& where) {
  const int type = a.componentType;
  if (type == TINYGLTF_COMPONENT_TYPE_FLOAT) return;
  const AttributeTypes* rule = nullptr;
  for (const AttributeTypes& r : kAttributeTypes) {
    if (name.starts_with(r.semantic)) rule = &r;
  }
  TESSERA_CHECK(rule != nullptr);
  const uint32_t bit = type_bit(type, a.normalized);
  if ((rule->core & bit) != 0u) return;
  const std::string is = "is " + at("accessors", size_t(index)) + ", of componentType " +
                         std::to_string(type) + " (" + component_type_name(type) +
                         (a.normalized ? ", normalized" : "") + ")";
  if (!ctx.mesh_quantization) {
    ctx.fail(where, is + "; glTF 2.0 allows only " + rule->core_names + " for " + name +
                        " (3.7.2.1) unless the file lists KHR_mesh_quantization in "
                        "extensionsUsed, which it does not");
  }
  if ((rule->quantized & bit) == 0u) {
    ctx.fail(where,
             is + "; KHR_mesh_quantization allows " + rule->quantized_names + " for " + name);
  }
}

// The `name` attribute (POSITION, NORMAL, TANGENT or TEXCOORD_n), accessors[index] at `where`,
// of accessor type `type`: its component type is checked (check_attribute_type) before its bytes
// are read, where a type of another size than the file's views hold would be refused first as
// reads past the view.
AccessorValues read_attribute(const Context& ctx, const tinygltf::Model& model, int index,
                              const std::string& name, const std::string& where, int type) {
  check_attribute_type(ctx, checked_accessor(ctx, model, index, where, {type}), index, name, where);
  return read_accessor(ctx, model, index, where, {type});
}

// Element i of `values` read as three floats: an iterator over the vec3s of an accessor's flat
// values (any of visit's kinds), so that a vector is built from them in one pass that the
// compiler vectorizes (a zero-fill by resize and a scalar copy were a twentieth of the import).
template <typename Values>
struct Vec3Reader {
  using iterator_category = std::forward_iterator_tag;
  using value_type = glm::vec3;
  using difference_type = std::ptrdiff_t;
  using pointer = void;
  using reference = glm::vec3;
  Values values;
  size_t i;
  glm::vec3 operator*() const {
    return glm::vec3(float(values[3 * i]), float(values[3 * i + 1]), float(values[3 * i + 2]));
  }
  Vec3Reader& operator++() {
    ++i;
    return *this;
  }
  Vec3Reader operator++(int) {
    Vec3Reader before = *this;
    ++i;
    return before;
  }
  bool operator==(const Vec3Reader& o) const { return i == o.i; }
};

// Triangle list of a strip or fan, as the glTF 2.0 specification (3.7.2.1) orders them, so that
// every triangle keeps the strip's (or fan's) winding.
std::vector<uint32_t> triangulate(int mode, std::vector<uint32_t> v) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return v;
  std::vector<uint32_t> out;
  reserve_populated(out, v.size() > 2 ? 3 * (v.size() - 2) : 0);
  for (size_t i = 0; i + 2 < v.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      const size_t odd = i % 2;
      out.insert(out.end(), {v[i], v[i + 1 + odd], v[i + 2 - odd]});
    } else {
      out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
    }
  }
  return out;
}

// Triangle t's face normal times twice its area, in double (no overflow from float positions).
glm::dvec3 area_normal(const Mesh& mesh, size_t t) {
  const uint32_t* tri = &mesh.indices[3 * t];
  const glm::dvec3 a(mesh.positions[tri[0]]), b(mesh.positions[tri[1]]), c(mesh.positions[tri[2]]);
  return glm::cross(b - a, c - a);
}

// `n` made unit length, or +z where it has no direction: what it is the normal of (a
// degenerate triangle, a vertex only such triangles use) covers no pixel, so any unit normal
// will do; this one keeps NaN out.
glm::vec3 unit_or_z(const glm::dvec3& n) {
  const double length = glm::length(n);
  return length > 0.0 && std::isfinite(length) ? glm::vec3(n / length) : glm::vec3(0, 0, 1);
}

// Normals for the vertices whose given NORMAL is the zero vector (`flagged`), which has no
// direction: the area-weighted sum of the face normals of the triangles that use the vertex,
// as OBJ's import makes them for a smoothing group. A glTF mesh splits its vertices where it
// wants a hard edge, so at one (a box's corner) this is the face's own normal, and on a smooth
// surface the surface's.
void generate_flagged_normals(Mesh& mesh, const std::vector<bool>& flagged) {
  std::vector<glm::dvec3> sums(mesh.positions.size(), glm::dvec3(0.0));
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t* tri = &mesh.indices[3 * t];
    if (!flagged[tri[0]] && !flagged[tri[1]] && !flagged[tri[2]]) continue;
    const glm::dvec3 n = area_normal(mesh, t);
    for (int k = 0; k < 3; ++k) {
      if (flagged[tri[k]]) sums[tri[k]] += n;
    }
  }
  for (size_t i = 0; i < flagged.size(); ++i) {
    if (flagged[i]) mesh.normals[i] = unit_or_z(sums[i]);
  }
}

// Flat normals, as the specification requires when NORMAL is absent: every triangle gets its
// own three vertices carrying its face normal.
void make_flat(Mesh& mesh) {
  Mesh flat;
  const size_t corners = mesh.indices.size();
  reserve_populated(flat.indices, corners);
  reserve_populated(flat.positions, corners);
  reserve_populated(flat.normals, corners);
  if (!mesh.uvs.empty()) reserve_populated(flat.uvs, corners);
  if (!mesh.uvs1.empty()) reserve_populated(flat.uvs1, corners);
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t* tri = &mesh.indices[3 * t];
    const glm::vec3 normal = unit_or_z(area_normal(mesh, t));
    for (int k = 0; k < 3; ++k) {
      flat.indices.push_back(uint32_t(flat.positions.size()));
      flat.positions.push_back(mesh.positions[tri[k]]);
      flat.normals.push_back(normal);
      if (!mesh.uvs.empty()) flat.uvs.push_back(mesh.uvs[tri[k]]);
      if (!mesh.uvs1.empty()) flat.uvs1.push_back(mesh.uvs1[tri[k]]);
    }
  }
  mesh = std::move(flat);
}

}  // namespace

Mesh convert_primitive(const Context& ctx, const tinygltf::Model& model, int mesh_index,
                       int primitive_index, const PrimitiveOptions& options) {
  const tinygltf::Primitive& prim = model.meshes[mesh_index].primitives[primitive_index];
  const std::string where =
      at("meshes", mesh_index) + ".primitives[" + std::to_string(primitive_index) + "]";
  if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      prim.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    ctx.fail(where + ".mode", std::string("is ") + std::to_string(prim.mode) + " (" +
                                  mode_name(prim.mode) +
                                  "); Tessera renders only TRIANGLES (4), TRIANGLE_STRIP (5) "
                                  "and TRIANGLE_FAN (6)");
  }
  auto attribute = [&](const char* name) {
    auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  const std::string attributes = where + ".attributes.";
  if (attribute("POSITION") < 0) ctx.fail(attributes + "POSITION", "is missing");
  const AccessorValues positions = read_attribute(ctx, model, attribute("POSITION"), "POSITION",
                                                  attributes + "POSITION", TINYGLTF_TYPE_VEC3);
  const size_t n = positions.count;
  Mesh mesh;
  visit(positions, [&](auto values) {
    using Reader = Vec3Reader<decltype(values)>;
    reserve_populated(mesh.positions, n);
    mesh.positions.assign(Reader{values, 0}, Reader{values, n});
  });
  // Checked after the copy: a float is non-finite where its exponent bits are all ones, and only
  // where the value it was converted from is (accessor values fit in a float); require_finite
  // then names the element. Adding one to an all-ones exponent field carries into the sign bit,
  // which an OR over every value keeps: a reduction the compiler vectorizes with the baseline
  // x86-64's SSE2 (a bool one, with std::isfinite, it does not; a max needs SSE4.1's pmaxsd).
  constexpr uint32_t kExponent = 0x7f800000u, kExponentOne = 0x00800000u, kSign = 0x80000000u;
  uint32_t carries = 0;
  const float* stored = reinterpret_cast<const float*>(mesh.positions.data());
  for (size_t i = 0; i < 3 * n; ++i) {
    carries |= (std::bit_cast<uint32_t>(stored[i]) & kExponent) + kExponentOne;
  }
  const bool finite = (carries & kSign) == 0;
  if (!finite) require_finite(ctx, positions, attributes + "POSITION");
  if (positions.count > UINT32_MAX) {
    ctx.fail(attributes + "POSITION", "has more than 2^32 - 1 vertices");
  }
  // Every other attribute must match POSITION's count. `checked` false: the caller checks
  // finiteness in its own pass and calls require_finite only when that fails.
  auto read = [&](const std::string& name, int type, bool checked = true) {
    const std::string path = attributes + name;
    AccessorValues v = read_attribute(ctx, model, attribute(name.c_str()), name, path, type);
    if (checked || v.count != n) require_finite(ctx, v, path);  // a NaN is named first
    if (v.count != n) {
      ctx.fail(path,
               "has " + std::to_string(v.count) + " elements, POSITION has " + std::to_string(n));
    }
    return v;
  };

  // TEXCOORD_n through set n's texture transform. Where absent: set 0 empty (Mesh::uvs: all
  // zero, not stored), set 1 zeros (a material reads it).
  auto read_uvs = [&](int set) {
    std::vector<glm::vec2> out;
    const std::string name = "TEXCOORD_" + std::to_string(set);
    if (attribute(name.c_str()) < 0 && set == 0) return out;
    reserve_populated(out, n);
    out.resize(n);  // zeros (value-initialized), written by memset
    if (attribute(name.c_str()) < 0) return out;
    const AccessorValues uvs = read(name, TINYGLTF_TYPE_VEC2);
    if (options.uv_transform[set] == glm::mat3(1.0f)) {
      // The product below with the identity: each coordinate plus +0, which turns -0 into +0
      // as the matrix's zero terms do, in float (the same bits; a loop the compiler vectorizes).
      visit(uvs, [&](auto values) {
        float* uv = reinterpret_cast<float*>(out.data());
        for (size_t i = 0; i < 2 * n; ++i) uv[i] = float(values[i]) + 0.0f;
      });
      return out;
    }
    const glm::dmat3 transform(options.uv_transform[set]);
    visit(uvs, [&](auto values) {
      for (size_t i = 0; i < n; ++i) {
        out[i] = glm::vec2(transform * glm::dvec3(values[2 * i], values[2 * i + 1], 1.0));
      }
    });
    return out;
  };
  mesh.uvs = read_uvs(0);
  if (options.uv1) {
    if (attribute("TEXCOORD_1") < 0) {
      ctx.warn(attributes + "TEXCOORD_1", "is missing, but " + options.material_where +
                                              " has a texture with texCoord 1; read as (0, 0)");
    }
    mesh.uvs1 = read_uvs(1);
  }

  std::vector<uint32_t> vertices;
  if (prim.indices >= 0) {
    const std::string path = where + ".indices";
    // The component type before the bytes are read: FLOAT indices over a view sized for shorts
    // were refused as reads past the view.
    const int type =
        checked_accessor(ctx, model, prim.indices, path, {TINYGLTF_TYPE_SCALAR}).componentType;
    if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      ctx.fail(path, "has componentType " + std::to_string(type) +
                         ", must be an unsigned byte, short or int");
    }
    AccessorValues indices = read_accessor(ctx, model, prim.indices, path, {TINYGLTF_TYPE_SCALAR});
    visit(indices, [&](auto values) {
      // The largest index first, in a loop without an exit that the compiler vectorizes; the
      // element is looked for only when one is out of range.
      std::remove_cvref_t<decltype(values[0])> largest = 0;
      for (size_t i = 0; i < indices.count; ++i) largest = std::max(largest, values[i]);
      if (largest < n) return;
      for (size_t i = 0; i < indices.count; ++i) {
        if (values[i] >= n) {
          ctx.fail(path, "element " + std::to_string(i) + " is vertex " +
                             std::to_string(uint64_t(values[i])) + ", past the " +
                             std::to_string(n) + " vertices of POSITION");
        }
      }
    });
    if (!indices.uints.empty()) {
      vertices = std::move(indices.uints);
    } else {
      reserve_populated(vertices, indices.count);
      visit(indices, [&](auto values) {
        for (size_t i = 0; i < indices.count; ++i) vertices.push_back(uint32_t(values[i]));
      });
    }
  } else {
    vertices.resize(n);
    for (size_t i = 0; i < n; ++i) vertices[i] = uint32_t(i);
  }
  if (prim.mode == TINYGLTF_MODE_TRIANGLES && vertices.size() % 3 != 0) {
    ctx.fail(prim.indices >= 0 ? where + ".indices" : attributes + "POSITION",
             "has " + std::to_string(vertices.size()) +
                 " elements, not a multiple of 3 as TRIANGLES need");
  }
  mesh.indices = triangulate(prim.mode, std::move(vertices));

  if (attribute("NORMAL") < 0) {
    make_flat(mesh);
    // The specification says to ignore given tangents when normals are generated.
  } else {
    const AccessorValues normals = read("NORMAL", TINYGLTF_TYPE_VEC3, false);
    reserve_populated(mesh.normals, n);
    mesh.normals.resize(n);
    bool renormalized = false, finite_normals = true;
    size_t zero = n;  // the first zero normal
    // Renormalized in double (which decides the stored bits), checked for finiteness in the same
    // pass; the loop has no exit and writes through a pointer, so the compiler vectorizes it.
    visit(normals, [&](auto values) {
      float* out = reinterpret_cast<float*>(mesh.normals.data());
      const size_t count = n;  // locals, so that the compiler sees what the stores cannot change
      bool renormalized_ = false, finite_ = true;
      size_t zero_ = count;
      for (size_t i = 0; i < count; ++i) {
        const double x = values[3 * i], y = values[3 * i + 1], z = values[3 * i + 2];
        const double length = std::sqrt(x * x + y * y + z * z);
        finite_ &= std::isfinite(x) & std::isfinite(y) & std::isfinite(z);
        zero_ = !(length > 0.0) ? std::min(zero_, i) : zero_;
        // A zero normal is not renormalized but replaced (below), and warned about as such.
        renormalized_ |= (length > 0.0) & (std::abs(length - 1.0) > 1e-3);
        // One division, not three: x * (1 / length) is within an ulp of x / length in double,
        // so the two round to different floats only where a float rounding boundary falls in
        // that ulp (a chance of about 2^-29 a value): no stored normal of the 79 glTF files of
        // assimp-testmodels and tests/data changed.
        const double inverse = 1.0 / length;
        out[3 * i] = float(x * inverse);
        out[3 * i + 1] = float(y * inverse);
        out[3 * i + 2] = float(z * inverse);
      }
      renormalized = renormalized_;
      finite_normals = finite_;
      zero = zero_;
    });
    // A NaN or infinite normal is an error, as every non-finite number of a model is (an OBJ's
    // `vn` too): it is damage, not a direction left out. A zero one is what an exporter writes
    // for a vertex it found no direction for (a degenerate face), which OBJ's import fills in
    // with a warning: the same here, for the vertices that have one.
    if (!finite_normals) require_finite(ctx, normals, attributes + "NORMAL");
    if (zero != n) {
      std::vector<bool> flagged(n, false);
      size_t count = 0;
      visit(normals, [&](auto values) {
        for (size_t i = zero; i < n; ++i) {
          const bool z = values[3 * i] == 0 && values[3 * i + 1] == 0 && values[3 * i + 2] == 0;
          flagged[i] = z;
          count += z;
        }
      });
      generate_flagged_normals(mesh, flagged);
      ctx.warn(attributes + "NORMAL",
               "element " + std::to_string(zero) + " is the zero vector, which has no direction (" +
                   std::to_string(count) + (count == 1 ? " such element" : " such elements") +
                   "); " +
                   (count == 1 ? "its vertex gets a normal" : "their vertices get normals") +
                   " generated from the triangles that use " + (count == 1 ? "it" : "them"));
    }
    if (renormalized) {
      ctx.warn(attributes + "NORMAL", "has normals that are not unit length; normalized");
    }
    if (attribute("TANGENT") >= 0) {
      const AccessorValues tangents = read("TANGENT", TINYGLTF_TYPE_VEC4);
      mesh.tangents.resize(n);
      visit(tangents, [&](auto values) {
        for (size_t i = 0; i < n; ++i) {
          const glm::dvec3 t(values[4 * i], values[4 * i + 1], values[4 * i + 2]);
          const double w = values[4 * i + 3];
          // Tessera's convention is glTF's: bitangent = w * cross(normal, tangent).
          if (!(glm::length(t) > 0.0)) {
            ctx.fail(attributes + "TANGENT",
                     "element " + std::to_string(i) + " is the zero vector");
          }
          mesh.tangents[i] = glm::vec4(glm::normalize(t), (w < 0.0 ? -1.0f : 1.0f));
        }
      });
    }
  }
  // Generated tangents are Lengyel's per-vertex sums (generate_tangents), not MikkTSpace: they
  // agree on smooth, well-parametrized meshes, but a normal map baked against MikkTSpace can
  // show small shading seams where the two frames differ (split uv islands, sharp edges).
  if (mesh.tangents.empty() && options.tangents) {
    mesh.tangents =
        generate_tangents(mesh.positions, mesh.normals,
                          options.tangent_set == 1 ? mesh.uvs1 : mesh.uvs, mesh.indices);
  }
  for (const char* ignored : {"COLOR_0", "JOINTS_0", "WEIGHTS_0"}) {
    if (attribute(ignored) >= 0) {
      ctx.warn(attributes + ignored, "is ignored (no vertex colours or skinning in Tessera)");
    }
  }
  if (!prim.targets.empty()) ctx.warn(where + ".targets", "morph targets are ignored");
  return mesh;
}

}  // namespace tessera::gltf
