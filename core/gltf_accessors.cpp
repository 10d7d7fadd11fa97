// Accessors and primitives: every byte read from a buffer is range-checked first, with
// overflow-checked size arithmetic, so a hostile file gets an Error and never a wild read.

#include <cmath>
#include <cstring>
#include <type_traits>

#include "core/check.h"
#include "core/gltf_detail.h"
#include "core/memory_pages.h"

namespace tessera::gltf {
namespace {

// a * b + c, or fails naming `where` if it does not fit in 64 bits.
uint64_t checked_span(const Context& ctx, const std::string& where, uint64_t a, uint64_t b,
                      uint64_t c) {
  uint64_t product = 0, sum = 0;
  if (__builtin_mul_overflow(a, b, &product) || __builtin_add_overflow(product, c, &sum)) {
    ctx.fail(where, "the size arithmetic overflows (" + std::to_string(a) + " x " +
                        std::to_string(b) + " + " + std::to_string(c) + ")");
  }
  return sum;
}

size_t component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "an unknown type";
  }
}

template <typename T>
T load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// One component; normalized integers as the glTF 2.0 specification (3.11) maps them.
template <typename T>
double read_component(const unsigned char* p, bool normalized) {
  const double v = load<T>(p);
  if constexpr (std::is_same_v<T, int8_t>) return normalized ? std::max(v / 127.0, -1.0) : v;
  if constexpr (std::is_same_v<T, uint8_t>) return normalized ? v / 255.0 : v;
  if constexpr (std::is_same_v<T, int16_t>) return normalized ? std::max(v / 32767.0, -1.0) : v;
  if constexpr (std::is_same_v<T, uint16_t>) return normalized ? v / 65535.0 : v;
  return v;
}

// `count` elements of `components` components of type T, `stride` bytes apart, into `out`:
// one loop per component type (a switch per component was an eighth of the import).
template <typename T>
void read_typed(const unsigned char* bytes, uint64_t count, int components, uint64_t stride,
                bool normalized, double* out) {
  for (uint64_t i = 0; i < count; ++i) {
    const unsigned char* e = bytes + i * stride;
    for (int c = 0; c < components; ++c) {
      *out++ = read_component<T>(e + c * sizeof(T), normalized);
    }
  }
}

// `count` elements of `components` components of type In, `stride` bytes apart, into `out`
// as Out (which holds every In value exactly): one copy when they are tightly packed.
template <typename In, typename Out>
void copy_typed(const unsigned char* bytes, uint64_t count, int components, uint64_t stride,
                Out* out) {
  static_assert(std::is_same_v<In, Out> || sizeof(In) < sizeof(Out));
  if (stride == sizeof(In) * components) {
    if constexpr (std::is_same_v<In, Out>) {
      std::memcpy(out, bytes, count * stride);
    } else {
      // One flat loop, which the compiler vectorizes (16-bit indices, mostly).
      for (uint64_t i = 0; i < count * components; ++i)
        out[i] = Out(load<In>(bytes + i * sizeof(In)));
    }
    return;
  }
  for (uint64_t i = 0; i < count; ++i) {
    const unsigned char* e = bytes + i * stride;
    for (int c = 0; c < components; ++c) *out++ = Out(load<In>(e + c * sizeof(In)));
  }
}

constexpr uint64_t kViewStride = ~uint64_t(0);

// Where `count` elements of `components` components each lie in bufferViews[view] at `offset`,
// `stride` bytes apart (0: tightly packed; kViewStride: the view's byteStride), after checking
// that they do: the first element's bytes (null when count is 0) and the stride.
std::pair<const unsigned char*, uint64_t> element_bytes(const Context& ctx,
                                                        const tinygltf::Model& model, int view,
                                                        uint64_t offset, uint64_t count,
                                                        int component_type, int components,
                                                        uint64_t stride, const std::string& where) {
  const auto [bytes, length] = buffer_view_bytes(ctx, model, view, where + ".bufferView");
  const uint64_t element = component_size(component_type) * uint64_t(components);
  if (stride == kViewStride) stride = model.bufferViews[view].byteStride;
  if (stride == 0) stride = element;
  if (stride < element) {
    ctx.fail(at("bufferViews", view) + ".byteStride",
             "is " + std::to_string(stride) + ", less than the " + std::to_string(element) +
                 "-byte elements of " + where);
  }
  if (count == 0) return {nullptr, stride};
  const uint64_t end =
      checked_span(ctx, where, stride, count - 1, checked_span(ctx, where, 1, offset, element));
  if (offset > length || end > length) {
    ctx.fail(where, std::to_string(count) + " elements of " + std::to_string(element) + " bytes, " +
                        std::to_string(stride) + " apart from byte " + std::to_string(offset) +
                        ", end at byte " + std::to_string(end) + ", past the " +
                        std::to_string(length) + " bytes of " + at("bufferViews", view));
  }
  if (ctx.read_pages) ctx.reads.emplace_back(bytes + offset, size_t(end - offset));
  return {bytes + offset, stride};
}

