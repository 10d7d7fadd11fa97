// The JSON checks that come before TinyGLTF: property types, required extensions, and the
// files that buffers and images name.

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include "core/check.h"
#include "core/gltf_detail.h"
#include "core/json_places.h"
#include "core/mapped_file.h"

namespace tessera::gltf {
namespace {

using nlohmann::json;

enum class Kind {
  index,   // integer 0 to 2^31 - 1: an index into one of the file's arrays (a glTFid)
  int32,   // integer 0 to 2^31 - 1 that is not an index (a mode, a uv set, an enum value)
  uint,    // integer >= 0, read into 64 bits (byte offsets, lengths and strides, counts)
  number,  // any JSON number
  string,
  boolean,
  object,   // checked against `fields`
  objects,  // array of objects, each checked against `fields`
  numbers,  // array of `length` numbers (any length when 0)
  indices,  // array of indices, each as Kind::index
  strings,  // array of strings
};

// The name of a field that stands for every member of its object (primitive attributes and
// morph targets, whose names are the file's: POSITION, TEXCOORD_0, _CUSTOM, ...).
constexpr std::string_view kEveryMember = "*";

struct Field {
  const char* name;
  Kind kind;
  std::vector<Field> fields = {};
  size_t length = 0;
};

const char* describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::object:
      return "an object";
    case json::value_t::array:
      return "an array";
    case json::value_t::string:
      return "a string";
    case json::value_t::boolean:
      return "a boolean";
    case json::value_t::number_float:
      return "a fractional number";
    case json::value_t::number_integer:
      return v.get<int64_t>() < 0 ? "a negative integer" : "an integer";
    case json::value_t::number_unsigned:
      return "an integer";
    default:
      return "an unexpected value";
  }
}

bool is_count(const json& v) {
  return v.is_number_unsigned() || (v.is_number_integer() && v.get<int64_t>() >= 0);
}

void check_fields(const Context& ctx, const json& object, const std::string& where,
                  const std::vector<Field>& fields);

// Fails unless `v`, an integer >= 0, is at most 2^31 - 1. TinyGLTF reads every index, and the
// other integers of Kind::int32, into an int, which a larger one wraps: 4294967296 to 0, a valid
// index that imported the wrong accessor, 3000000000 to -1294967296. Quoted as written.
void check_int_range(const Context& ctx, const json& v, const std::string& where) {
  if (v.get<uint64_t>() > uint64_t(INT32_MAX)) {
    ctx.fail(where, "is " + v.dump() + ", above " + std::to_string(INT32_MAX) +
                        " (2^31 - 1), the largest Tessera reads here (TinyGLTF holds it in a "
                        "32-bit int)");
  }
}

void check_value(const Context& ctx, const json& v, const std::string& where, const Field& f) {
  auto wrong = [&](const std::string& expected) {
    ctx.fail(where, "must be " + expected + " (found " + describe(v) + ")");
  };
  switch (f.kind) {
    case Kind::index:
    case Kind::int32:
      if (!is_count(v)) wrong("an integer >= 0");
      check_int_range(ctx, v, where);
      break;
    case Kind::uint:
      if (!is_count(v)) wrong("an integer >= 0");
      break;
    case Kind::number:
      if (!v.is_number()) wrong("a number");
      break;
    case Kind::string:
      if (!v.is_string()) wrong("a string");
      break;
    case Kind::boolean:
      if (!v.is_boolean()) wrong("true or false");
      break;
    case Kind::object:
      if (!v.is_object()) wrong("an object");
      check_fields(ctx, v, where, f.fields);
      break;
    case Kind::objects:
      if (!v.is_array()) wrong("an array of objects");
      for (size_t i = 0; i < v.size(); ++i) {
        const std::string item = where + "[" + std::to_string(i) + "]";
        if (!v[i].is_object()) {
          ctx.fail(item, std::string("must be an object (found ") + describe(v[i]) + ")");
        }
        check_fields(ctx, v[i], item, f.fields);
      }
      break;
    case Kind::numbers:
    case Kind::indices:
    case Kind::strings: {
      const char* item_kind = f.kind == Kind::numbers   ? "numbers"
                              : f.kind == Kind::indices ? "integers >= 0"
                                                        : "strings";
      if (!v.is_array()) wrong(std::string("an array of ") + item_kind);
      if (f.length != 0 && v.size() != f.length) {
        ctx.fail(where, "must have " + std::to_string(f.length) + " elements (found " +
                            std::to_string(v.size()) + ")");
      }
      for (size_t i = 0; i < v.size(); ++i) {
        const std::string item = where + "[" + std::to_string(i) + "]";
        bool ok = f.kind == Kind::numbers   ? v[i].is_number()
                  : f.kind == Kind::indices ? is_count(v[i])
                                            : v[i].is_string();
        if (!ok) {
          ctx.fail(item,
                   std::string("must be one of ") + item_kind + " (found " + describe(v[i]) + ")");
        }
        if (f.kind == Kind::indices) check_int_range(ctx, v[i], item);
      }
      break;
    }
  }
}

