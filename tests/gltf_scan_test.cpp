// The glTF importer's fast JSON scan (scan_document): it vouches only for syntactically valid
// JSON whose checked properties have the types check_document requires, and gives up on every
// other text, so that the full parse names the error. Expected results come from the JSON
// grammar (RFC 8259) and the glTF 2.0 schema, not from the scan.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/gltf_detail.h"

namespace tessera::gltf {
namespace {

using nlohmann::json;

TEST(GltfScan, ValidDocumentKeepsOnlyTheMembersReadFromTheJsonAfterTinyGltf) {
  const std::string text = R"({"asset": {"version": "2.0"},
    "accessors": [{"bufferView": 0, "count": 3, "componentType": 5126, "type": "VEC3",
                   "min": [-1.5, 0, 2e3], "max": [1, 1E-2, 3]}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "nodes": [{"mesh": 0, "name": "a \"quoted\" name", "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}],
    "animations": [{"channels": [], "extras": {"deep": [null, true, false, {"x": -0.5}]}}],
    "scene": 0, "scenes": [{"nodes": [0]}]})";
  const std::optional<json> doc = scan_document(text);
  ASSERT_TRUE(doc.has_value());
  json expected = json::parse(text);
  for (const char* dropped : {"accessors", "bufferViews", "meshes", "nodes", "animations"}) {
    expected.erase(dropped);
  }
  EXPECT_EQ(*doc, expected);
}

TEST(GltfScan, GivesUpOnTypeErrorsOfCheckedProperties) {
  for (const char* text : {
           R"({"accessors": [{"count": -1}]})",      // integer >= 0
           R"({"accessors": [{"count": 1.0}]})",     // a fraction is not an integer
           R"({"accessors": [{"count": 1e2}]})",     // nor is an exponent
           R"({"accessors": [{"count": "1"}]})",     // a string is not a number
           R"({"accessors": [{"normalized": 1}]})",  // boolean
           R"({"meshes": [{"primitives": {}}]})",    // array of objects
           R"({"meshes": [{"primitives": [3]}]})",   // ... each an object
           R"({"nodes": [{"matrix": [1, 2, 3]}]})",  // 16 numbers
           R"({"nodes": [{"children": [0, -2]}]})",  // integers >= 0
           R"({"extensionsUsed": ["a", 1]})",        // strings
           R"({"meshes": [{"primitives": [{"attributes": {"POSITION": 0.5}}]}]})",
           R"({"asset": {"version": 2}})",
       }) {
    EXPECT_FALSE(scan_document(text).has_value()) << text;
  }
}

// Nodes are read from TinyGLTF's model, so the scan also gives up where that would differ from
// the JSON: TinyGLTF keeps indices in an int, drops a skin that is not an integer (one
// check_document refuses), and reads no translation, rotation or scale beside a matrix.
TEST(GltfScan, GivesUpWhereTinyGltfReadsNodesDifferently) {
  for (
      const char* text : {
          R"({"nodes": [{"mesh": 2147483648}]})",  // 2^31: wraps in an int
          R"({"nodes": [{"children": [0, 4294967296]}]})",
          R"({"nodes": [{"extensions": {"KHR_lights_punctual": {"light": 9999999999}}}]})",
          R"({"nodes": [{"skin": -1}]})",
          R"({"nodes": [{"skin": "a"}]})",
          R"({"nodes": [{"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "scale": [1, 1, 1]}]})",
          R"({"nodes": [{"rotation": [0, 0, 0, 1], "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}]})",
      }) {
    EXPECT_FALSE(scan_document(text).has_value()) << text;
  }
}