// Reads `count` elements of `components` components each from bufferViews[view] at `offset`,
// `stride` bytes apart (as element_bytes), appending them to `out` as doubles.
void read_elements(const Context& ctx, const tinygltf::Model& model, int view, uint64_t offset,
                   uint64_t count, int component_type, int components, bool normalized,
                   uint64_t stride, const std::string& where, std::vector<double>& out) {
  const auto [start, step] =
      element_bytes(ctx, model, view, offset, count, component_type, components, stride, where);
  if (count == 0) return;
  const size_t first = out.size();
  out.resize(first + count * components);
  double* const values = out.data() + first;
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return read_typed<int8_t>(start, count, components, step, normalized, values);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return read_typed<uint8_t>(start, count, components, step, normalized, values);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return read_typed<int16_t>(start, count, components, step, normalized, values);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return read_typed<uint16_t>(start, count, components, step, normalized, values);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return read_typed<uint32_t>(start, count, components, step, normalized, values);
    default:
      return read_typed<float>(start, count, components, step, normalized, values);
  }
}

// The elements of a float or plain unsigned integer accessor over a buffer view into r.floats
// or r.uints, with read_elements' checks. Returns false, having read nothing, for the others.
bool read_stored_type(const Context& ctx, const tinygltf::Model& model, const tinygltf::Accessor& a,
                      const std::string& where, AccessorValues& r) {
  const int type = a.componentType;
  const bool is_float = type == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool is_uint = !a.normalized && (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                         type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                                         type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  if (a.bufferView < 0 || a.sparse.isSparse || !(is_float || is_uint)) return false;
  const auto [start, stride] = element_bytes(ctx, model, a.bufferView, a.byteOffset, a.count, type,
                                             r.components, kViewStride, where);
  if (a.count == 0) return true;
  const size_t n = size_t(a.count) * r.components;
  if (is_float && stride == sizeof(float) * r.components) {
    r.packed = start;  // read in place, not copied into fresh memory
  } else if (is_float) {
    r.floats.resize(n);
    copy_typed<float>(start, a.count, r.components, stride, r.floats.data());
  } else {
    reserve_populated(r.uints, n);
    r.uints.resize(n);
    uint32_t* out = r.uints.data();
    if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
      copy_typed<uint8_t>(start, a.count, r.components, stride, out);
    } else if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
      copy_typed<uint16_t>(start, a.count, r.components, stride, out);
    } else {
      copy_typed<uint32_t>(start, a.count, r.components, stride, out);
    }
  }
  return true;
}

}  // namespace

std::pair<const unsigned char*, size_t> buffer_view_bytes(const Context& ctx,
                                                          const tinygltf::Model& model, int index,
                                                          const std::string& where) {
  check_index(ctx, where, index, model.bufferViews.size(), "bufferViews");
  const tinygltf::BufferView& view = model.bufferViews[index];
  const std::string name = at("bufferViews", index);
  check_index(ctx, name + ".buffer", view.buffer, model.buffers.size(), "buffers");
  const std::span<const unsigned char> data = view.buffer == 0 && !ctx.glb_buffer.empty()
                                                  ? ctx.glb_buffer
                                                  : std::span(model.buffers[view.buffer].data);
  const uint64_t end = checked_span(ctx, name, 1, view.byteOffset, view.byteLength);
  if (end > data.size()) {
    ctx.fail(name, "bytes " + std::to_string(view.byteOffset) + ".." + std::to_string(end) +
                       " are past the end of " + at("buffers", view.buffer) + " (" +
                       std::to_string(data.size()) + " bytes): the buffer is truncated or " +
                       "the view is wrong");
  }
  return {data.data() + view.byteOffset, view.byteLength};
}