void check_fields(const Context& ctx, const json& object, const std::string& where,
                  const std::vector<Field>& fields) {
  const auto path = [&](const std::string& key) { return where.empty() ? key : where + "." + key; };
  for (const Field& f : fields) {
    if (f.name == kEveryMember) {
      for (const auto& [key, value] : object.items()) check_value(ctx, value, path(key), f);
      continue;
    }
    auto it = object.find(f.name);
    if (it != object.end()) check_value(ctx, *it, path(f.name), f);
  }
}

// The properties Tessera reads (glTF 2.0 schema, and the extensions it supports), and every
// index of glTF 2.0 (each glTFid of its schema: those of skins and animations too, which Tessera
// ignores, but TinyGLTF reads into an int as it reads the others). Others are left to TinyGLTF
// and then ignored.
const std::vector<Field>& document_schema() {
  static const std::vector<Field> texture_transform = {{"offset", Kind::numbers, {}, 2},
                                                       {"rotation", Kind::number},
                                                       {"scale", Kind::numbers, {}, 2},
                                                       {"texCoord", Kind::int32}};
  static const std::vector<Field> texture_info = {
      {"index", Kind::index},
      {"texCoord", Kind::int32},
      {"scale", Kind::number},
      {"strength", Kind::number},
      {"extensions", Kind::object, {{"KHR_texture_transform", Kind::object, texture_transform}}}};
  // Attribute name -> accessor: a primitive's attributes and each of its morph targets.
  static const std::vector<Field> attributes = {{kEveryMember.data(), Kind::index}};
  static const std::vector<Field> schema = {
      {"asset", Kind::object, {{"version", Kind::string}, {"minVersion", Kind::string}}},
      {"extensionsUsed", Kind::strings},
      {"extensionsRequired", Kind::strings},
      {"scene", Kind::index},
      {"scenes", Kind::objects, {{"nodes", Kind::indices}, {"name", Kind::string}}},
      {"nodes",
       Kind::objects,
       {{"name", Kind::string},
        {"children", Kind::indices},
        {"mesh", Kind::index},
        {"camera", Kind::index},
        {"skin", Kind::index},
        {"matrix", Kind::numbers, {}, 16},
        {"translation", Kind::numbers, {}, 3},
        {"rotation", Kind::numbers, {}, 4},
        {"scale", Kind::numbers, {}, 3},
        {"extensions",
         Kind::object,
         {{"KHR_lights_punctual", Kind::object, {{"light", Kind::index}}}}}}},
      {"meshes",
       Kind::objects,
       {{"name", Kind::string},
        {"primitives",
         Kind::objects,
         {{"attributes", Kind::object, attributes},
          {"indices", Kind::index},
          {"material", Kind::index},
          {"mode", Kind::int32},
          {"targets", Kind::objects, attributes}}}}},
      {"accessors",
       Kind::objects,
       {{"bufferView", Kind::index},
        {"byteOffset", Kind::uint},
        {"componentType", Kind::uint},
        {"normalized", Kind::boolean},
        {"count", Kind::uint},
        {"type", Kind::string},
        {"min", Kind::numbers},
        {"max", Kind::numbers},
        // TinyGLTF reads a sparse accessor's numbers into an int too.
        {"sparse",
         Kind::object,
         {{"count", Kind::int32},
          {"indices",
           Kind::object,
           {{"bufferView", Kind::index},
            {"byteOffset", Kind::int32},
            {"componentType", Kind::int32}}},
          {"values", Kind::object, {{"bufferView", Kind::index}, {"byteOffset", Kind::int32}}}}}}},
      {"bufferViews",
       Kind::objects,
       {{"buffer", Kind::index},
        {"byteOffset", Kind::uint},
        {"byteLength", Kind::uint},
        {"byteStride", Kind::uint},
        {"target", Kind::int32}}},
      {"buffers", Kind::objects, {{"uri", Kind::string}, {"byteLength", Kind::uint}}},
      {"materials",
       Kind::objects,
       {{"name", Kind::string},
        {"pbrMetallicRoughness",
         Kind::object,
         {{"baseColorFactor", Kind::numbers, {}, 4},
          {"metallicFactor", Kind::number},
          {"roughnessFactor", Kind::number},
          {"baseColorTexture", Kind::object, texture_info},
          {"metallicRoughnessTexture", Kind::object, texture_info}}},
        {"normalTexture", Kind::object, texture_info},
        {"occlusionTexture", Kind::object, texture_info},
        {"emissiveTexture", Kind::object, texture_info},
        {"emissiveFactor", Kind::numbers, {}, 3},
        {"alphaMode", Kind::string},
        {"alphaCutoff", Kind::number},
        {"doubleSided", Kind::boolean},
        {"extensions",
         Kind::object,
         {{"KHR_materials_emissive_strength",
           Kind::object,
           {{"emissiveStrength", Kind::number}}}}}}},
      {"textures",
       Kind::objects,
       {{"sampler", Kind::index}, {"source", Kind::index}, {"name", Kind::string}}},
      {"images",
       Kind::objects,
       {{"uri", Kind::string},
        {"mimeType", Kind::string},
        {"bufferView", Kind::index},
        {"name", Kind::string}}},
      {"samplers",
       Kind::objects,
       {{"magFilter", Kind::int32},
        {"minFilter", Kind::int32},
        {"wrapS", Kind::int32},
        {"wrapT", Kind::int32}}},
      {"skins",
       Kind::objects,
       {{"inverseBindMatrices", Kind::index},
        {"skeleton", Kind::index},
        {"joints", Kind::indices}}},
      {"animations",
       Kind::objects,
       {{"channels",
         Kind::objects,
         {{"sampler", Kind::index}, {"target", Kind::object, {{"node", Kind::index}}}}},
        {"samplers", Kind::objects, {{"input", Kind::index}, {"output", Kind::index}}}}},
      {"cameras",
       Kind::objects,
       {{"type", Kind::string},
        {"perspective",
         Kind::object,
         {{"aspectRatio", Kind::number},
          {"yfov", Kind::number},
          {"zfar", Kind::number},
          {"znear", Kind::number}}},
        {"orthographic",
         Kind::object,
         {{"xmag", Kind::number},
          {"ymag", Kind::number},
          {"zfar", Kind::number},
          {"znear", Kind::number}}}}},
      {"extensions",
       Kind::object,
       {{"KHR_lights_punctual",
         Kind::object,
         {{"lights",
           Kind::objects,
           {{"type", Kind::string},
            {"name", Kind::string},
            {"color", Kind::numbers, {}, 3},
            {"intensity", Kind::number},
            {"range", Kind::number},
            {"spot",
             Kind::object,
             {{"innerConeAngle", Kind::number}, {"outerConeAngle", Kind::number}}}}}}}}}};
  return schema;
}

