// glTF 2.0 import: the broken files of Debian's assimp-testmodels and tests/data/bad/ each give
// their specific Error; good files import to the counts, bounds and transforms read by hand
// from their JSON; BoxTextured, 2CylinderEngine and the asset generator's triangle modes render
// the same with the compute path and the reference renderer, and are kept as golden images.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "core/check.h"
#include "core/image.h"
#include "core/model_import.h"
#include "tests/accuracy_support.h"
#include "tests/support/bad_corpus.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

const std::string kModels = "/usr/share/assimp/models/glTF2/";
const std::string kData = TESSERA_TEST_DATA_DIR;

// The Error message of importing `path`, or "" if it imports.
std::string import_error(const std::string& path, const ImportOptions& options = {}) {
  try {
    import_gltf(path, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

#define EXPECT_IMPORT_ERROR(path, ...)                           \
  do {                                                           \
    const std::string message = import_error(path);              \
    for (const char* word : {__VA_ARGS__}) {                     \
      EXPECT_NE(message.find(word), std::string::npos)           \
          << (path) << ": '" << word << "' not in: " << message; \
    }                                                            \
  } while (0)

TEST(GltfImport, AssimpBrokenFilesGiveSpecificErrors) {
  EXPECT_IMPORT_ERROR(kModels + "wrongTypes/badArray.gltf", "badArray.gltf", "meshes[0].primitives",
                      "must be an array of objects", "found an object");
  EXPECT_IMPORT_ERROR(kModels + "wrongTypes/badExtension.gltf",
                      "baseColorTexture.extensions.KHR_texture_transform", "must be an object",
                      "found a string");
  EXPECT_IMPORT_ERROR(kModels + "wrongTypes/badNumber.gltf", "materials[0].normalTexture.scale",
                      "must be a number", "found a string");
  EXPECT_IMPORT_ERROR(kModels + "wrongTypes/badObject.gltf", "materials[0].pbrMetallicRoughness",
                      "must be an object", "found an array");
  EXPECT_IMPORT_ERROR(kModels + "wrongTypes/badString.gltf", "scenes[0].name", "must be a string",
                      "found an integer");
  EXPECT_IMPORT_ERROR(kModels + "wrongTypes/badUint.gltf", "baseColorTexture.index", "integer >= 0",
                      "negative");
  EXPECT_IMPORT_ERROR(kModels + "SchemaFailures/sceneWrongType.gltf",
                      "scene:", "must be an integer >= 0", "found a string");
  // 24 vertices; the first index is 255 (IndexOutOfRange) or 65535 (AllIndicesOutOfRange).
  EXPECT_IMPORT_ERROR(kModels + "IndexOutOfRange/IndexOutOfRange.gltf",
                      "meshes[0].primitives[0].indices", "is vertex 255", "past the 24 vertices");
  EXPECT_IMPORT_ERROR(kModels + "IndexOutOfRange/AllIndicesOutOfRange.gltf",
                      "meshes[0].primitives[0].indices", "is vertex 65535", "past the 24 vertices");
  // meshes[1] ("TruncatedCube") draws 35 vertices as TRIANGLES.
  EXPECT_IMPORT_ERROR(kModels + "IncorrectVertexArrays/Cube.gltf",
                      "meshes[1].primitives[0].attributes.POSITION", "35 elements",
                      "not a multiple of 3");
  EXPECT_IMPORT_ERROR(kModels + "MissingBin/BoxTextured.gltf", "buffers[0].uri", "BoxTextured0.bin",
                      "No such file");
  EXPECT_IMPORT_ERROR(kModels + "RecursiveNodes/RecursiveNodes.gltf", "nodes[1].children[0]",
                      "node 0", "cycle");
  EXPECT_IMPORT_ERROR(kModels + "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb",
                      "attributes.POSITION", "NaN or infinite");
  EXPECT_IMPORT_ERROR(kModels + "TestNoRootNode/NoScene.gltf", "no scene");
}

// glTF 1.0 files are named as such, by their asset.version (the string "1.0", or the number 1
// that CesiumMilkTruck's exporter wrote), not by the first 1.0 property the 2.0 schema refuses:
// these two were refused as "scene: must be an integer >= 0 (found a string)" and
// "asset.version: must be a string (found an integer)" (a new user's trial).
TEST(GltfImport, Gltf1FilesAreRefusedByVersion) {
  const std::string v1 = "/usr/share/assimp/models/glTF/";
  EXPECT_IMPORT_ERROR(v1 + "BoxTextured-glTF/BoxTextured.gltf", "BoxTextured.gltf: asset.version",
                      "is \"1.0\"", "glTF 1.0", "only glTF 2.0 is supported");
  EXPECT_IMPORT_ERROR(v1 + "CesiumMilkTruck/CesiumMilkTruck.gltf",
                      "asset.version: is 1:", "glTF 1.0", "only glTF 2.0 is supported");
  // The binary form is refused by its header, as before.
  EXPECT_IMPORT_ERROR(v1 + "BoxTextured-glTF-Binary/BoxTextured.glb",
                      "is a binary glTF of version 1, not 2");
  // Any other version that is not 2.x keeps its own message.
  const std::string three = ::testing::TempDir() + "version3.gltf";
  std::ofstream(three) << R"({"asset": {"version": "3.0"}, "scenes": [{}]})";
  EXPECT_IMPORT_ERROR(three, "asset.version", "is '3.0'; only glTF 2.x is supported");
}

// A zero normal has no direction: the vertex gets one generated from its triangles, with a
// warning naming the accessor, the first such element and their count, as OBJ's import does
// for `vn 0 0 0` (it was an error here). BoxBadNormals' elements 0 to 3 are zero; they are the
// corners of the box's face at z = +0.5, whose outward normal is +z. Its elements 4 to 7,
// (0, -0.1, 0), are renormalized to -y as before.
TEST(GltfImport, ZeroNormalsAreGeneratedWithAWarning) {
  const std::string path = kModels + "BoxBadNormals-glTF-Binary/BoxBadNormals.glb";
  const ImportedModel model = import_gltf(path);
  ASSERT_EQ(model.scene.meshes.size(), 1u);
  const Mesh& mesh = model.scene.meshes[0];
  ASSERT_EQ(mesh.normals.size(), 24u);  // vertices kept shared: none split
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(mesh.normals[i], glm::vec3(0, 0, 1)) << "vertex " << i;
  }
  for (int i = 4; i < 8; ++i) EXPECT_EQ(mesh.normals[i], glm::vec3(0, -1, 0)) << "vertex " << i;
  const std::string warning = path +
                              ": meshes[0].primitives[0].attributes.NORMAL: element 0 is the zero "
                              "vector, which has no direction (4 such elements); their vertices "
                              "get normals generated from the triangles that use them";
  EXPECT_NE(std::find(model.warnings.begin(), model.warnings.end(), warning), model.warnings.end())
      << ::testing::PrintToString(model.warnings);
  // Each fault once: the zero normals are not also "not unit length".
  EXPECT_EQ(std::count_if(model.warnings.begin(), model.warnings.end(),
                          [](const std::string& w) { return w.find("not unit length") != w.npos; }),
            1);
  // An error in strict import, as OBJ's warning is.
  ImportOptions strict;
  strict.strict = true;
  EXPECT_NE(import_error(path, strict).find("zero vector, which has no direction"),
            std::string::npos);
}

// A valid file that places no meshes (SceneWithoutNodes: a scene without nodes) drew nothing
// without a word, where a scene file's model that no object places is warned about.
TEST(GltfImport, ModelThatPlacesNothingIsWarnedAbout) {
  const std::string path = kModels + "TestNoRootNode/SceneWithoutNodes.gltf";
  const ImportedModel model = import_gltf(path);
  EXPECT_TRUE(model.scene.objects.empty());
  EXPECT_EQ(model.warnings, std::vector<std::string>{
                                path + ": scenes[0]: has no nodes, so the model places nothing and "
                                       "draws nothing"});
  // A file of lights alone places something.
  EXPECT_TRUE(import_gltf(kData + "/lamp.gltf").warnings.empty());
}

// Each tests/data/bad/NAME.gltf must fail with the text of NAME.expected in its message.
TEST(GltfImport, HandMadeBadFilesGiveTheirExpectedErrors) {
  EXPECT_GE(testing::expect_bad_corpus(kData + "/bad", "", ".gltf",
                                       [](const std::string& path) { return import_error(path); }),
            20);
  // .glb files that are not binary glTF: said so, not reported as JSON (a fresh user's trial).
  EXPECT_GE(testing::expect_bad_corpus(kData + "/bad", "", ".glb",
                                       [](const std::string& path) { return import_error(path); }),
            2);
}

TEST(GltfImport, PointsAndLinesAreRefusedByName) {
  const char* modes[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
  for (int m : {0, 1, 2, 3, 7, 8, 9, 10}) {
    char name[64];
    std::snprintf(name, sizeof name, "Mesh_PrimitiveMode_%02d.gltf", m);
    EXPECT_IMPORT_ERROR(kModels + "glTF-Asset-Generator/Mesh_PrimitiveMode/" + name,
                        "meshes[0].primitives[0].mode", modes[m % 7]);
  }
}

TEST(GltfImport, LimitsAreEnforced) {
  ImportOptions small_files;
  small_files.max_file_bytes = 1000;
  const std::string glb = kModels + "BoxTextured-glTF-Binary/BoxTextured.glb";
  EXPECT_NE(import_error(glb, small_files).find("over the limit of 1000"), std::string::npos);
  ImportOptions small_textures;
  small_textures.max_texture_side = 128;
  EXPECT_NE(import_error(glb, small_textures).find("images[0]: is 211x211, over the largest"),
            std::string::npos)
      << import_error(glb, small_textures);
  // A .glb cut short.
  std::ifstream in(glb, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = ::testing::TempDir() + "truncated.glb";
  std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() - 100));
  EXPECT_NE(import_error(cut).find("truncated"), std::string::npos) << import_error(cut);
  // The .gltf form's sampler wraps with MIRRORED_REPEAT (wrapS 33648) and CLAMP_TO_EDGE
  // (wrapT 33071), the .glb form's repeats: both are supported, so strict import passes.
  ImportOptions strict;
  strict.strict = true;
  const std::string gltf = kModels + "BoxTextured-glTF/BoxTextured.gltf";
  EXPECT_EQ(import_error(gltf, strict), "");
  EXPECT_EQ(import_error(glb, strict), "");
  const Texture mirrored =
      import_gltf(gltf).scene.textures.at(0);  // a copy: the model is a temporary
  EXPECT_EQ(mirrored.wrap_u, TextureWrap::mirrored_repeat);
  EXPECT_EQ(mirrored.wrap_v, TextureWrap::clamp_to_edge);
  const Texture repeating = import_gltf(glb).scene.textures.at(0);
  EXPECT_EQ(repeating.wrap_u, TextureWrap::repeat);
  EXPECT_EQ(repeating.wrap_v, TextureWrap::repeat);
}

// An image file that does not decode is named by its file as well as its glTF place (a fresh
// user's trial: "images[0]: cannot be decoded" said which image, not which file).
TEST(GltfImport, AnImageThatDoesNotDecodeNamesItsFile) {
  namespace fs = std::filesystem;
  const fs::path folder = fs::path(test::output_path("x")).parent_path() / "undecodable";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const fs::path source = kModels + "BoxTextured-glTF";
  fs::copy_file(source / "BoxTextured.gltf", folder / "BoxTextured.gltf");
  fs::copy_file(source / "BoxTextured0.bin", folder / "BoxTextured0.bin");
  std::ofstream(folder / "CesiumLogoFlat.png") << "not an image at all";
  const std::string error = import_error((folder / "BoxTextured.gltf").string());
  EXPECT_NE(error.find("images[0]: 'CesiumLogoFlat.png' cannot be decoded: "), std::string::npos)
      << error;
}

void world_bounds(const Scene& s, glm::vec3& lo, glm::vec3& hi) {
  lo = glm::vec3(INFINITY);
  hi = glm::vec3(-INFINITY);
  for (const Object& o : s.objects) {
    for (const glm::vec3& p : s.meshes[o.mesh].positions) {
      const glm::vec3 w(o.transform * glm::vec4(p, 1.0f));
      lo = glm::min(lo, w);
      hi = glm::max(hi, w);
    }
  }
}

size_t triangles(const Scene& s) {
  size_t n = 0;
  for (const Object& o : s.objects) n += s.meshes[o.mesh].triangle_count();
  return n;
}

// import_gltf_bytes (the fuzzer's entry point): a .gltf's text and a .glb from memory, external
// files found through base_dir, give the file's scene; messages name the given name.
// Warnings and the first error come in the order of the node walk, whether the walk or a
// primitive's conversion gives them. A file of three nodes:
// a triangle with COLOR_0 (a conversion warns), a node with a skin (the walk warns), another
// triangle with COLOR_0; `first` and `last` replace the first and last node's mesh.
std::vector<unsigned char> ordered_messages_file(const std::string& first,
                                                 const std::string& last) {
  // Two buffers of a triangle's POSITION then COLOR_0 (9 floats each, base64): the second's
  // first coordinate is NaN.
  const std::string good =
      "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAA"
      "AIA/";
  const std::string nan =
      "AADAfwAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAA"
      "AIA/";
  const std::string text = R"({"asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0, 1, 2]}],
    "nodes": [{"mesh": )" + first +
                           R"(}, {"skin": 0}, {"mesh": )" + last + R"(}],
    "skins": [{"joints": [1]}],
    "meshes": [
      {"primitives": [{"attributes": {"POSITION": 0, "COLOR_0": 1}}]},
      {"primitives": [{"attributes": {"POSITION": 2, "COLOR_0": 3}}]},
      {"primitives": [{"attributes": {"POSITION": 4, "COLOR_0": 5}}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
       "min": [0, 0, 0], "max": [1, 1, 0]},
      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
       "min": [0, 0, 0], "max": [1, 1, 0]},
      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
      {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3"},
      {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC3"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36},
      {"buffer": 1, "byteLength": 36}, {"buffer": 1, "byteOffset": 36, "byteLength": 36}],
    "buffers": [
      {"byteLength": 72, "uri": "data:application/octet-stream;base64,)" +
                           good + R"("},
      {"byteLength": 72, "uri": "data:application/octet-stream;base64,)" +
                           nan + R"("}]})";
  return std::vector<unsigned char>(text.begin(), text.end());
}