// TinyGLTF also reads a sparse accessor's count, offsets and index type into an int, so the scan
// gives up on those over 2^31 - 1 too; check_document then quotes the value as written, where
// TinyGLTF's int would wrap 3000000000 to a negative count and 4294967297 to 1.
TEST(GltfScan, GivesUpOnSparseValuesThatTinyGltfsIntWouldWrap) {
  const auto sparse = [](const std::string& members) {
    return R"({"accessors": [{"count": 4, "sparse": {)" + members + "}}]}";
  };
  for (const std::string& text : {
           sparse(R"("count": 2147483648)"),
           sparse(R"("count": 4294967297)"),
           sparse(R"("indices": {"bufferView": 0, "byteOffset": 2147483648})"),
           sparse(R"("indices": {"bufferView": 0, "componentType": 4294972421})"),
           sparse(R"("values": {"bufferView": 0, "byteOffset": 2147483648})"),
       }) {
    EXPECT_FALSE(scan_document(text).has_value()) << text;
  }
  EXPECT_TRUE(scan_document(sparse(R"("count": 2147483647, "indices": {"byteOffset": 2147483647,)"
                                   R"( "componentType": 5125}, "values": {"byteOffset": 0})"))
                  .has_value());
}

// Every index, and the other integers TinyGLTF reads into an int, over 2^31 - 1: check_document
// refuses them, so the scan gives up on them too (it vouched for primitive attributes, whose
// 4294967296 TinyGLTF wrapped to accessors[0]).
TEST(GltfScan, GivesUpOnEveryIntThatTinyGltfWouldWrap) {
  for (const char* text : {
           R"({"meshes": [{"primitives": [{"attributes": {"POSITION": 4294967296}}]}]})",
           R"({"meshes": [{"primitives": [{"attributes": {"TEXCOORD_0": 2147483648}}]}]})",
           R"({"meshes": [{"primitives": [{"targets": [{"NORMAL": 2147483648}]}]}]})",
           R"({"meshes": [{"primitives": [{"mode": 4294967300}]}]})",
           R"({"materials": [{"normalTexture": {"index": 0, "texCoord": 4294967297}}]})",
           R"({"samplers": [{"wrapS": 4294977593}]})",
           R"({"skins": [{"joints": [2147483648]}]})",
           R"({"animations": [{"channels": [{"target": {"node": 2147483648}}]}]})",
       }) {
    EXPECT_FALSE(scan_document(text).has_value()) << text;
  }
  EXPECT_TRUE(
      scan_document(
          R"({"meshes": [{"primitives": [{"attributes": {"POSITION": 2147483647}, "mode": 4}]}]})")
          .has_value());
}

TEST(GltfScan, VouchesForTheLargestIntIndex) {
  EXPECT_TRUE(scan_document(R"({"nodes": [{"mesh": 2147483647, "skin": 0}]})").has_value());
}

TEST(GltfScan, GivesUpOnInvalidOrUnusualJson) {
  std::string deep = "{\"extras\": ";  // appended: GCC 12 warns (wrongly) about a chain of +
  deep.append(300, '[').append(300, ']').append("}");
  for (const std::string& text : {
           std::string(R"([{"asset": {}}])"),                          // not an object
           std::string(R"({"asset": {"version": "2.0"},})"),           // trailing comma
           std::string(R"({"asset": {"version": "2.0"}} x)"),          // text after the document
           std::string(R"({"asset": {"version": "2.0"})"),             // unterminated
           std::string(R"({"asset": {"version": '2.0'}})"),            // single quotes
           std::string(R"({"scene": 01})"),                            // leading zero
           std::string(R"({"scene": +1})"),                            // plus sign
           std::string(R"({"extras": [1.]})"),                         // fraction without digits
           std::string(R"({"extras": [tru]})"),                        // literal
           std::string("{\"extras\": \"a\x01\"}"),                     // control character
           std::string(R"({"extras": "\q"})"),                         // unknown escape
           std::string(R"({"asset": {"version": "2.\u0030"}})"),       // \u: left to nlohmann
           std::string("{\"nodes\": [{\"name\": \"caf\xc3\xa9\"}]}"),  // non-ASCII: left to it
           std::string(R"({"scene": 12345678901234567890})"),          // beyond 18 digits
           std::string(R"({"extras": 1e1000})"),                       // 4-digit exponent
           std::string(R"({"ext\"ras": 1})"),                          // key with an escape
           deep,                                                       // nested beyond 256
       }) {
    EXPECT_FALSE(scan_document(text).has_value()) << text;
  }
}

}  // namespace
}  // namespace tessera::gltf