// Extensions whose every use Tessera honours, so files that require them can be imported.
// KHR_mesh_quantization only widens the component types of vertex attributes, which
// read_accessor reads whatever they are (convert_primitive holds them to the extension's).
const std::set<std::string> kSupportedExtensions = {
    "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_texture_transform",
    "KHR_mesh_quantization"};

// RFC 3986 percent-decoding of a relative uri into a file name.
std::string decode_uri(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out.push_back(char(std::stoi(uri.substr(i + 1, 2), nullptr, 16)));
      i += 2;
    } else {
      out.push_back(uri[i]);
    }
  }
  return out;
}

void check_files(const Context& ctx, const json& doc, const char* array, bool is_buffer) {
  auto it = doc.find(array);
  if (it == doc.end()) return;
  for (size_t i = 0; i < it->size(); ++i) {
    const json& item = (*it)[i];
    const std::string where = at(array, i);
    auto uri = item.find("uri");
    if (uri == item.end()) {
      if (is_buffer && i != 0)
        ctx.fail(where, "has no uri (only buffers[0] of a .glb may omit it)");
      continue;
    }
    const std::string u = uri->get<std::string>();
    if (u.rfind("data:", 0) == 0) continue;  // embedded: within the file's own size limit
    if (u.find("://") != std::string::npos) {
      ctx.fail(where + ".uri", "'" + u + "' is not a relative file name (no network access)");
    }
    const std::filesystem::path path = std::filesystem::path(ctx.base_dir) / decode_uri(u);
    try {
      require_regular_file(path.string());
    } catch (const Error& e) {
      ctx.fail(where + ".uri", e.what());
    }
    std::error_code error;
    const uintmax_t size = std::filesystem::file_size(path, error);
    if (error) ctx.fail(where + ".uri", "cannot read '" + path.string() + "': " + error.message());
    if (size > ctx.options.max_file_bytes) {
      ctx.fail(where + ".uri", "'" + path.string() + "' is " + std::to_string(size) +
                                   " bytes, over the limit of " +
                                   std::to_string(ctx.options.max_file_bytes));
    }
    if (is_buffer) {
      const uint64_t length = item.value("byteLength", uint64_t(0));
      if (size < length) {
        ctx.fail(where, "'" + path.string() + "' is truncated: " + std::to_string(size) +
                            " bytes, byteLength says " + std::to_string(length));
      }
    }
  }
}