TEST(GltfImport, MessagesComeInTheWalksOrder) {
  const auto error_of = [](const std::vector<unsigned char>& bytes) -> std::string {
    try {
      import_gltf_bytes(bytes, "ordered.gltf", "/nonexistent");
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  const ImportedModel m =
      import_gltf_bytes(ordered_messages_file("0", "1"), "ordered.gltf", "/nonexistent");
  EXPECT_EQ(m.scene.meshes.size(), 2u);
  EXPECT_EQ(m.warnings,
            (std::vector<std::string>{
                "ordered.gltf: meshes[0].primitives[0].attributes.COLOR_0: is ignored (no "
                "vertex colours or skinning in Tessera)",
                "ordered.gltf: nodes[1].skin: skins are ignored (bind pose)",
                "ordered.gltf: meshes[1].primitives[0].attributes.COLOR_0: is ignored (no "
                "vertex colours or skinning in Tessera)"}));
  // The NaN triangle first: its error, although the walk fails later at the last node.
  EXPECT_EQ(error_of(ordered_messages_file("2", "7")),
            "ordered.gltf: meshes[2].primitives[0].attributes.POSITION: element 0 has a NaN or "
            "infinite component");
  // The walk failing first: its error, although the NaN triangle comes later.
  EXPECT_EQ(error_of(ordered_messages_file("7", "2")),
            "ordered.gltf: nodes[0].mesh: refers to meshes[7], but the file has 3 meshes");
}

TEST(GltfImport, FromMemoryGivesTheFilesScene) {
  const auto bytes_of = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
  };
  for (const char* file :
       {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb"}) {
    const std::string path = kModels + file;
    const ImportedModel from_file = import_gltf(path);
    const ImportedModel from_memory = import_gltf_bytes(
        bytes_of(path), "memory box", std::filesystem::path(path).parent_path().string());
    ASSERT_EQ(from_memory.scene.meshes.size(), 1u) << file;
    EXPECT_EQ(from_memory.scene.meshes[0].positions, from_file.scene.meshes[0].positions);
    EXPECT_EQ(from_memory.scene.meshes[0].indices, from_file.scene.meshes[0].indices);
    ASSERT_EQ(from_memory.scene.textures.size(), 1u) << file;
    EXPECT_EQ(from_memory.scene.textures[0].width, 211u);
  }
  // The .gltf's BoxTextured0.bin is not in /nonexistent; the size limit holds as for files.
  const std::vector<unsigned char> text = bytes_of(kModels + "BoxTextured-glTF/BoxTextured.gltf");
  for (uint64_t limit : {uint64_t(1) << 30, uint64_t(1000)}) {
    ImportOptions options;
    options.max_file_bytes = limit;
    try {
      import_gltf_bytes(text, "memory box", "/nonexistent", options);
      ADD_FAILURE() << "imported without its buffer, limit " << limit;
    } catch (const Error& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("memory box: ", 0), 0u) << m;
      EXPECT_NE(m.find(limit == 1000 ? "over the limit of 1000" : "/nonexistent/BoxTextured0.bin"),
                std::string::npos)
          << m;
    }
  }
}

// A rotation far from unit length is normalized with a warning (an error when strict); glTF
// asks for unit quaternions (5.25, node.rotation), and writers' rounding stays within 1e-3.
TEST(GltfImport, NonUnitQuaternionIsNormalizedWithAWarning) {
  std::ifstream in(kData + "/bad/zero_quaternion.gltf");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const std::string last = "0,\n    0\n   ]";  // the rotation's last two numbers
  const size_t at = text.find(last);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, last.size(), "0,\n    2\n   ]");  // (0, 0, 0, 2): the identity, too long
  const std::vector<unsigned char> bytes(text.begin(), text.end());
  const ImportedModel m = import_gltf_bytes(bytes, "q.gltf", "/nonexistent");
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_EQ(m.warnings[0],
            "q.gltf: nodes[0].rotation: is not a unit quaternion (its length is 2.000000); it is "
            "normalized");
  EXPECT_EQ(m.scene.objects.at(0).transform, glm::mat4(1.0f));
  ImportOptions strict;
  strict.strict = true;
  EXPECT_THROW(import_gltf_bytes(bytes, "q.gltf", "/nonexistent", strict), Error);
}