const tinygltf::Accessor& checked_accessor(const Context& ctx, const tinygltf::Model& model,
                                           int index, const std::string& where,
                                           std::initializer_list<int> types) {
  check_index(ctx, where, index, model.accessors.size(), "accessors");
  const tinygltf::Accessor& a = model.accessors[index];
  const std::string name = where + " (" + at("accessors", index) + ")";
  bool type_ok = false;
  std::string expected;
  for (int t : types) {
    type_ok |= a.type == t;
    expected += std::string(expected.empty() ? "" : " or ") + type_name(t);
  }
  if (!type_ok) ctx.fail(name, std::string("is ") + type_name(a.type) + ", must be " + expected);
  if (component_size(a.componentType) == 0) {
    ctx.fail(name, "has invalid componentType " + std::to_string(a.componentType));
  }
  if (a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                       a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
    ctx.fail(name, "is normalized, which only byte and short components may be");
  }
  return a;
}

AccessorValues read_accessor(const Context& ctx, const tinygltf::Model& model, int index,
                             const std::string& where, std::initializer_list<int> types) {
  const tinygltf::Accessor& a = checked_accessor(ctx, model, index, where, types);
  const std::string name = where + " (" + at("accessors", index) + ")";
  AccessorValues r;
  r.count = a.count;
  r.components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
  // An accessor over no buffer view is all zeros (before its sparse values).
  if (a.bufferView < 0) {
    // Zeros cost no file bytes, so the count alone could ask for any amount of memory: it is
    // held to the size a buffer of these elements could have (found by fuzzing).
    const uint64_t bytes =
        checked_span(ctx, name, a.count, component_size(a.componentType) * r.components, 0);
    if (bytes > ctx.options.max_file_bytes) {
      ctx.fail(name, "has no bufferView and " + std::to_string(a.count) + " elements (" +
                         std::to_string(bytes) + " bytes), over the limit of " +
                         std::to_string(ctx.options.max_file_bytes) +
                         " bytes (ImportOptions::max_file_bytes)");
    }
    r.values.assign(size_t(a.count) * r.components, 0.0);
  } else if (!read_stored_type(ctx, model, a, name, r)) {
    read_elements(ctx, model, a.bufferView, a.byteOffset, a.count, a.componentType, r.components,
                  a.normalized, kViewStride, name, r.values);
  }
  if (a.sparse.isSparse) {
    const std::string sparse = name + ".sparse";
    if (a.sparse.count < 1 || size_t(a.sparse.count) > a.count) {
      ctx.fail(sparse + ".count", "is " + std::to_string(a.sparse.count) + ", must be in 1.." +
                                      std::to_string(a.count));
    }
    const int index_type = a.sparse.indices.componentType;
    if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      ctx.fail(sparse + ".indices.componentType",
               "is " + std::to_string(index_type) + ", must be an unsigned integer type");
    }
    std::vector<double> indices, values;
    read_elements(ctx, model, a.sparse.indices.bufferView, uint64_t(a.sparse.indices.byteOffset),
                  uint64_t(a.sparse.count), index_type, 1, false, 0, sparse + ".indices", indices);
    read_elements(ctx, model, a.sparse.values.bufferView, uint64_t(a.sparse.values.byteOffset),
                  uint64_t(a.sparse.count), a.componentType, r.components, a.normalized, 0,
                  sparse + ".values", values);
    for (size_t i = 0; i < indices.size(); ++i) {
      if (indices[i] >= double(a.count)) {
        ctx.fail(sparse + ".indices", "element " + std::to_string(i) + " is " +
                                          std::to_string(uint64_t(indices[i])) + ", past the " +
                                          std::to_string(a.count) + " elements");
      }
      std::copy_n(values.begin() + i * r.components, r.components,
                  r.values.begin() + size_t(indices[i]) * r.components);
    }
  }
  return r;
}

}  // namespace tessera::gltf