// The members of the document that the importer reads from the JSON after TinyGLTF on a
// document the scan vouches for (the rest, the large nodes, accessors, bufferViews and meshes
// among them, it reads from TinyGLTF's model).
const std::set<std::string, std::less<>> kDocumentMembers = {
    "asset",     "extensionsUsed", "extensionsRequired", "scene",  "scenes",  "cameras",
    "materials", "textures",       "samplers",           "images", "buffers", "extensions"};

// A strict JSON reader that checks the property types of document_schema without building a
// document: it only says whether the text is valid JSON whose checked properties all have their
// types, and where each top-level member's value lies. Wherever nlohmann::json and check_value
// might see the text differently from this simple reading (escapes \u, bytes of 0x80 and more,
// integers of 19 digits or more, exponents of 4 digits or more, a byte-order mark, keys with
// escapes, deep nesting), it gives up, as it does at the first error, and the caller parses the
// whole document instead, whose checks name the error. It accepts only what nlohmann::json
// parses to the same values and check_value accepts (no index over 2^31 - 1, which TinyGLTF's
// int would wrap). So that nodes can be read from TinyGLTF's model, which keeps them in a
// narrower form, it also gives up on an object with both a matrix and translation, rotation or
// scale (TinyGLTF drops the latter, whose presence Tessera warns about).
class Scan {
 public:
  explicit Scan(std::string_view text) : p_(text.data()), end_(text.data() + text.size()) {}

  // The text of the document's "buffers" array: true with `length_text` = the text of
  // buffers[0].byteLength's value, when buffers[0] has exactly one byteLength, an integer, and
  // no uri (the buffer a .glb stores in its BIN chunk).
  bool first_buffer_length(std::string_view& length_text) {
    size_t index = 0;
    int lengths = 0;
    bool uri = false;
    const bool ok = array(
        [&] {
          if (index != 0) return any();
          return object([&](std::string_view key) {
            uri |= key == "uri";
            if (key != "byteLength") return any();
            ++lengths;
            const char* begin = p_;
            Number kind;
            if (!number(kind)) return false;
            length_text = std::string_view(begin, size_t(p_ - begin));
            return kind == Number::count;
          });
        },
        index);
    return ok && at_end() && lengths == 1 && !uri;
  }

  // The top-level object: true with members[key] = its value's text for every member.
  bool document(std::map<std::string, std::string_view, std::less<>>& members) {
    space();
    if (!take('{')) return false;
    space();
    if (take('}')) return at_end();
    for (;;) {
      std::string_view key;
      if (!key_string(key) || !colon()) return false;
      space();
      const char* begin = p_;
      const Field* field = find(document_schema(), key);
      if (!(field ? checked(*field) : any())) return false;
      members[std::string(key)] = std::string_view(begin, size_t(p_ - begin));  // last wins
      space();
      if (take('}')) return at_end();
      if (!take(',')) return false;
      space();
    }
  }

 private:
  static constexpr int kMaxDepth = 256;
  enum class Number { count, other };  // count: an integer >= 0 that nlohmann stores as one

  const char* p_;
  const char* end_;
  int depth_ = 0;