// A binary glTF (specification 4.4) of `json` and a BIN chunk of `bin`, each padded to 4 bytes.
std::vector<unsigned char> glb_of(std::string json, std::vector<unsigned char> bin) {
  while (json.size() % 4 != 0) json += ' ';
  while (bin.size() % 4 != 0) bin.push_back(0);
  std::vector<unsigned char> out;
  const auto u32 = [&](uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
  };
  u32(0x46546C67u);  // "glTF"
  u32(2);
  u32(uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  u32(uint32_t(json.size()));
  u32(0x4E4F534Au);  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  u32(uint32_t(bin.size()));
  u32(0x004E4942u);  // "BIN\0"
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

std::string base64(const std::vector<unsigned char>& bytes) {
  const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= bytes[i + 2];
    for (size_t k = 0; k < 4; ++k)
      out += i + k <= bytes.size() ? digits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// One triangle: POSITION (36 bytes) then 16-bit indices (6 bytes) in buffers[0], whose
// `buffer` text (byteLength, and uri if any) is given; `views` are the two buffer views.
std::string triangle_document(const std::string& buffer, const std::string& views) {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "buffers": [)" +
         buffer + R"(],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
       "min": [0, 0, 0], "max": [1, 1, 0]},
      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    "bufferViews": [)" +
         views + "]}";
}

std::vector<unsigned char> triangle_bytes() {
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint16_t indices[3] = {0, 1, 2};
  std::vector<unsigned char> bin(42);
  std::memcpy(bin.data(), positions, 36);
  std::memcpy(bin.data() + 36, indices, 6);
  return bin;
}

// A .glb's buffers[0] is read where it lies in the BIN chunk, not copied by TinyGLTF (which is
// given a stand-in of one byte): the scene is that of the same buffer as a data uri, and range
// checks and messages use the buffer's real size.
TEST(GltfImport, GlbBufferReadInTheFileGivesTheEmbeddedScene) {
  const std::string views =
      R"({"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6})";
  const std::vector<unsigned char> bin = triangle_bytes();
  const ImportedModel embedded = import_gltf_bytes(
      [&] {
        const std::string text = triangle_document(
            R"({"byteLength": 42, "uri": "data:application/octet-stream;base64,)" + base64(bin) +
                R"("})",
            views);
        return std::vector<unsigned char>(text.begin(), text.end());
      }(),
      "embedded.gltf", "/nonexistent");
  // The byteLength's text as writers give it, with space around it, and members after it.
  for (const char* buffer : {R"({"byteLength": 42})", R"({ "byteLength" :   42 , "name": "b" })",
                             R"({"name": "b", "byteLength":42})"}) {
    const ImportedModel glb =
        import_gltf_bytes(glb_of(triangle_document(buffer, views), bin), "t.glb", "/nonexistent");
    ASSERT_EQ(glb.scene.meshes.size(), 1u) << buffer;
    EXPECT_EQ(glb.scene.meshes[0], embedded.scene.meshes[0]) << buffer;
    EXPECT_EQ(glb.scene.meshes[0].positions[1], glm::vec3(1, 0, 0));
  }
  const auto error_of = [&](const std::string& buffer, const std::string& views) {
    try {
      import_gltf_bytes(glb_of(triangle_document(buffer, views), bin), "t.glb", "/nonexistent");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // A view past the buffer's end: measured against its 42 bytes, not the stand-in's one.
  EXPECT_EQ(error_of(R"({"byteLength": 42})",
                     R"({"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, )"
                     R"("byteLength": 12})"),
            "t.glb: bufferViews[1]: bytes 36..48 are past the end of buffers[0] (42 bytes): the "
            "buffer is truncated or the view is wrong");
  // A byteLength past the BIN chunk (44 bytes, padded): TinyGLTF is given the file and says so.
  const std::string longer = error_of(R"({"byteLength": 100})", views);
  EXPECT_EQ(longer.rfind("t.glb: TinyGLTF cannot read it: Invalid `byteLength'", 0), 0u) << longer;
  // A JSON chunk length off by 3 (a fresh user's trial got TinyGLTF's "BIN Chunk data length
  // exceeds the GLB size"): said to be misaligned.
  std::vector<unsigned char> off = glb_of(triangle_document(R"({"byteLength": 42})", views), bin);
  off[12] -= 3;
  try {
    import_gltf_bytes(off, "off.glb", "/nonexistent");
    ADD_FAILURE() << "a misaligned JSON chunk was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("off.glb: its JSON chunk's length, "), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("is not a multiple of 4"), std::string::npos) << e.what();
  }
}

// A sparse accessor's numbers that TinyGLTF holds in an int are quoted as written when over
// 2^31 - 1, at their glTF path (tests/data/bad/sparse_count_over_int.gltf has the count): the
// int would have wrapped this byteOffset to 0, and the message named what that read instead.
TEST(GltfImport, SparseNumbersOverAnIntAreQuotedAsWritten) {
  const std::string text = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "accessors": [{"componentType": 5126, "count": 3, "type": "VEC3", "sparse": {"count": 1,
      "indices": {"bufferView": 0, "byteOffset": 4294967296, "componentType": 5123},
      "values": {"bufferView": 0}}}]})";
  try {
    import_gltf_bytes(std::vector<unsigned char>(text.begin(), text.end()), "s.gltf",
                      "/nonexistent");
    ADD_FAILURE() << "imported";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "s.gltf: accessors[0].sparse.indices.byteOffset: is 4294967296, above 2147483647 "
              "(2^31 - 1), the largest Tessera reads here (TinyGLTF holds it in a 32-bit int)");
  }
}

// The Error message of importing the JSON document `doc` as NAME, or "no error".
std::string document_error(const nlohmann::json& doc, const std::string& name) {
  const std::string text = doc.dump();
  try {
    import_gltf_bytes(std::vector<unsigned char>(text.begin(), text.end()), name, "/nonexistent");
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

// Every index of glTF 2.0 (each glTFid of its schema, and KHR_lights_punctual's light) and every
// other integer that TinyGLTF reads into an int is refused over 2^31 - 1, quoted as written at
// its glTF path: TinyGLTF's int wraps 4294967296 (2^32) to 0, a valid index, and a POSITION of
// 4294967296 imported accessors[0]. A negative one is refused by its type.
TEST(GltfImport, IndicesOverAnIntAreQuotedAsWritten) {
  const nlohmann::json base = nlohmann::json::parse(triangle_document(
      R"({"byteLength": 42, "uri": "data:application/octet-stream;base64,)" +
          base64(triangle_bytes()) + R"("})",
      R"({"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6})"));
  ASSERT_EQ(document_error(base, "i.gltf"), "no error");
  // (JSON pointer, glTF path); absent objects and arrays on the way are created.
  const std::pair<const char*, std::string> cases[] = {
      {"/scene", "scene"},
      {"/scenes/0/nodes/0", "scenes[0].nodes[0]"},
      {"/nodes/0/mesh", "nodes[0].mesh"},
      {"/nodes/0/children/0", "nodes[0].children[0]"},
      {"/nodes/0/camera", "nodes[0].camera"},
      {"/nodes/0/skin", "nodes[0].skin"},
      {"/nodes/0/extensions/KHR_lights_punctual/light",
       "nodes[0].extensions.KHR_lights_punctual.light"},
      {"/meshes/0/primitives/0/attributes/POSITION", "meshes[0].primitives[0].attributes.POSITION"},
      {"/meshes/0/primitives/0/attributes/TEXCOORD_0",
       "meshes[0].primitives[0].attributes.TEXCOORD_0"},
      {"/meshes/0/primitives/0/indices", "meshes[0].primitives[0].indices"},
      {"/meshes/0/primitives/0/material", "meshes[0].primitives[0].material"},
      {"/meshes/0/primitives/0/mode", "meshes[0].primitives[0].mode"},
      {"/meshes/0/primitives/0/targets/0/POSITION", "meshes[0].primitives[0].targets[0].POSITION"},
      {"/accessors/0/bufferView", "accessors[0].bufferView"},
      {"/accessors/0/sparse/indices/bufferView", "accessors[0].sparse.indices.bufferView"},
      {"/accessors/0/sparse/values/bufferView", "accessors[0].sparse.values.bufferView"},
      {"/bufferViews/0/buffer", "bufferViews[0].buffer"},
      {"/bufferViews/0/target", "bufferViews[0].target"},
      {"/materials/0/pbrMetallicRoughness/baseColorTexture/index",
       "materials[0].pbrMetallicRoughness.baseColorTexture.index"},
      {"/materials/0/pbrMetallicRoughness/metallicRoughnessTexture/index",
       "materials[0].pbrMetallicRoughness.metallicRoughnessTexture.index"},
      {"/materials/0/normalTexture/index", "materials[0].normalTexture.index"},
      {"/materials/0/occlusionTexture/index", "materials[0].occlusionTexture.index"},
      {"/materials/0/emissiveTexture/index", "materials[0].emissiveTexture.index"},
      {"/materials/0/emissiveTexture/texCoord", "materials[0].emissiveTexture.texCoord"},
      {"/materials/0/emissiveTexture/extensions/KHR_texture_transform/texCoord",
       "materials[0].emissiveTexture.extensions.KHR_texture_transform.texCoord"},
      {"/textures/0/sampler", "textures[0].sampler"},
      {"/textures/0/source", "textures[0].source"},
      {"/images/0/bufferView", "images[0].bufferView"},
      {"/samplers/0/magFilter", "samplers[0].magFilter"},
      {"/samplers/0/minFilter", "samplers[0].minFilter"},
      {"/samplers/0/wrapS", "samplers[0].wrapS"},
      {"/samplers/0/wrapT", "samplers[0].wrapT"},
      {"/skins/0/inverseBindMatrices", "skins[0].inverseBindMatrices"},
      {"/skins/0/skeleton", "skins[0].skeleton"},
      {"/skins/0/joints/0", "skins[0].joints[0]"},
      {"/animations/0/channels/0/sampler", "animations[0].channels[0].sampler"},
      {"/animations/0/channels/0/target/node", "animations[0].channels[0].target.node"},
      {"/animations/0/samplers/0/input", "animations[0].samplers[0].input"},
      {"/animations/0/samplers/0/output", "animations[0].samplers[0].output"},
  };
  for (const auto& [pointer, path] : cases) {
    nlohmann::json doc = base;
    doc[nlohmann::json::json_pointer(pointer)] = uint64_t(1) << 32;
    EXPECT_EQ(document_error(doc, "i.gltf"),
              "i.gltf: " + path +
                  ": is 4294967296, above 2147483647 (2^31 - 1), the largest Tessera reads here "
                  "(TinyGLTF holds it in a 32-bit int)");
    doc[nlohmann::json::json_pointer(pointer)] = -1;
    const std::string negative = document_error(doc, "i.gltf");
    EXPECT_TRUE(negative.starts_with("i.gltf: " + path + ": must be ") &&
                negative.ends_with(" (found a negative integer)"))
        << negative;
  }
  // 2^31 - 1 itself is read (and is then past the file's arrays).
  nlohmann::json largest = base;
  largest["nodes"][0]["mesh"] = INT32_MAX;
  EXPECT_EQ(document_error(largest, "i.gltf"),
            "i.gltf: nodes[0].mesh: refers to meshes[2147483647], but the file has 1 meshes");
}