  static const Field* find(const std::vector<Field>& fields, std::string_view key) {
    for (const Field& f : fields) {
      if (key == f.name || f.name == kEveryMember) return &f;
    }
    return nullptr;
  }
  void space() {
    while (p_ < end_ && (*p_ == ' ' || *p_ == '\n' || *p_ == '\r' || *p_ == '\t')) ++p_;
  }
  bool take(char c) {
    if (p_ == end_ || *p_ != c) return false;
    ++p_;
    return true;
  }
  bool at_end() {
    space();
    return p_ == end_;
  }
  bool colon() {
    space();
    return take(':');
  }
  bool digits() {
    const char* begin = p_;
    while (p_ < end_ && *p_ >= '0' && *p_ <= '9') ++p_;
    return p_ > begin;
  }
  // A string; `plain` is set when it has no escape (its text is its value).
  bool string(bool& plain) {
    if (!take('"')) return false;
    plain = true;
    while (p_ < end_) {
      const unsigned char c = static_cast<unsigned char>(*p_++);
      if (c == '"') return true;
      if (c < 0x20 || c >= 0x80) return false;
      if (c == '\\') {
        if (p_ == end_ || std::strchr("\"\\/bfnrt", *p_) == nullptr || *p_ == '\0') return false;
        ++p_;
        plain = false;
      }
    }
    return false;
  }
  bool key_string(std::string_view& key) {
    const char* begin = p_ + 1;
    bool plain = false;
    if (!string(plain) || !plain) return false;
    key = std::string_view(begin, size_t(p_ - 1 - begin));
    return true;
  }
  bool number(Number& kind) {
    const bool negative = take('-');
    const char* begin = p_;
    if (p_ < end_ && *p_ == '0') {
      ++p_;
    } else if (!digits()) {
      return false;
    }
    const bool integer = p_ == end_ || (*p_ != '.' && *p_ != 'e' && *p_ != 'E');
    if (integer && p_ - begin > 18) return false;
    if (take('.') && !digits()) return false;
    if (p_ < end_ && (*p_ == 'e' || *p_ == 'E')) {
      ++p_;
      if (!take('+')) take('-');
      const char* exponent = p_;
      if (!digits() || p_ - exponent > 3) return false;
    }
    kind = integer && !negative ? Number::count : Number::other;
    return true;
  }
  bool literal(std::string_view word) {
    if (size_t(end_ - p_) < word.size() || std::string_view(p_, word.size()) != word) return false;
    p_ += word.size();
    return true;
  }
  // Elements of an array, each read by `element`; counts them.
  template <typename F>
  bool array(F&& element, size_t& count) {
    count = 0;
    if (!take('[')) return false;
    space();
    if (take(']')) return true;
    for (;;) {
      space();
      if (!element()) return false;
      ++count;
      space();
      if (take(']')) return true;
      if (!take(',')) return false;
    }
  }
  // Members of an object, each value read by `member(key)`.
  template <typename F>
  bool object(F&& member) {
    if (!take('{')) return false;
    space();
    if (take('}')) return true;
    for (;;) {
      std::string_view key;
      space();
      if (!key_string(key) || !colon()) return false;
      space();
      if (!member(key)) return false;
      space();
      if (take('}')) return true;
      if (!take(',')) return false;
    }
  }
  bool nested(bool (Scan::*read)(const Field*), const Field* f) {
    if (++depth_ > kMaxDepth) return false;
    const bool ok = (this->*read)(f);
    --depth_;
    return ok;
  }
  bool any() { return nested(&Scan::any_value, nullptr); }
  bool any_value(const Field*) {
    if (p_ == end_) return false;
    size_t count = 0;
    bool plain = false;
    Number kind;
    switch (*p_) {
      case '{':
        return object([&](std::string_view) { return any(); });
      case '[':
        return array([&] { return any(); }, count);
      case '"':
        return string(plain);
      case 't':
        return literal("true");
      case 'f':
        return literal("false");
      case 'n':
        return literal("null");
      default:
        return number(kind);
    }
  }
  bool fields(const std::vector<Field>& fields) {
    bool matrix = false, trs = false;
    return object([&](std::string_view key) {
             const Field* f = find(fields, key);
             if (f && f->name != kEveryMember) {
               matrix |= key == "matrix";
               trs |= key == "translation" || key == "rotation" || key == "scale";
             }
             return f ? checked(*f) : any();
           }) &&
           !(matrix && trs);
  }
  bool count() {
    Number kind;
    return number(kind) && kind == Number::count;
  }
  // A count that fits in TinyGLTF's int.
  bool index() {
    const char* begin = p_;
    if (!count()) return false;
    const std::string_view digits(begin, size_t(p_ - begin));
    return digits.size() < 10 || (digits.size() == 10 && digits <= "2147483647");
  }
  bool checked(const Field& f) { return nested(&Scan::checked_value, &f); }
  // check_value's test of `f`, on the text.
  bool checked_value(const Field* field) {
    const Field& f = *field;
    size_t n = 0;
    bool plain = false;
    Number kind;
    switch (f.kind) {
      case Kind::index:
      case Kind::int32:
        return index();
      case Kind::uint:
        return count();
      case Kind::number:
        return number(kind);
      case Kind::string:
        return string(plain);
      case Kind::boolean:
        return literal("true") || literal("false");
      case Kind::object:
        return fields(f.fields);
      case Kind::objects:
        return array([&] { return fields(f.fields); }, n);
      case Kind::numbers:
        return array([&] { return number(kind); }, n) && (f.length == 0 || n == f.length);
      case Kind::indices:
        return array([&] { return index(); }, n);
      case Kind::strings:
        return array([&] { return string(plain); }, n);
    }
    return false;
  }
};

}  // namespace

std::optional<json> scan_document(std::string_view text, std::string_view* glb_buffer_length) {
  std::map<std::string, std::string_view, std::less<>> members;
  if (!Scan(text).document(members)) return std::nullopt;
  if (glb_buffer_length) {
    *glb_buffer_length = {};
    const auto buffers = members.find("buffers");
    std::string_view number;
    if (buffers != members.end() && Scan(buffers->second).first_buffer_length(number)) {
      *glb_buffer_length = number;
    }
  }
  json doc = json::object();
  try {
    for (const auto& [key, value] : members) {
      if (kDocumentMembers.count(key)) doc[key] = json::parse(value.begin(), value.end());
    }
  } catch (const json::exception&) {
    return std::nullopt;  // not expected (the scan is stricter); the full parse names it
  }
  return doc;
}

void explain_tinygltf_failure(const Context& ctx, std::string_view text) {
  json doc;
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const json::out_of_range& e) {
    // "number overflow parsing '1e999'" (id 406) says what but not where: the number's first
    // place in the text, by line and column.
    const std::string what = e.what();
    const size_t open = what.find('\''), close = what.rfind('\'');
    if (e.id != 406 || open == std::string::npos || close <= open) return;
    const std::string number = what.substr(open + 1, close - open - 1);
    const size_t at = text.find(number);
    if (at == std::string_view::npos) return;
    const JsonPlace place = place_of_offset(text, at);
    ctx.fail("", "line " + std::to_string(place.line) + ", column " + std::to_string(place.column) +
                     ": the number " + number + " is out of the range of a double");
  } catch (const json::exception&) {
    return;
  }
  if (!doc.is_object()) return;
  const auto integer = [](const json& j, const char* key) -> std::optional<int64_t> {
    const auto it = j.find(key);
    if (it == j.end() || !it->is_number_integer()) return std::nullopt;
    return it->get<int64_t>();
  };
  const json& accessors = member(doc, "accessors");
  const json& meshes = member(doc, "meshes");
  for (size_t m = 0; m < meshes.size(); ++m) {
    const json& primitives = member(meshes[m], "primitives");
    for (size_t p = 0; p < primitives.size(); ++p) {
      const std::string where = at("meshes", m) + ".primitives[" + std::to_string(p) + "]";
      if (const auto i = integer(primitives[p], "indices"))
        check_index(ctx, where + ".indices", *i, accessors.size(), "accessors");
      for (const auto& [name, value] : member_object(primitives[p], "attributes").items()) {
        if (value.is_number_integer())
          check_index(ctx, where + ".attributes." + name, value.get<int64_t>(), accessors.size(),
                      "accessors");
      }
    }
  }
  for (size_t i = 0; i < accessors.size(); ++i) {
    const auto type = integer(accessors[i], "componentType");
    if (type && !(*type >= 5120 && *type <= 5123) && *type != 5125 && *type != 5126) {
      ctx.fail(at("accessors", i) + ".componentType",
               "is " + std::to_string(*type) + "; glTF allows 5120 to 5123, 5125 and 5126 (5.1)");
    }
  }
  const json& views = member(doc, "bufferViews");
  for (size_t i = 0; i < views.size(); ++i) {
    const auto stride = integer(views[i], "byteStride");
    if (stride && (*stride < 4 || *stride > 252 || *stride % 4 != 0)) {
      ctx.fail(at("bufferViews", i) + ".byteStride",
               "is " + std::to_string(*stride) + "; glTF allows 4 to 252, a multiple of 4 (5.11)");
    }
  }
  const json& cameras = member(doc, "cameras");
  for (size_t i = 0; i < cameras.size(); ++i) {
    if (!cameras[i].is_object()) continue;
    const std::string type = cameras[i].value("type", std::string());
    if (type != "perspective" && type != "orthographic") {
      ctx.fail(at("cameras", i) + ".type",
               "is '" + type + "'; glTF cameras are \"perspective\" or \"orthographic\"");
    }
    if (!cameras[i].contains(type))
      ctx.fail(at("cameras", i), "a " + type + " camera needs \"" + type + "\"");
  }
  const json& lights =
      member(member_object(member_object(doc, "extensions"), "KHR_lights_punctual"), "lights");
  for (size_t i = 0; i < lights.size(); ++i) {
    if (lights[i].is_object() && lights[i].value("type", std::string()) == "spot" &&
        !lights[i].contains("spot")) {
      ctx.fail("extensions.KHR_lights_punctual.lights[" + std::to_string(i) + "]",
               "a spot light needs \"spot\"");
    }
  }
  const json& buffers = member(doc, "buffers");
  for (size_t i = 0; i < buffers.size(); ++i) {
    if (!buffers[i].is_object()) continue;
    const std::string uri = buffers[i].value("uri", std::string());
    const size_t data = uri.find(";base64,");
    if (uri.rfind("data:", 0) != 0 || data == std::string::npos) continue;
    const std::string_view digits = std::string_view(uri).substr(data + 8);
    const bool base64 = std::all_of(digits.begin(), digits.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/' || c == '=';
    });
    if (!base64) {
      ctx.fail(at("buffers", i) + ".uri",
               "is a data uri whose data is not base64 (A-Z, a-z, 0-9, +, / and =)");
    }
  }
}