// One triangle whose POSITION (accessors[0]) and NORMAL (accessors[1]) are stored with the given
// componentType, 12 bytes apart each: positions (0, 0, 0), (32767, 0, 0), (0, -32768, 16384) as
// SHORT (the same bits as UNSIGNED_SHORT), else (0, 0, 0), (1, 0, 0), (0, 1, 0); normals
// (127, 0, 0), (0, -128, 0), (0, 0, 127) as BYTE, else the unit axes. `extension` lists
// KHR_mesh_quantization in extensionsUsed and extensionsRequired.
std::vector<unsigned char> quantized_triangle(int position_type, bool position_normalized,
                                              int normal_type, bool normal_normalized,
                                              bool extension) {
  std::vector<unsigned char> bin(72, 0);
  for (int v = 0; v < 3; ++v) {
    for (int c = 0; c < 3; ++c) {
      unsigned char* p =
          &bin[size_t(12 * v + (position_type == 5122 || position_type == 5123 ? 2 * c : 4 * c))];
      const int16_t shorts[3][3] = {{0, 0, 0}, {32767, 0, 0}, {0, -32768, 16384}};
      const float unit = v == c + 1 ? 1.0f : 0.0f;  // (1, 0, 0) and (0, 1, 0)
      const uint32_t whole = uint32_t(unit);
      if (position_type == 5122 || position_type == 5123) std::memcpy(p, &shorts[v][c], 2);
      if (position_type == 5126) std::memcpy(p, &unit, 4);
      if (position_type == 5125) std::memcpy(p, &whole, 4);
      unsigned char* n = &bin[size_t(36 + 12 * v + (normal_type == 5120 ? c : 4 * c))];
      const int8_t bytes[3][3] = {{127, 0, 0}, {0, -128, 0}, {0, 0, 127}};
      const float axis = v == c ? (v == 1 ? -1.0f : 1.0f) : 0.0f;
      if (normal_type == 5120) std::memcpy(n, &bytes[v][c], 1);
      if (normal_type == 5126) std::memcpy(n, &axis, 4);
    }
  }
  const auto normalized = [](bool n) { return n ? "true" : "false"; };
  const std::string extensions = extension ? R"("extensionsUsed": ["KHR_mesh_quantization"],
      "extensionsRequired": ["KHR_mesh_quantization"],)"
                                           : "";
  const std::string text = R"({"asset": {"version": "2.0"}, )" + extensions +
                           R"( "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}],
    "accessors": [
      {"bufferView": 0, "componentType": )" +
                           std::to_string(position_type) + R"(, "normalized": )" +
                           normalized(position_normalized) + R"(, "count": 3, "type": "VEC3"},
      {"bufferView": 1, "componentType": )" +
                           std::to_string(normal_type) + R"(, "normalized": )" +
                           normalized(normal_normalized) + R"(, "count": 3, "type": "VEC3"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36, "byteStride": 12},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 36, "byteStride": 12}],
    "buffers": [{"byteLength": 72, "uri": "data:application/octet-stream;base64,)" +
                           base64(bin) + R"("}]})";
  return std::vector<unsigned char>(text.begin(), text.end());
}

// glTF 2.0 allows only FLOAT POSITION, NORMAL and TANGENT (3.7.2.1); KHR_mesh_quantization adds
// integer positions and normalized BYTE and SHORT normals and tangents. A file that lists the
// extension imports with integers mapped as the specification maps them (3.11: normalized
// SHORT c / 32767 and BYTE c / 127, at least -1); one that does not is refused by path.
TEST(GltfImport, QuantizedAttributesNeedKhrMeshQuantization) {
  const auto error_of = [](const std::vector<unsigned char>& bytes) {
    try {
      import_gltf_bytes(bytes, "q.gltf", "/nonexistent");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const ImportedModel m =
      import_gltf_bytes(quantized_triangle(5122, true, 5120, true, true), "q.gltf", "/nonexistent");
  EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
  const Mesh& mesh = m.scene.meshes.at(0);
  ASSERT_EQ(mesh.positions.size(), 3u);
  EXPECT_EQ(mesh.positions[1], glm::vec3(1, 0, 0));
  EXPECT_EQ(mesh.positions[2], glm::vec3(0, -1, float(16384.0 / 32767.0)));
  EXPECT_EQ(mesh.normals[0], glm::vec3(1, 0, 0));
  EXPECT_EQ(mesh.normals[1], glm::vec3(0, -1, 0));
  EXPECT_EQ(mesh.normals[2], glm::vec3(0, 0, 1));
  // Not normalized, the integers themselves (a node's scale would bring them to size).
  const ImportedModel raw = import_gltf_bytes(quantized_triangle(5123, false, 5120, true, true),
                                              "q.gltf", "/nonexistent");
  EXPECT_EQ(raw.scene.meshes.at(0).positions[2], glm::vec3(0, 32768, 16384));
  // Without the extension.
  const std::string rule =
      " (3.7.2.1) unless the file lists KHR_mesh_quantization in "
      "extensionsUsed, which it does not";
  EXPECT_EQ(error_of(quantized_triangle(5122, true, 5120, true, false)),
            "q.gltf: meshes[0].primitives[0].attributes.POSITION: is accessors[0], of "
            "componentType 5122 (SHORT, normalized); glTF 2.0 allows only FLOAT (5126) for "
            "POSITION" +
                rule);
  EXPECT_EQ(error_of(quantized_triangle(5126, false, 5120, true, false)),
            "q.gltf: meshes[0].primitives[0].attributes.NORMAL: is accessors[1], of "
            "componentType 5120 (BYTE, normalized); glTF 2.0 allows only FLOAT (5126) for NORMAL" +
                rule);
  EXPECT_EQ(error_of(quantized_triangle(5126, false, 5126, false, false)), "no error");
  // With it, types the extension does not list either.
  EXPECT_EQ(error_of(quantized_triangle(5125, false, 5120, true, true)),
            "q.gltf: meshes[0].primitives[0].attributes.POSITION: is accessors[0], of "
            "componentType 5125 (UNSIGNED_INT); KHR_mesh_quantization allows FLOAT, BYTE, "
            "UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT for POSITION");
  EXPECT_EQ(error_of(quantized_triangle(5126, false, 5120, false, true)),
            "q.gltf: meshes[0].primitives[0].attributes.NORMAL: is accessors[1], of "
            "componentType 5120 (BYTE); KHR_mesh_quantization allows FLOAT or normalized BYTE or "
            "SHORT for NORMAL");
}

// The triangle of triangle_bytes, unlit (flat normals, its vertices in order), with a TEXCOORD_0
// (accessors[2], in buffers[1]) of componentType `type` holding the six components `uv`, each
// vertex's two at a 4-byte aligned stride (3.6.2.4); `extension` lists KHR_mesh_quantization.
nlohmann::json uv_triangle(int type, bool normalized, const std::vector<int64_t>& uv,
                           bool extension) {
  nlohmann::json doc = nlohmann::json::parse(triangle_document(
      R"({"byteLength": 42, "uri": "data:application/octet-stream;base64,)" +
          base64(triangle_bytes()) + R"("})",
      R"({"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6})"));
  const size_t size = type == 5120 || type == 5121 ? 1 : type == 5122 || type == 5123 ? 2 : 4;
  const size_t stride = std::max<size_t>(4, 2 * size);
  std::vector<unsigned char> bytes(3 * stride, 0);
  for (size_t i = 0; i < 6; ++i) {
    const uint32_t bits = uint32_t(uv[i]);  // two's complement: its low bytes are the value's
    std::memcpy(&bytes[i / 2 * stride + i % 2 * size], &bits, size);
  }
  doc["buffers"].push_back({{"byteLength", bytes.size()},
                            {"uri", "data:application/octet-stream;base64," + base64(bytes)}});
  doc["bufferViews"].push_back(
      {{"buffer", 1}, {"byteLength", bytes.size()}, {"byteStride", stride}});
  doc["accessors"].push_back({{"bufferView", 2},
                              {"componentType", type},
                              {"normalized", normalized},
                              {"count", 3},
                              {"type", "VEC2"}});
  doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2;
  if (extension) doc["extensionsUsed"] = {"KHR_mesh_quantization"};
  return doc;
}

// TEXCOORD_n may be FLOAT, normalized UNSIGNED_BYTE or normalized UNSIGNED_SHORT (glTF 2.0
// 3.7.2.1), read as c / 255 and c / 65535 (3.11); KHR_mesh_quantization adds BYTE, UNSIGNED_BYTE,
// SHORT and UNSIGNED_SHORT, normalized or not (normalized BYTE max(c / 127, -1), the others the
// integers they are). Any other is refused naming the attribute, as POSITION's is.
TEST(GltfImport, TexcoordComponentTypesAreTheSpecificationsAndReadAsItMapsThem) {
  const auto uvs = [](const nlohmann::json& doc) {
    const std::string text = doc.dump();
    const ImportedModel m =
        import_gltf_bytes(std::vector<unsigned char>(text.begin(), text.end()), "t.gltf", "/none");
    EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
    return m.scene.meshes.at(0).uvs;
  };
  using uv = glm::vec2;
  EXPECT_EQ(uvs(uv_triangle(5121, true, {0, 255, 51, 128, 255, 1}, false)),
            (std::vector<uv>{{0, 1}, {0.2f, float(128.0 / 255.0)}, {1, float(1.0 / 255.0)}}));
  EXPECT_EQ(uvs(uv_triangle(5123, true, {0, 65535, 13107, 32768, 65535, 1}, false)),
            (std::vector<uv>{{0, 1}, {0.2f, float(32768.0 / 65535.0)}, {1, float(1.0 / 65535.0)}}));
  EXPECT_EQ(uvs(uv_triangle(5120, true, {-128, 127, -127, 0, 64, 1}, true)),
            (std::vector<uv>{{-1, 1}, {-1, 0}, {float(64.0 / 127.0), float(1.0 / 127.0)}}));
  EXPECT_EQ(uvs(uv_triangle(5123, false, {0, 1, 2, 3, 4, 5}, true)),
            (std::vector<uv>{{0, 1}, {2, 3}, {4, 5}}));
  const std::string is =
      "t.gltf: meshes[0].primitives[0].attributes.TEXCOORD_0: is accessors[2], "
      "of componentType ";
  const std::string core =
      "; glTF 2.0 allows only FLOAT (5126), normalized UNSIGNED_BYTE (5121) or normalized "
      "UNSIGNED_SHORT (5123) for TEXCOORD_0 (3.7.2.1) unless the file lists KHR_mesh_quantization "
      "in extensionsUsed, which it does not";
  EXPECT_EQ(document_error(uv_triangle(5120, true, {0, 0, 0, 0, 0, 0}, false), "t.gltf"),
            is + "5120 (BYTE, normalized)" + core);
  EXPECT_EQ(document_error(uv_triangle(5121, false, {0, 0, 0, 0, 0, 0}, false), "t.gltf"),
            is + "5121 (UNSIGNED_BYTE)" + core);
  EXPECT_EQ(document_error(uv_triangle(5122, false, {0, 0, 0, 0, 0, 0}, false), "t.gltf"),
            is + "5122 (SHORT)" + core);
  EXPECT_EQ(document_error(uv_triangle(5125, false, {0, 0, 0, 0, 0, 0}, true), "t.gltf"),
            is + "5125 (UNSIGNED_INT); KHR_mesh_quantization allows FLOAT, BYTE, UNSIGNED_BYTE, "
                 "SHORT or UNSIGNED_SHORT for TEXCOORD_0");
  // TEXCOORD_1, read where a texture uses it (tests/data/texcoord1.gltf: base colour), likewise.
  std::ifstream in(kData + "/texcoord1.gltf");
  nlohmann::json two_sets = nlohmann::json::parse(in);
  two_sets["accessors"][3]["componentType"] = 5122;
  two_sets["accessors"][3]["normalized"] = true;
  EXPECT_EQ(document_error(two_sets, "t.gltf"),
            "t.gltf: meshes[0].primitives[0].attributes.TEXCOORD_1: is accessors[3], of "
            "componentType 5122 (SHORT, normalized); glTF 2.0 allows only FLOAT (5126), normalized "
            "UNSIGNED_BYTE (5121) or normalized UNSIGNED_SHORT (5123) for TEXCOORD_1 (3.7.2.1) "
            "unless the file lists KHR_mesh_quantization in extensionsUsed, which it does not");
}

// The triangle of triangle_bytes, embedded, placed by `node` (nodes[0]).
std::vector<unsigned char> placed_triangle(const std::string& node) {
  std::string text = triangle_document(
      R"({"byteLength": 42, "uri": "data:application/octet-stream;base64,)" +
          base64(triangle_bytes()) + R"("})",
      R"({"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6})");
  const std::string nodes = R"("nodes": [{"mesh": 0}])";
  text.replace(text.find(nodes), nodes.size(), R"("nodes": [)" + node + "]");
  return std::vector<unsigned char>(text.begin(), text.end());
}

// A scale of 0, which Tessera's scene files refuse, is valid glTF (3.5.3: a scale of 0 on every
// axis hides a node): imported as written, with the scene files' words as a warning, and an
// error in strict import. A matrix that flattens (determinant 0) likewise.
TEST(GltfImport, ZeroScaleIsImportedAsWrittenWithAWarning) {
  const std::string drawn =
      "imported as written, as glTF 2.0 allows (3.5.3): drawn flat, or not at all where every "
      "axis is 0";
  const std::string flattens = "flat.gltf: nodes[0].scale: a scale of 0 flattens the object; ";
  const ImportedModel flat = import_gltf_bytes(
      placed_triangle(R"({"mesh": 0, "scale": [1, 0, 1]})"), "flat.gltf", "/nonexistent");
  EXPECT_EQ(flat.warnings, std::vector<std::string>{flattens + drawn});
  EXPECT_EQ(flat.scene.objects.at(0).transform,
            glm::mat4(1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1));
  const ImportedModel hidden = import_gltf_bytes(
      placed_triangle(R"({"mesh": 0, "scale": [0, 0, 0]})"), "flat.gltf", "/nonexistent");
  EXPECT_EQ(hidden.warnings, std::vector<std::string>{flattens + drawn});
  EXPECT_EQ(glm::mat3(hidden.scene.objects.at(0).transform), glm::mat3(0.0f));
  const ImportedModel matrix = import_gltf_bytes(
      placed_triangle(R"({"mesh": 0, "matrix": [1,0,0,0, 0,0,0,0, 0,0,1,0, 0,0,0,1]})"),
      "flat.gltf", "/nonexistent");
  EXPECT_EQ(matrix.warnings,
            std::vector<std::string>{"flat.gltf: nodes[0].matrix: flattens the object (its upper "
                                     "3x3 part has determinant 0); " +
                                     drawn});
  // A small scale is not 0.
  EXPECT_TRUE(import_gltf_bytes(placed_triangle(R"({"mesh": 0, "scale": [1, 1e-30, 1]})"),
                                "flat.gltf", "/nonexistent")
                  .warnings.empty());
  ImportOptions strict;
  strict.strict = true;
  try {
    import_gltf_bytes(placed_triangle(R"({"mesh": 0, "scale": [1, 0, 1]})"), "flat.gltf",
                      "/nonexistent", strict);
    ADD_FAILURE() << "a scale of 0 was imported in strict import";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), flattens + drawn + " (an error in strict import)");
  }
}

TEST(GltfImport, BoxTexturedAllThreeFormsGiveTheSameScene) {
  const ImportedModel gltf = import_gltf(kModels + "BoxTextured-glTF/BoxTextured.gltf");
  const ImportedModel glb = import_gltf(kModels + "BoxTextured-glTF-Binary/BoxTextured.glb");
  const ImportedModel embedded =
      import_gltf(kModels + "BoxTextured-glTF-Embedded/BoxTextured.gltf");
  // From the JSON: 36 indices (12 triangles), 24 vertices in [-0.5, 0.5]^3, node 0's matrix
  // (columns (1,0,0), (0,0,-1), (0,1,0)) over the mesh's node, one 211x211 texture
  // (CesiumLogoFlat.png).
  const Scene& s = gltf.scene;
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(triangles(s), 12u);
  EXPECT_EQ(s.meshes[0].positions.size(), 24u);
  const glm::mat4 expected(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1);
  EXPECT_EQ(s.objects[0].transform, expected);
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].width, 211u);
  EXPECT_TRUE(s.textures[0].srgb);
  EXPECT_EQ(s.materials[0].base_color_map, 0u);
  EXPECT_EQ(s.materials[0].metallic, 0.0f);  // metallicFactor 0, roughness default 1
  EXPECT_EQ(s.materials[0].roughness, 1.0f);
  glm::vec3 lo, hi;
  world_bounds(s, lo, hi);
  EXPECT_EQ(lo, glm::vec3(-0.5f));
  EXPECT_EQ(hi, glm::vec3(0.5f));
  for (const ImportedModel* other : {&glb, &embedded}) {
    const Scene& o = other->scene;
    ASSERT_EQ(o.meshes.size(), 1u);
    EXPECT_EQ(o.meshes[0].positions, s.meshes[0].positions);
    EXPECT_EQ(o.meshes[0].normals, s.meshes[0].normals);
    EXPECT_EQ(o.meshes[0].uvs, s.meshes[0].uvs);
    EXPECT_EQ(o.meshes[0].indices, s.meshes[0].indices);
    EXPECT_EQ(o.objects[0].transform, s.objects[0].transform);
    EXPECT_EQ(o.textures[0].texels, s.textures[0].texels);
  }
}