namespace {

// A glTF 1.0 document differs from 2.0 throughout (objects keyed by id where 2.0 has arrays,
// "scene" a string), so it is named by its version before the 2.0 schema refuses the first
// property it meets ("scene: must be an integer >= 0 (found a string)"). Its asset.version is
// "1.0" (a string, as in 2.0), or the number 1 that some 1.0 exporters wrote.
void refuse_gltf_1(const Context& ctx, const json& doc) {
  const auto asset = doc.find("asset");
  if (asset == doc.end() || !asset->is_object()) return;
  const auto version = asset->find("version");
  if (version == asset->end()) return;
  const bool one =
      version->is_string()
          ? *version == "1" || version->get<std::string>().rfind("1.", 0) == 0
          : version->is_number() && version->get<double>() >= 1.0 && version->get<double>() < 2.0;
  if (one) {
    ctx.fail("asset.version",
             "is " + version->dump() +
                 ": this is a glTF 1.0 file, which Tessera does not read (only glTF 2.0 is "
                 "supported; re-export or convert the model to glTF 2.0)");
  }
}

}  // namespace

void check_document(const Context& ctx, const json& doc) {
  if (!doc.is_object()) ctx.fail("", "the JSON document is not an object");
  if (!doc.contains("asset")) ctx.fail("asset", "is missing (every glTF file has one)");
  refuse_gltf_1(ctx, doc);
  check_fields(ctx, doc, "", document_schema());
  const std::string version = doc["asset"].value("version", "");
  if (version.rfind("2.", 0) != 0) {
    ctx.fail("asset.version", "is '" + version + "'; only glTF 2.x is supported");
  }
  for (const auto& name : doc.value("extensionsRequired", json::array())) {
    if (!kSupportedExtensions.count(name.get<std::string>())) {
      ctx.fail("extensionsRequired", "the file requires extension " + name.get<std::string>() +
                                         ", which Tessera does not support");
    }
  }
  for (const auto& name : doc.value("extensionsUsed", json::array())) {
    if (!kSupportedExtensions.count(name.get<std::string>())) {
      ctx.warn("extensionsUsed", "extension " + name.get<std::string>() + " is ignored");
    }
  }
  check_files(ctx, doc, "buffers", true);
  check_files(ctx, doc, "images", false);
}

}  // namespace tessera::gltf