TEST(GltfImport, EngineCountsAndADeepNodesWorldTransform) {
  const ImportedModel m = import_gltf(kModels + "2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  // From the JSON: 67 mesh instances with 115 primitives in all, 121496 triangles (sum of index
  // counts / 3 over instances), one perspective camera with yfov 0.3143463730812073.
  EXPECT_EQ(m.scene.objects.size(), 115u);
  EXPECT_EQ(triangles(m.scene), 121496u);
  ASSERT_EQ(m.cameras.size(), 1u);
  EXPECT_FLOAT_EQ(m.cameras[0].vertical_fov, 0.3143463730812073f);
  // nodes[17] (mesh 6) hangs under 16 <- 15 <- 14 <- 13 <- 0; 16, 13 and 0 have no transform.
  const double n14[] = {-2.430540746445331e-07,
                        1.4087579529586947e-06,
                        -1.0,
                        0.0,
                        -1.0,
                        -2.430540746445331e-07,
                        2.4305373358401994e-07,
                        0.0,
                        -2.4305373358401994e-07,
                        1.0,
                        1.4087580666455324e-06,
                        0.0,
                        -48.26182556152344,
                        -59.11042404174805,
                        34.595985412597656,
                        1.0};
  const double n15[] = {-0.45468202233314514, 0.6541662216186523, -0.6044260263442993, 0.0,
                        0.8696397542953491,   0.4726206660270691, -0.1426759660243988, 0.0,
                        0.19233042001724243,  -0.590505063533783, -0.7837810516357422, 0.0,
                        14.898193359375,      85.82951354980469,  -48.034645080566406, 1.0};
  const double n17[] = {0.8450329899787903,  0.005398945417255163, -0.5346869230270386, 0.0,
                        -0.4710906744003296, 0.4805830717086792,   -0.7396712303161621, 0.0,
                        0.25296804308891296, 0.8769326210021973,   0.4086519181728363,  0.0,
                        -74.0894775390625,   71.41646575927734,    -157.91323852539062, 1.0};
  const glm::mat4 expected(glm::make_mat4(n14) * glm::make_mat4(n15) * glm::make_mat4(n17));
  int found = 0;
  for (const Object& o : m.scene.objects) {
    bool same = true;
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) same &= std::abs(o.transform[c][r] - expected[c][r]) < 1e-4f;
    }
    found += same;
  }
  EXPECT_GE(found, 1);
  EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
}

TEST(GltfImport, StripsFansAndIndexTypesGiveTheSameSquare) {
  // The asset generator's square: 4 vertices, 2 triangles covering it, each drawn by a different
  // mode or index component type. Every variant covers the same area: 2 triangles with normal
  // +z (flat normals where NORMAL is absent), counter-clockwise in xy.
  for (int m : {4, 5, 6, 11, 12, 13, 14, 15}) {
    char name[64];
    std::snprintf(name, sizeof name, "Mesh_PrimitiveMode_%02d.gltf", m);
    SCOPED_TRACE(name);
    const ImportedModel model =
        import_gltf(kModels + "glTF-Asset-Generator/Mesh_PrimitiveMode/" + name);
    ASSERT_EQ(model.scene.objects.size(), 1u);
    const Mesh& mesh = model.scene.meshes[model.scene.objects[0].mesh];
    ASSERT_EQ(mesh.triangle_count(), 2u);
    double area = 0.0;
    for (size_t t = 0; t < 2; ++t) {
      const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]),
          b(mesh.positions[mesh.indices[3 * t + 1]]), c(mesh.positions[mesh.indices[3 * t + 2]]);
      const glm::dvec3 n = glm::cross(b - a, c - a);
      EXPECT_GT(n.z, 0.0);  // counter-clockwise seen from +z
      area += 0.5 * glm::length(n);
    }
    EXPECT_NEAR(area, 1.0, 1e-6);  // the unit square (positions in [-0.5, 0.5]^2)
  }
}

// tests/data/texcoord1.gltf: a quad with two uv sets; base colour reads TEXCOORD_1, the
// metallic-roughness map TEXCOORD_0.
TEST(GltfImport, SecondUvSetIsReadForTheMapsThatUseIt) {
  const ImportedModel m = import_gltf(kData + "/texcoord1.gltf");
  EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
  ASSERT_EQ(m.scene.objects.size(), 1u);
  const Mesh& mesh = m.scene.meshes[m.scene.objects[0].mesh];
  ASSERT_EQ(mesh.uvs.size(), 4u);
  ASSERT_EQ(mesh.uvs1.size(), 4u);
  EXPECT_EQ(mesh.uvs[1], glm::vec2(0.25f, 0.5f));
  EXPECT_EQ(mesh.uvs1[0], glm::vec2(0.0f, 0.5f));
  EXPECT_EQ(mesh.uvs1[1], glm::vec2(1.0f, 0.5f));
  const Material& mat = m.scene.materials[m.scene.objects[0].material];
  EXPECT_EQ(mat.uv1_maps, TS_MAP_BASE_COLOR);
  EXPECT_NE(mat.metallic_roughness_map, kNoTexture);
  // Without a texture on set 1 no second set is read.
  const ImportedModel box = import_gltf(kModels + "BoxTextured-glTF-Binary/BoxTextured.glb");
  for (const Mesh& b : box.scene.meshes) EXPECT_TRUE(b.uvs1.empty());
}

// features.gltf with a normal map on its material: tangents are generated. The strip's first
// triangle, (0,0,0) (1,0,0) (0,1,0) with uvs (0,0) (1,0) (0,1) before the uv transform (which
// scales both by 2), has u growing along +x and v along +y: tangent +x, bitangent +y = cross(+z,
// +x), so w = +1. Its three flat vertices are the mesh's first three.
TEST(GltfImport, NormalMappedMaterialGetsGeneratedTangents) {
  std::ifstream in(kData + "/features.gltf");
  nlohmann::json doc = nlohmann::json::parse(in);
  doc["materials"][0]["normalTexture"] = {{"index", 0}};
  const std::string text = doc.dump();
  const ImportedModel m =
      import_gltf_bytes(std::vector<unsigned char>(text.begin(), text.end()), "features", kData);
  const Mesh& mesh = m.scene.meshes[m.scene.objects[0].mesh];
  ASSERT_EQ(mesh.tangents.size(), 6u);
  for (int v = 0; v < 3; ++v) EXPECT_EQ(mesh.tangents[v], glm::vec4(1, 0, 0, 1)) << v;
}

TEST(GltfImport, HandMadeFeaturesFile) {
  const ImportedModel m = import_gltf(kData + "/features.gltf");
  EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
  const Scene& s = m.scene;
  ASSERT_EQ(s.objects.size(), 1u);
  const Mesh& mesh = s.meshes[s.objects[0].mesh];
  // A strip of 4 vertices, no indices -> (0,1,2), (1,3,2); no NORMAL -> flat, 6 vertices. The
  // sparse accessor moves vertex 3 from (1,1,0) to (2,2,0).
  ASSERT_EQ(mesh.triangle_count(), 2u);
  ASSERT_EQ(mesh.positions.size(), 6u);
  EXPECT_EQ(mesh.positions[3], glm::vec3(1, 0, 0));
  EXPECT_EQ(mesh.positions[4], glm::vec3(2, 2, 0));
  EXPECT_EQ(mesh.positions[5], glm::vec3(0, 1, 0));
  for (const glm::vec3& n : mesh.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
  // Normalized ushort uvs (65535 -> 1) through KHR_texture_transform offset (0.5, 0), scale 2.
  EXPECT_EQ(mesh.uvs[0], glm::vec2(0.5f, 0.0f));  // vertex 0, uv (0, 0)
  EXPECT_EQ(mesh.uvs[1], glm::vec2(2.5f, 0.0f));  // vertex 1, uv (1, 0)
  EXPECT_EQ(mesh.uvs[4], glm::vec2(2.5f, 2.0f));  // vertex 3, uv (1, 1)
  // Its material has no normal map, the one reader of tangents: none are generated.
  EXPECT_TRUE(mesh.tangents.empty());
  // World = translate(1, 2, 3) * scale 2 (the child's matrix).
  const glm::mat4 world(2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1);
  EXPECT_EQ(s.objects[0].transform, world);
  glm::vec3 lo, hi;
  world_bounds(s, lo, hi);
  EXPECT_EQ(lo, glm::vec3(1, 2, 3));
  EXPECT_EQ(hi, glm::vec3(5, 6, 3));
  // Material: factors as written, emission 4 x (0.1, 0.2, 0.3) times the emissive map; base
  // colour and occlusion share a texture, but occlusion strength 0.5 gives a copy with R' = 1 + 0.5
  // (R - 1).
  const Material& mat = s.materials[s.objects[0].material];
  EXPECT_EQ(mat.base_color, glm::vec3(0.5f, 0.25f, 1.0f));
  EXPECT_FLOAT_EQ(mat.metallic, 0.3f);
  EXPECT_FLOAT_EQ(mat.roughness, 0.6f);
  EXPECT_NEAR(mat.emissive.x, 0.4f, 1e-6f);
  EXPECT_NEAR(mat.emissive.z, 1.2f, 1e-6f);
  ASSERT_EQ(s.textures.size(), 2u);
  const Texture& base = s.textures[mat.base_color_map];
  const Texture& occlusion = s.textures[mat.occlusion_map];
  EXPECT_TRUE(base.srgb);
  EXPECT_FALSE(occlusion.srgb);
  EXPECT_EQ(base.texels[0], glm::u8vec4(0, 64, 128, 255));
  EXPECT_EQ(occlusion.texels[0].r, 128);  // 255 * (1 + 0.5 * (0 - 1)) = 127.5, rounded
  EXPECT_EQ(occlusion.texels[1].r, 255);  // R = 255 stays
  // The emissive texture is the base colour's image read as sRGB: the same Scene texture.
  EXPECT_EQ(mat.emissive_map, mat.base_color_map);
  EXPECT_TRUE(mat.double_sided);
  // Camera at (0, 0, 10) looking down -z; yfov 0.5, znear 0.05.
  ASSERT_EQ(m.cameras.size(), 1u);
  EXPECT_EQ(m.cameras[0].position, glm::vec3(0, 0, 10));
  EXPECT_EQ(m.cameras[0].target, glm::vec3(0, 0, 9));
  EXPECT_FLOAT_EQ(m.cameras[0].vertical_fov, 0.5f);
  EXPECT_FLOAT_EQ(m.cameras[0].near_plane, 0.05f);
  // Lights: 683 cd -> 1 W/sr at (0, 5, 0); the spot (1366 cd -> 2 W/sr, range 7) turned +90
  // degrees about x, so its -z axis points along +y.
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].kind, LightKind::point);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 1.0f);
  EXPECT_EQ(s.lights[0].position, glm::vec3(0, 5, 0));
  EXPECT_EQ(s.lights[0].color, glm::vec3(1, 0.5f, 0.25f));
  EXPECT_EQ(s.lights[1].kind, LightKind::spot);
  EXPECT_FLOAT_EQ(s.lights[1].intensity, 2.0f);
  EXPECT_FLOAT_EQ(s.lights[1].range, 7.0f);
  EXPECT_NEAR(s.lights[1].direction.y, 1.0f, 1e-6f);
  EXPECT_NEAR(s.lights[1].direction.z, 0.0f, 1e-6f);
  EXPECT_FLOAT_EQ(s.lights[1].inner_angle, 0.2f);
  EXPECT_FLOAT_EQ(s.lights[1].outer_angle, 0.4f);
}

// A material's numbers are held in floats: one that a float cannot hold (1e39, finite as a
// double) is refused at its path, quoted as written, where it became an infinity that the
// renderer refused without a place (emissiveStrength) or not at all (normalTexture.scale). The
// limits are the scene files' for the same parameters: a factor in [0, 1] stays so, emission
// and the normal scale may be any float (emission >= 0), however large.
TEST(GltfImport, MaterialNumbersBeyondAFloatAreRefusedAtTheirPath) {
  std::ifstream in(kData + "/features.gltf");
  const nlohmann::json features = nlohmann::json::parse(in);
  const std::string fits = ", which does not fit a 32-bit float (at most 3.40282347e+38)";
  const std::string strength = "/materials/0/extensions/KHR_materials_emissive_strength";
  const std::string transform =
      "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform";
  const std::string base_transform =
      "materials[0].pbrMetallicRoughness.baseColorTexture.extensions.KHR_texture_transform";
  // (JSON pointer, value, the message after "f.gltf: ").
  const std::tuple<std::string, double, std::string> cases[] = {
      {strength + "/emissiveStrength", 1e39,
       "materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength: is 1e+39" + fits},
      {strength + "/emissiveStrength", -1,
       "materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength: is -1.0, must "
       "be >= 0"},
      {"/materials/0/normalTexture/scale", 1e39,
       "materials[0].normalTexture.scale: is 1e+39" + fits},
      {"/materials/0/normalTexture/scale", -1e39,
       "materials[0].normalTexture.scale: is -1e+39" + fits},
      {"/materials/0/occlusionTexture/strength", 1e39,
       "materials[0].occlusionTexture.strength: is 1e+39, outside [0, 1]"},
      {"/materials/0/pbrMetallicRoughness/metallicFactor", 1e39,
       "materials[0].pbrMetallicRoughness.metallicFactor: is 1e+39, outside [0, 1]"},
      {"/materials/0/pbrMetallicRoughness/roughnessFactor", -0.5,
       "materials[0].pbrMetallicRoughness.roughnessFactor: is -0.5, outside [0, 1]"},
      {"/materials/0/pbrMetallicRoughness/baseColorFactor/3", 1e39,
       "materials[0].pbrMetallicRoughness.baseColorFactor[3]: is 1e+39, outside [0, 1]"},
      {"/materials/0/emissiveFactor/1", 1.5,
       "materials[0].emissiveFactor[1]: is 1.5, outside [0, 1]"},
      {transform + "/offset/0", 1e39, base_transform + ".offset[0]: is 1e+39" + fits},
      {transform + "/scale/1", -1e39, base_transform + ".scale[1]: is -1e+39" + fits},
  };
  for (const auto& [pointer, value, message] : cases) {
    nlohmann::json doc = features;
    doc[nlohmann::json::json_pointer(pointer)] = value;
    if (pointer.find("normalTexture") != std::string::npos)
      doc["materials"][0]["normalTexture"]["index"] = 0;
    EXPECT_EQ(document_error(doc, "f.gltf"), "f.gltf: " + message);
  }
  // Large but within a float: imported, and the renderer takes them.
  nlohmann::json large = features;
  large[nlohmann::json::json_pointer(strength + "/emissiveStrength")] = 3e38;
  large["materials"][0]["normalTexture"] = {{"index", 0}, {"scale", -3e38}};
  const std::string text = large.dump();
  const ImportedModel m =
      import_gltf_bytes(std::vector<unsigned char>(text.begin(), text.end()), "f.gltf", kData);
  const Material& mat = m.scene.materials.at(m.scene.objects.at(0).material);
  EXPECT_EQ(mat.emissive, glm::vec3(0.1f, 0.2f, 0.3f) * 3e38f);  // each below 3.4e38
  EXPECT_EQ(mat.normal_scale, -3e38f);
  EXPECT_NO_THROW(validate_scene(m.scene));
}

// A node's matrix, translation, rotation and scale, a camera's znear and a light's intensity and
// range are held in floats too, by the same check as the material numbers: 1e39 (finite as a
// double) became an infinite object transform that validate_scene refused as
// "objects[0]: invalid scene: object 0 has a NaN or infinite transform", naming neither the
// file nor the node, or an infinite near plane or light range. Numbers that each fit a float
// but whose product down the hierarchy does not are refused at the node whose world transform
// overflows.
TEST(GltfImport, NodeCameraAndLightNumbersBeyondAFloatAreRefusedAtTheirPath) {
  std::ifstream in(kData + "/features.gltf");
  const nlohmann::json features = nlohmann::json::parse(in);
  ASSERT_EQ(document_error(features, "f.gltf"), "no error");
  const std::string fits = ", which does not fit a 32-bit float (at most 3.40282347e+38)";
  const std::string lights = "/extensions/KHR_lights_punctual/lights/";
  const std::string light_where = "extensions.KHR_lights_punctual.lights";
  // (JSON pointer, value, the message after "f.gltf: ").
  const std::tuple<std::string, double, std::string> cases[] = {
      {"/nodes/0/translation/0", 1e39, "nodes[0].translation[0]: is 1e+39" + fits},
      {"/nodes/2/scale/1", -1e39, "nodes[2].scale[1]: is -1e+39" + fits},
      // The rotation was normalized (a warning) before the float it is held in was considered.
      {"/nodes/4/rotation/3", 1e39, "nodes[4].rotation[3]: is 1e+39" + fits},
      {"/nodes/1/matrix/12", -1e39, "nodes[1].matrix[12]: is -1e+39" + fits},
      {"/nodes/1/matrix/0", 1e39, "nodes[1].matrix[0]: is 1e+39" + fits},
      // A node with both a matrix and TRS is read from the JSON, not from TinyGLTF's model (the
      // scan gives up on it); its TRS numbers, ignored, are held to a float all the same.
      {"/nodes/1/translation", 1e39, "nodes[1].translation[0]: is 1e+39" + fits},
      // 1e20 in each of two nodes: 2e40 in the child's world transform.
      {"/nodes/0/scale", 1e20,
       "nodes[1]: its world transform (its ancestors' transforms times its own) overflows a "
       "32-bit float"},
      {"/cameras/0/perspective/znear", 1e39, "cameras[0].perspective.znear: is 1e+39" + fits},
      {lights + "0/intensity", 1e39, light_where + "[0].intensity: is 1e+39" + fits},
      {lights + "1/range", 1e39, light_where + "[1].range: is 1e+39" + fits},
  };
  for (const auto& [pointer, value, message] : cases) {
    nlohmann::json doc = features;
    doc["nodes"][2]["scale"] = {1, 1, 1};
    nlohmann::json& v = doc[nlohmann::json::json_pointer(pointer)];
    v = v.is_null() ? nlohmann::json{value, value, value} : nlohmann::json(value);
    if (pointer == "/nodes/0/scale") doc["nodes"][1]["matrix"][0] = 1e20;
    EXPECT_EQ(document_error(doc, "f.gltf"), "f.gltf: " + message) << pointer;
  }
  // Large but within a float: imported as written.
  nlohmann::json large = features;
  large["nodes"][0]["translation"][0] = 1.5e38;  // times the child's scale of 2: 3e38
  large["cameras"][0]["perspective"]["znear"] = 3e38;
  large["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = 3e38;
  large["extensions"]["KHR_lights_punctual"]["lights"][1]["range"] = 3e38;
  const std::string text = large.dump();
  const ImportedModel m =
      import_gltf_bytes(std::vector<unsigned char>(text.begin(), text.end()), "f.gltf", kData);
  EXPECT_EQ(m.scene.objects.at(0).transform[3][0], 1.5e38f);
  EXPECT_EQ(m.cameras.at(0).near_plane, 3e38f);
  EXPECT_EQ(m.scene.lights.at(0).intensity, float(3e38 / 683.0));
  EXPECT_EQ(m.scene.lights.at(1).range, 3e38f);
}

// A lit scene framing the model's world bounds from the front and above.
Scene framed(Scene s) {
  glm::vec3 lo, hi;
  world_bounds(s, lo, hi);
  const glm::vec3 centre = 0.5f * (lo + hi);
  const float radius = 0.5f * glm::length(hi - lo);
  s.camera.target = centre;
  s.camera.position = centre + radius * glm::vec3(1.2f, 1.0f, 2.2f);
  s.camera.vertical_fov = glm::radians(45.0f);
  s.camera.near_plane = 0.01f * radius;
  Light sun;
  sun.kind = LightKind::directional;
  sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.6f));
  sun.intensity = 3.0f;
  s.lights = {sun};
  s.ambient = glm::vec3(0.15f);
  s.background = glm::vec3(0.05f);
  return s;
}

// Rendered models are compared with the reference (tests/accuracy_support.h) and then kept
// as golden images (tests/golden/gltf_*.png), small so that the suite stays fast.
class GltfRender : public test::VulkanTest {};

TEST_F(GltfRender, BoxTexturedMatchesTheReference) {
  const Scene scene = framed(import_gltf(kModels + "BoxTextured-glTF/BoxTextured.gltf").scene);
  Renderer renderer(context());
  test::expect_reference_and_golden(renderer, scene, 160, 120, "gltf_box_textured");
}

TEST_F(GltfRender, EngineMatchesTheReference) {
  const Scene scene =
      framed(import_gltf(kModels + "2CylinderEngine-glTF-Binary/2CylinderEngine.glb").scene);
  Renderer renderer(context());
  test::expect_reference_and_golden(renderer, scene, 160, 120, "gltf_engine");
}

// The asset generator's triangle modes (strips, fans, lists; indexed by every index type or
// not) side by side in one frame, 4 by 2 in the order 04, 05, 06, 11 / 12, 13, 14, 15: each
// file's unit square (one object) moved to its cell.
TEST_F(GltfRender, PrimitiveModesMatchTheReference) {
  Scene scene;
  int cell = 0;
  for (int m : {4, 5, 6, 11, 12, 13, 14, 15}) {
    char name[64];
    std::snprintf(name, sizeof name, "Mesh_PrimitiveMode_%02d.gltf", m);
    Scene part = import_gltf(kModels + "glTF-Asset-Generator/Mesh_PrimitiveMode/" + name).scene;
    ASSERT_EQ(part.objects.size(), 1u) << name;
    Object o = part.objects[0];
    o.mesh += uint32_t(scene.meshes.size());
    o.material += uint32_t(scene.materials.size());
    const glm::vec3 offset(1.25f * (float(cell % 4) - 1.5f), 0.625f - 1.25f * float(cell / 4), 0);
    o.transform = glm::translate(glm::mat4(1.0f), offset) * o.transform;
    scene.objects.push_back(o);
    scene.meshes.insert(scene.meshes.end(), part.meshes.begin(), part.meshes.end());
    scene.materials.insert(scene.materials.end(), part.materials.begin(), part.materials.end());
    ++cell;
  }
  // The grid spans x in [-2.375, 2.375], y in [-1.125, 1.125]: seen from 4 m in front (and a
  // little right and above), 45 degrees high and 75 wide fit +-1.66 and +-2.8 m.
  scene = framed(std::move(scene));
  scene.camera.target = glm::vec3(0.0f);
  scene.camera.position = glm::vec3(0.6f, 0.5f, 4.0f);
  Renderer renderer(context());
  test::expect_reference_and_golden(renderer, scene, 160, 96, "gltf_primitive_modes");
}

// tests/data/texcoord1.gltf seen head-on: a 2x2 m quad whose TEXCOORD_0 is (0.25, 0.5) at every
// vertex, the centre of the red texel of its 2x1 red|blue base-colour texture, and whose
// TEXCOORD_1 runs u from 0 at its left edge to 1 at its right. Base colour reads set 1: red a
// quarter of the way in from the left (u = 0.25), blue a quarter in from the right (u = 0.75).
// Read through set 0 the whole quad is red.
TEST_F(GltfRender, SecondUvSetMatchesTheReference) {
  Scene scene = import_gltf(kData + "/texcoord1.gltf").scene;
  scene.camera.position = glm::vec3(0, 0, 3);
  scene.camera.target = glm::vec3(0);
  Light sun;
  sun.kind = LightKind::directional;
  sun.direction = glm::vec3(0, 0, -1);
  sun.intensity = 3.0f;
  scene.lights = {sun};
  // 64 px span 2 * 3 tan(22.5 deg) = 2.485 m: pixel column 19 (centre 19.5) is at x = -0.486 m,
  // u = 0.257; column 44 at x = +0.486 m, u = 0.743: within 0.02 texel of the texel centres.
  const uint32_t size = 64, left = 19, right = 44, row = 32;
  Renderer renderer(context());
  test::expect_reference_and_golden(renderer, scene, size, size, "gltf_texcoord1");
  const Image8 set1 = renderer.read_ldr();
  const auto red_over_blue = [&](const Image8& image, uint32_t x) {
    const glm::u8vec4 p = image.pixels[size_t(row) * size + x];
    return double(p.r) / std::max(1.0, double(p.b));
  };
  EXPECT_GT(red_over_blue(set1, left), 4.0);
  EXPECT_LT(red_over_blue(set1, right), 0.25);

  // The generic shading pipeline decides per material at run time; the same answer.
  RendererOptions generic;
  generic.specialize_lights = false;
  test::expect_meets_bars(test::compare_with_reference(context(), scene, size, size,
                                                       "gltf_texcoord1_generic", generic));

  scene.materials[scene.objects[0].material].uv1_maps = 0;
  const Image8 set0 = render(scene, size, size).ldr;
  EXPECT_GT(red_over_blue(set0, left), 4.0);
  EXPECT_GT(red_over_blue(set0, right), 4.0);
}

// A single-sided triangle under a node that mirrors it (scale -1 in x): its front face stays
// its front (glTF 2.0, 3.7.4), so seen from +z it covers as many pixels as its unmirrored twin.
// The importer once wound mirrored instances the other way on top of the renderer doing so
// (is_mirroring), and such triangles were culled.
TEST_F(GltfRender, MirroredNodeKeepsItsFrontFace) {
  const auto triangle_under = [](const std::string& scale) {
    const std::string text = R"({"asset": {"version": "2.0"}, "scene": 0,
      "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0, "scale": )" +
                             scale + R"(}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 0]}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "buffers": [{"byteLength": 36,
        "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
    Scene s = import_gltf_bytes(std::vector<unsigned char>(text.begin(), text.end()),
                                "triangle.gltf", ".")
                  .scene;
    s.camera.position = glm::vec3(0, 0.4f, 3);
    s.camera.target = glm::vec3(0, 0.4f, 0);
    s.ambient = glm::vec3(1.0f);
    return s;
  };
  const auto covered = [](const std::vector<uint64_t>& visibility) {
    return std::count_if(visibility.begin(), visibility.end(),
                         [](uint64_t key) { return key != ~0ull; });
  };
  const Scene plain = triangle_under("[1, 1, 1]"), mirrored = triangle_under("[-1, 1, 1]");
  const long long plain_pixels = covered(render(plain, 64, 64).visibility);
  EXPECT_GT(plain_pixels, 200);
  EXPECT_EQ(covered(render(mirrored, 64, 64).visibility), plain_pixels)
      << "the mirrored triangle must show its front face, the mirror image of the plain one";
  ReferenceSettings rs;
  rs.frame.width = rs.frame.height = 64;
  const ReferenceFrame ref = render_reference(mirrored, rs);
  EXPECT_EQ(std::count_if(ref.owner.begin(), ref.owner.end(),
                          [](uint32_t o) { return o != kNoTriangle; }),
            plain_pixels);
}

}  // namespace
}  // namespace tessera
