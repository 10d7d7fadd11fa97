// OBJ/MTL import (core/obj_import.cpp): bad files and the message each must give, small files
// whose meshes are derived by hand, and assimp's test models (Debian assimp-testmodels), counted
// with awk and rendered against the reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/check.h"
#include "core/image.h"
#include "core/model_import.h"
#include "tests/accuracy_support.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

const std::string kAssimpObj = "/usr/share/assimp/models/OBJ/";

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Writes `text` to `name` in the test's output folder and returns the path.
std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = test::output_path(name);
  std::ofstream(path) << text;
  return path;
}

/// Imports `text` written to `name` in the test's output folder.
ImportedModel import_text(const std::string& name, const std::string& text) {
  return import_obj(write_file(name, text));
}

/// The one mesh of `text` imported (as import_text does).
Mesh only_mesh(const std::string& name, const std::string& text) {
  ImportedModel model = import_text(name, text);
  EXPECT_EQ(model.scene.meshes.size(), 1u) << name;
  return model.scene.meshes.at(0);
}

std::string error_of(const std::string& path, const ImportOptions& options = {}) {
  try {
    import_obj(path, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

std::string all_warnings(const ImportedModel& model) {
  std::string s;
  for (const std::string& w : model.warnings) s += w + "\n";
  return s;
}

// Each tests/data/bad/NAME.obj comes with NAME.expected: "error: TEXT" or "warning: TEXT", TEXT
// a part of the message (the place and what is wrong, written by hand from the file).
TEST(ObjImportBadFiles, EachGivesItsMessage) {
  const fs::path dir = fs::path(TESSERA_TEST_DATA_DIR) / "bad";
  int errors = 0, warnings = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".obj") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const fs::path expected_path = fs::path(entry.path()).replace_extension(".expected");
    ASSERT_TRUE(fs::exists(expected_path)) << "every bad file says what it must produce";
    const std::string expected = read_text(expected_path);
    if (expected.rfind("error: ", 0) == 0) {
      ++errors;
      EXPECT_NE(error_of(entry.path().string()).find(expected.substr(7)), std::string::npos)
          << "expected: " << expected.substr(7) << "\ngot: " << error_of(entry.path().string());
    } else {
      ASSERT_EQ(expected.rfind("warning: ", 0), 0u) << expected;
      ++warnings;
      ImportedModel model;
      ASSERT_NO_THROW(model = import_obj(entry.path().string()));
      EXPECT_NE(all_warnings(model).find(expected.substr(9)), std::string::npos)
          << "expected: " << expected.substr(9) << "\ngot: " << all_warnings(model);
      // A warning leaves a scene that renders.
      EXPECT_NO_THROW(validate_scene(model.scene));
      // Strict import turns it into an error.
      ImportOptions strict;
      strict.strict = true;
      EXPECT_NE(error_of(entry.path().string(), strict).find("strict"), std::string::npos);
    }
  }
  EXPECT_GE(errors, 15);
  EXPECT_GE(warnings, 8);
}

TEST(ObjImportLimits, FileOverMaxBytesIsRefused) {
  const std::string path = kAssimpObj + "spider.obj";
  ImportOptions options;
  options.max_file_bytes = 1000;
  const std::string e = error_of(path, options);
  EXPECT_NE(e.find("spider.obj' is "), std::string::npos) << e;
  EXPECT_NE(e.find("over the limit of 1000"), std::string::npos) << e;
}

TEST(ObjImportLimits, TextureOverMaxSideIsRefused) {
  write_png(test::output_path("wide.png"), Image8{4, 2, std::vector<glm::u8vec4>(8)});
  write_file("wide.mtl", "newmtl m\nmap_Kd wide.png\n");
  const std::string obj =
      write_file("wide.obj", "mtllib wide.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n");
  ImportOptions options;
  options.max_texture_side = 3;
  const std::string e = error_of(obj, options);
  EXPECT_NE(e.find("wide.mtl' line 2 ('map_Kd' of material 'm'): texture"), std::string::npos) << e;
  EXPECT_NE(e.find("is 4x2, over the largest side of 3"), std::string::npos) << e;
  options.max_texture_side = 4;
  EXPECT_NO_THROW(import_obj(obj, options));
}

TEST(ObjImportLimits, MissingFileNamesIt) {
  EXPECT_NE(error_of("/nonexistent/model.obj").find("'/nonexistent/model.obj' not found"),
            std::string::npos);
}

// A unit quad with uvs: fanned from its first corner, (0 1 2) (0 2 3); OBJ's v flipped.
// A file is read in 1 MiB chunks, each line scanned as tinyobjloader gets it: lines across
// chunk boundaries, a "\r\n" split by one, and a line longer than a chunk must give the scene
// of the same text imported from memory (one piece), and an error beyond the first chunk its
// line number.
TEST(ObjImportChunks, FileReadInChunksGivesTheTextsScene) {
  const int n = 300;  // n x n quads: about 4 MB of text, several chunks
  std::string text = "#" + std::string(3 << 19, 'x') + "\r\n";  // 1.5 MiB comment line
  size_t lines = 1;                                             // lines written so far
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i, ++lines) {
      text += "v " + std::to_string(i) + ".25 " + std::to_string(j) + ".5 -0.125\r\n";
    }
  }
  text += "vn 0 0 1\r\n";
  ++lines;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i, ++lines) {
      const int a = j * (n + 1) + i + 1, b = a + 1, c = b + n + 1, d = a + n + 1;
      text += "f " + std::to_string(a) + "//1 " + std::to_string(b) + "//1 " + std::to_string(c) +
              "//1 " + std::to_string(d) + "//1\r\n";
    }
  }
  // The long first line makes the buffer grow to 2 MiB before any line is complete; padding it
  // puts a "\r" as the last byte of those 2 MiB and its "\n" after them.
  const size_t boundary = size_t(2) << 20;
  const size_t cr = text.rfind('\r', boundary - 1);
  text.insert(1, boundary - 1 - cr, 'x');
  ASSERT_EQ(text.substr(boundary - 1, 2), "\r\n");
  ASSERT_GT(text.size(), size_t(3) << 20);
  const ImportedModel from_file = import_text("chunks.obj", text);
  const ImportedModel from_text = import_obj_text(text, "chunks.obj", "");
  ASSERT_EQ(from_file.scene.meshes.size(), 1u);
  const Mesh& mesh = from_file.scene.meshes[0];
  EXPECT_EQ(mesh.positions.size(), size_t(n + 1) * (n + 1));  // one vertex per position
  EXPECT_EQ(mesh.triangle_count(), size_t(2) * n * n);
  EXPECT_EQ(mesh.positions.back(), glm::vec3(n + 0.25f, n + 0.5f, -0.125f));
  ASSERT_EQ(from_text.scene.meshes.size(), 1u);
  EXPECT_EQ(mesh.positions, from_text.scene.meshes[0].positions);
  EXPECT_EQ(mesh.indices, from_text.scene.meshes[0].indices);
  EXPECT_EQ(mesh.normals, from_text.scene.meshes[0].normals);
  EXPECT_TRUE(from_file.warnings.empty()) << all_warnings(from_file);

  const std::string bad = write_file("chunks_bad.obj", text + "v 1 2\r\n");
  EXPECT_EQ(error_of(bad), "'" + bad + "' line " + std::to_string(lines + 1) +
                               ", column 1: 'v' has 2 numbers, expected 3 (x y z), 4 or 6");
}

TEST(ObjImportGeometry, QuadBecomesTwoTriangles) {
  const ImportedModel model = import_text("quad.obj",
                                          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                          "f 1/1 2/2 3/3 4/4\n");
  ASSERT_EQ(model.scene.meshes.size(), 1u);
  const Mesh& m = model.scene.meshes[0];
  EXPECT_EQ(m.positions, (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}));
  EXPECT_EQ(m.uvs, (std::vector<glm::vec2>{{0, 1}, {1, 1}, {1, 0}, {0, 0}}));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  // No vn and no smoothing group: the face's own normal.
  EXPECT_EQ(m.normals, std::vector<glm::vec3>(4, glm::vec3(0, 0, 1)));
  ASSERT_EQ(model.scene.objects.size(), 1u);
  EXPECT_EQ(model.scene.objects[0].transform, glm::mat4(1.0f));
  EXPECT_EQ(model.scene.materials.size(), 1u) << "the default material";
  EXPECT_TRUE(model.warnings.empty()) << all_warnings(model);
  EXPECT_NO_THROW(validate_scene(model.scene));
}

// `v x y z r g b` is read for its position; the colours are said to be ignored, once.
TEST(ObjImportGeometry, VertexColoursAreIgnoredWithAWarning) {
  const ImportedModel model = import_text("coloured.obj",
                                          "v 0 0 0\nv 1 0 0 1 0 0\nv 1 1 0 0 1 0\n"
                                          "f 1 2 3\n");
  ASSERT_EQ(model.scene.meshes.size(), 1u);
  EXPECT_EQ(model.scene.meshes[0].positions,
            (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}));
  ASSERT_EQ(model.warnings.size(), 1u) << all_warnings(model);
  EXPECT_NE(model.warnings[0].find("coloured.obj' line 2: vertex colours (2 vertices with r g b) "
                                   "are ignored"),
            std::string::npos)
      << model.warnings[0];
}

TEST(ObjImportGeometry, ConvexPentagonIsAFan) {
  const Mesh m = only_mesh("pentagon.obj",
                           "v 1 0 0\nv 0.3 0.95 0\nv -0.8 0.6 0\nv -0.8 -0.6 0\nv 0.3 -0.95 0\n"
                           "f 1 2 3 4 5\n");
  EXPECT_EQ(m.positions.size(), 5u);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
}

// Twice the signed area of triangle t of `m` in the xy plane (> 0: counter-clockwise seen
// from +z).
double signed_area_xy(const Mesh& m, size_t t) {
  const glm::dvec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                   c = m.positions[m.indices[3 * t + 2]];
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// An L of area 2 * 1 + 1 * 1 = 3 with a reflex corner at (1, 1): a fan from corner 0 would
// cover the missing square; ear clipping gives 6 - 2 triangles, all inside, summing to 3.
void expect_l_shape(const Mesh& m, double facing) {
  ASSERT_EQ(m.triangle_count(), 4u);
  double area = 0.0;
  for (size_t t = 0; t < 4; ++t) {
    const double a = facing * signed_area_xy(m, t);
    EXPECT_GT(a, 0.0) << "triangle " << t << " keeps the polygon's winding";
    area += a / 2.0;
    glm::vec3 centroid(0.0f);
    for (int k = 0; k < 3; ++k) centroid += m.positions[m.indices[3 * t + k]] / 3.0f;
    EXPECT_TRUE(centroid.x < 1.0f || centroid.y < 1.0f) << "triangle " << t << " is inside the L";
  }
  EXPECT_NEAR(area, 3.0, 1e-6);
  for (const glm::vec3& n : m.normals) EXPECT_EQ(n, glm::vec3(0, 0, float(facing)));
}

TEST(ObjImportGeometry, ConcavePolygonIsEarClipped) {
  expect_l_shape(
      import_text("l_front.obj",
                  "v 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 0\nv 2 0 0\nv 2 1 0\nf 1 2 3 4 5 6\n")
          .scene.meshes.at(0),
      1.0);
  // The same L wound the other way faces -z: the projection must keep its winding too.
  expect_l_shape(
      import_text("l_back.obj",
                  "v 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 0\nv 2 0 0\nv 2 1 0\nf 6 5 4 3 2 1\n")
          .scene.meshes.at(0),
      -1.0);
}

TEST(ObjImportGeometry, VerticesAreSharedByIndexTriple) {
  const Mesh a =
      only_mesh("shared.obj",
                "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
                "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n");
  EXPECT_EQ(a.positions.size(), 4u);
  EXPECT_EQ(a.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  // Corner 3 of the second face has another uv: one more vertex.
  const Mesh b =
      only_mesh("split.obj",
                "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
                "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/5/1 4/4/1\n");
  EXPECT_EQ(b.positions.size(), 5u);
  EXPECT_EQ(b.uvs[3], glm::vec2(0.5f, 0.5f));
  EXPECT_EQ(b.indices, (std::vector<uint32_t>{0, 1, 2, 0, 3, 4}));
}

TEST(ObjImportGeometry, FileNormalsAreNormalized) {
  const Mesh m = only_mesh("normals.obj",
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nvn 3 0 4\nvn 0 -5 0\n"
                           "f 1//1 2//2 3//3\n");
  EXPECT_EQ(m.normals, (std::vector<glm::vec3>{{0, 0, 1}, {0.6f, 0, 0.8f}, {0, -1, 0}}));
}

// The scan runs up to a chunk ahead of tinyobjloader; what it tells the conversion (smoothing
// groups, the lines of polygons) must reach the faces it belongs to. A grid of n x n quads in
// the plane z = 0, several chunks long: its first n/2 rows smooth (one vertex per position),
// the rest flat (four vertices per quad), then a self-intersecting polygon with no ear.
TEST(ObjImportChunks, SmoothingGroupsAndPolygonLinesFollowTheirFaces) {
  const int n = 300;
  std::string text;
  size_t lines = 0;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i, ++lines) {
      text += "v " + std::to_string(i) + ".5 " + std::to_string(j) + ".25 0\n";
    }
  }
  for (int j = 0; j < n; ++j) {
    if (j == 0 || j == n / 2) {
      text += j == 0 ? "s 1\n" : "s off\n";
      ++lines;
    }
    for (int i = 0; i < n; ++i, ++lines) {
      const int a = j * (n + 1) + i + 1, b = a + 1, c = b + n + 1, d = a + n + 1;
      text += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + " " +
              std::to_string(d) + "\n";
    }
  }
  // A pentagon whose path crosses itself twice: (3,2) (0,1) (3,3) (1,0) (2,1).
  text += "v 3 2 1\nv 0 1 1\nv 3 3 1\nv 1 0 1\nv 2 1 1\n";
  lines += 5;
  text += "f -5 -4 -3 -2 -1\n";
  ++lines;
  ASSERT_GT(text.size(), size_t(3) << 20);
  const ImportedModel model = import_text("chunks_smooth.obj", text);
  ASSERT_EQ(model.scene.meshes.size(), 1u);
  const Mesh& mesh = model.scene.meshes[0];
  const size_t grid_vertices = size_t(n / 2 + 1) * (n + 1) + size_t(4) * (n / 2) * n;
  EXPECT_EQ(mesh.positions.size(), grid_vertices + 5);
  EXPECT_EQ(mesh.triangle_count(), size_t(2) * n * n + 3);
  for (size_t v = 0; v < grid_vertices; ++v) ASSERT_EQ(mesh.normals[v], glm::vec3(0, 0, 1)) << v;
  ASSERT_EQ(model.warnings.size(), 1u);
  EXPECT_EQ(model.warnings[0],
            "'" + test::output_path("chunks_smooth.obj") + "' line " + std::to_string(lines) +
                ": the polygon intersects itself; its triangulation is arbitrary");
}

// Two triangles of area 1/2 on the edge (0,0,0)-(0,1,0), one facing +z, one facing +x.
const char* const kTent =
    "v 0 0 0\nv 0 1 0\nv -1 0 0\nv 0 0 -1\n"
    "f 3 1 2\nf 1 4 2\n";

TEST(ObjImportGeometry, SmoothingGroupsShareNormals) {
  const Mesh m = only_mesh("smooth.obj", std::string("s 1\n") + kTent);
  ASSERT_EQ(m.positions.size(), 4u);
  const float h = float(std::sqrt(0.5));
  // Vertices in first-use order: (-1,0,0), (0,0,0), (0,1,0), (0,0,-1).
  EXPECT_EQ(m.positions, (std::vector<glm::vec3>{{-1, 0, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, -1}}));
  const std::vector<glm::vec3> expected{{0, 0, 1}, {h, 0, h}, {h, 0, h}, {1, 0, 0}};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(glm::distance(m.normals[i], expected[i]), 0.0f, 1e-6f) << i;
  }
  const Mesh flat = only_mesh("flat.obj", std::string("s off\n") + kTent);
  ASSERT_EQ(flat.positions.size(), 6u);
  EXPECT_EQ(flat.normals, (std::vector<glm::vec3>{
                              {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}}));
}

// Smoothing groups reach across shapes: the tent's two faces in two groups (`g`) still share
// the normal (h, 0, h) at the ridge, the sum of +z and +x, though the second face comes after
// the first shape's mesh was made.
TEST(ObjImportGeometry, SmoothingGroupsSpanShapes) {
  const ImportedModel model =
      import_text("smooth_shapes.obj",
                  "s 1\nv 0 0 0\nv 0 1 0\nv -1 0 0\nv 0 0 -1\ng a\nf 3 1 2\ng b\nf 1 4 2\n");
  ASSERT_EQ(model.scene.meshes.size(), 2u);
  const float h = float(std::sqrt(0.5));
  const Mesh& a = model.scene.meshes[0];
  const Mesh& b = model.scene.meshes[1];
  ASSERT_EQ(a.positions, (std::vector<glm::vec3>{{-1, 0, 0}, {0, 0, 0}, {0, 1, 0}}));
  ASSERT_EQ(b.positions, (std::vector<glm::vec3>{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}}));
  const std::vector<glm::vec3> expected_a{{0, 0, 1}, {h, 0, h}, {h, 0, h}};
  const std::vector<glm::vec3> expected_b{{h, 0, h}, {1, 0, 0}, {h, 0, h}};
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(glm::distance(a.normals[i], expected_a[i]), 0.0f, 1e-6f) << i;
    EXPECT_NEAR(glm::distance(b.normals[i], expected_b[i]), 0.0f, 1e-6f) << i;
  }
}

// Faces may refer to vertices and normals defined further down; a face after them, by negative
// indices, refers to the same corners, so it shares their vertices, in first-use order.
TEST(ObjImportGeometry, FacesBeforeTheirVertices) {
  const Mesh m = only_mesh("forward.obj",
                           "f 1//1 2//1 3//1\nf 2//1 4//1 3//1\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                           "v 1 1 0\nvn 0 0 2\nf -4//-1 -3//-1 -2//-1\n");
  EXPECT_EQ(m.positions, (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 0, 1, 2}));
  EXPECT_EQ(m.normals, std::vector<glm::vec3>(4, glm::vec3(0, 0, 1)));
}

// Ns -> roughness = (2 / (Ns + 2))^(1/4): Ns = 30 gives 16^(-1/4) = 0.5, Ns = 510 gives
// 256^(-1/4) = 0.25, Ns = 0 gives 1. Pr wins over Ns; neither leaves the default 0.5.
TEST(ObjImportMaterials, MtlValuesAndOneMeshPerMaterial) {
  write_file("mat.mtl",
             "newmtl a\nKd 0.5 0.25 1\nNs 30\n"
             "newmtl b\nNs 510\nPm 0.75\nKe 2 3 4\n"
             "newmtl c\nNs 0\n"
             "newmtl d\nNs 30\nPr 0.125\n"
             "newmtl e\nKd 1 1 1\n");
  const ImportedModel model =
      import_text("mat.obj",
                  "mtllib mat.mtl\ns 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                  "f 1 2 3\nusemtl c\nf 1 2 3\nusemtl a\nf 1 2 3\nusemtl c\nf 2 3 1\n"
                  "usemtl b\nf 1 2 3\nusemtl d\nf 1 2 3\nusemtl e\nf 1 2 3\n");
  EXPECT_TRUE(model.warnings.empty()) << all_warnings(model);
  const std::vector<Material>& mats = model.scene.materials;
  ASSERT_EQ(mats.size(), 6u) << "a to e, then the default for the face before any usemtl";
  EXPECT_EQ(mats[0].base_color, glm::vec3(0.5f, 0.25f, 1.0f));
  EXPECT_FLOAT_EQ(mats[0].roughness, 0.5f);
  EXPECT_FLOAT_EQ(mats[0].metallic, 0.0f);
  EXPECT_FLOAT_EQ(mats[1].roughness, 0.25f);
  EXPECT_FLOAT_EQ(mats[1].metallic, 0.75f);
  EXPECT_EQ(mats[1].emissive, glm::vec3(2, 3, 4));
  EXPECT_FLOAT_EQ(mats[2].roughness, 1.0f);
  EXPECT_FLOAT_EQ(mats[3].roughness, 0.125f);
  EXPECT_FLOAT_EQ(mats[4].roughness, 0.5f);
  // One group: a mesh per material in order of first use: default, c (2 faces), a, b, d, e.
  const std::vector<uint32_t> material_of_object{5, 2, 0, 1, 3, 4};
  ASSERT_EQ(model.scene.objects.size(), material_of_object.size());
  for (size_t i = 0; i < material_of_object.size(); ++i) {
    EXPECT_EQ(model.scene.objects[i].material, material_of_object[i]) << i;
    EXPECT_EQ(model.scene.objects[i].mesh, i);
  }
  EXPECT_EQ(model.scene.meshes[1].triangle_count(), 2u);
  EXPECT_EQ(model.scene.meshes[1].positions.size(), 3u)
      << "f 2 3 1 reuses f 1 2 3's vertices (same smoothing group)";
}

// tinyobjloader drops statements before the first `newmtl` unless there is none (then they
// make a material named ""), and names a material by the rest of its line, spaces included.
TEST(ObjImportMaterials, UnnamedAndSpacedMaterialNames) {
  write_file("unnamed.mtl", "Kd 1 0 0\n");
  const ImportedModel unnamed =
      import_text("unnamed.obj", "mtllib unnamed.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  ASSERT_EQ(unnamed.scene.materials.size(), 2u) << "the unnamed one, then the default";
  EXPECT_EQ(unnamed.scene.materials[0].base_color, glm::vec3(1, 0, 0));
  EXPECT_EQ(unnamed.scene.objects.at(0).material, 1u);
  write_file("spaced.mtl", "Kd 1 0 0\nnewmtl two words\nKd 0 1 0\n");
  const ImportedModel spaced =
      import_text("spaced.obj", "mtllib spaced.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  ASSERT_GE(spaced.scene.materials.size(), 1u);
  EXPECT_EQ(spaced.scene.materials[0].base_color, glm::vec3(0, 1, 0));
  EXPECT_NO_THROW(validate_scene(spaced.scene));
}

// Texture options Tessera does not apply are named in the warning, only those given.
TEST(ObjImportMaterials, UnsupportedTextureOptionsAreNamed) {
  write_png(test::output_path("option.png"), Image8{1, 1, {{255, 0, 0, 255}}});
  write_png(test::output_path("option2.png"), Image8{1, 1, {{0, 255, 0, 255}}});
  write_file("options.mtl",
             "newmtl a\nmap_Kd -s 2 2 1 -o 0.5 0 0 option.png\n"
             "newmtl b\nmap_Kd -clamp on option2.png\n");
  const ImportedModel m = import_text(
      "options.obj",
      "mtllib options.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 3 2\n");
  const std::string w = all_warnings(m);
  EXPECT_NE(w.find("texture options -s, -o are not supported and ignored"), std::string::npos) << w;
  EXPECT_NE(w.find("texture option -clamp is not supported and ignored"), std::string::npos) << w;
  EXPECT_EQ(m.warnings.size(), 2u) << w;
}

// A `usemtl` names a material with spaces whole, as `newmtl` declares it ("My Red"); a name no
// library has falls back to its first word (LoadObj's reading), and a missing one is warned
// about once, quoted whole (a fresh user's trial: "usemtl My Red" took 'My' and drew grey).
TEST(ObjImportMaterials, UsemtlNamesWithSpaces) {
  write_file("spaces.mtl", "newmtl My Red\nKd 1 0 0\nnewmtl green\nKd 0 1 0\n");
  const ImportedModel m = import_text(
      "spaces.obj",
      "mtllib spaces.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl My Red \nf 1 2 3\n"
      "usemtl green with a comment\nf 1 3 2\nusemtl No Such\nf 2 1 3\nusemtl No Such\nf 2 3 1\n");
  ASSERT_EQ(m.scene.objects.size(), 3u);
  const auto colour_of = [&](size_t i) {
    return m.scene.materials.at(m.scene.objects[i].material).base_color;
  };
  EXPECT_EQ(colour_of(0), glm::vec3(1, 0, 0));
  EXPECT_EQ(colour_of(1), glm::vec3(0, 1, 0));
  EXPECT_EQ(colour_of(2), Material{}.base_color);
  EXPECT_EQ(m.warnings.size(), 1u) << all_warnings(m);
  EXPECT_NE(all_warnings(m).find("material 'No Such' is not defined"), std::string::npos)
      << all_warnings(m);
}

TEST(ObjImportMaterials, TextureMaps) {
  const auto gray = [](std::initializer_list<uint8_t> values) {
    std::vector<glm::u8vec4> texels;
    for (uint8_t v : values) texels.push_back(glm::u8vec4(v, v, v, 255));
    return texels;
  };
  const Image8 base{2, 2, {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}, {9, 9, 9, 255}}};
  write_png(test::output_path("base.png"), base);
  write_png(test::output_path("rough.png"), Image8{2, 1, gray({64, 32})});
  write_png(test::output_path("metal.png"), Image8{1, 2, gray({200, 100})});
  write_png(test::output_path("normal.png"), Image8{1, 1, {{128, 140, 250, 255}}});
  write_png(test::output_path("height.png"), Image8{1, 1, gray({77})});
  write_file("tex.mtl",
             "newmtl a\nmap_Kd base.png\nmap_Pr rough.png\nmap_Pm metal.png\n"
             "norm -bm 0.5 normal.png\nmap_Ke base.png\n"
             "newmtl b\nKd 0.5 0.5 0.5\nmap_Kd base.png\nmap_bump height.png\n");
  const ImportedModel model =
      import_text("tex.obj",
                  "mtllib tex.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n"
                  "usemtl b\nf 1 2 3\n");
  const Scene& s = model.scene;
  ASSERT_EQ(s.textures.size(), 3u) << "base (shared by a and b), packed metal-roughness, normal";
  const Material& a = s.materials.at(0);
  EXPECT_EQ(a.base_color_map, 0u);
  EXPECT_TRUE(s.textures[0].srgb);
  EXPECT_EQ(s.textures[0].texels, base.pixels);
  // Packed at 2 x 2: G from rough.png's row (nearest), B from metal.png's column.
  ASSERT_EQ(a.metallic_roughness_map, 1u);
  const Texture& mr = s.textures[1];
  EXPECT_FALSE(mr.srgb);
  ASSERT_EQ(mr.width, 2u);
  ASSERT_EQ(mr.height, 2u);
  EXPECT_EQ(
      mr.texels,
      (std::vector<glm::u8vec4>{
          {255, 64, 200, 255}, {255, 32, 200, 255}, {255, 64, 100, 255}, {255, 32, 100, 255}}));
  EXPECT_EQ(a.roughness, 1.0f) << "a map without Pr is the roughness";
  EXPECT_EQ(a.metallic, 1.0f);
  ASSERT_EQ(a.normal_map, 2u);
  EXPECT_FALSE(s.textures[2].srgb);
  EXPECT_EQ(a.normal_scale, 0.5f);
  EXPECT_EQ(a.emissive_map, 0u) << "map_Ke reads base.png as sRGB too: the same texture";
  const Material& b = s.materials.at(1);
  EXPECT_EQ(b.base_color_map, 0u);
  EXPECT_EQ(b.normal_map, kNoTexture) << "a grayscale bump map is a height map";
  EXPECT_NE(all_warnings(model).find("tex.mtl' line 10 ('map_bump' of material 'b'): the bump "
                                     "map is grayscale"),
            std::string::npos)
      << all_warnings(model);
  EXPECT_NO_THROW(validate_scene(s));
}

// Counts from the file itself:
//   awk '$1=="f"{t+=NF-3} END{print t}' spider.obj                              -> 1368
//   awk '$1=="f"{n[NF-1]++} END{for(k in n) print k, n[k]}' spider.obj          -> 3 1368
//   awk '$1=="g"{g=$2} $1=="usemtl"{m=$2} $1=="f"{p[g SUBSEP m]=1;
//        for(i=2;i<=NF;i++) u[g SUBSEP m SUBSEP $i]=1} END{...count p, u}' spider.obj
//                                                            -> 19 meshes, 974 index triples
//   Normal 488 (line 1560) is (0, 0, 0), used by 108 corners; those get generated normals,
//   keyed by (v, vt, smoothing group) instead of the triple:
//   awk '$1=="vn"{n++; if($2==0&&$3==0&&$4==0) z[n]=1} $1=="g"{g=$2} $1=="usemtl"{m=$2}
//        $1=="s"{s=($2=="off")?0:$2} $1=="f"{f++; for(i=2;i<=NF;i++){split($i,a,"/");
//        k=(a[3] in z)?((s>0)?"s" s:"f" f):a[3]; u[g SUBSEP m SUBSEP a[1] SUBSEP a[2] SUBSEP k]=1}}
//        END{for(x in u) c++; print c}' spider.obj                      -> 986 vertices
//   grep -c ^newmtl spider.mtl -> 5; every material has its own map_Kd -> 5 textures
TEST(ObjImportAssimpModels, SpiderCounts) {
  const ImportedModel model = import_obj(kAssimpObj + "spider.obj");
  const Scene& s = model.scene;
  ASSERT_EQ(model.warnings.size(), 1u) << all_warnings(model);
  EXPECT_NE(model.warnings[0].find("spider.obj' line 1560: normal (0, 0, 0) has no direction"),
            std::string::npos)
      << model.warnings[0];
  EXPECT_EQ(s.meshes.size(), 19u);
  EXPECT_EQ(s.objects.size(), 19u);
  EXPECT_EQ(s.materials.size(), 5u);
  EXPECT_EQ(s.textures.size(), 5u);
  size_t triangles = 0, vertices = 0;
  for (const Mesh& m : s.meshes) {
    triangles += m.triangle_count();
    vertices += m.positions.size();
  }
  EXPECT_EQ(triangles, 1368u);
  EXPECT_EQ(vertices, 986u);
  // The file's first face, f 1/1/1 2/2/2 3/3/3: v 1 = (1.160379 4.512684 6.449167),
  // vt 1 = (0.186192 0.222718) -> uv (0.186192, 1 - 0.222718).
  const Mesh& first = s.meshes[0];
  EXPECT_EQ(first.positions[0], glm::vec3(1.160379f, 4.512684f, 6.449167f));
  EXPECT_NEAR(first.uvs[0].x, 0.186192f, 1e-6f);
  EXPECT_NEAR(first.uvs[0].y, 1.0f - 0.222718f, 1e-6f);
  EXPECT_NO_THROW(validate_scene(s));
}

// import_obj_text (the fuzzer's entry point): the spider from memory, its materials and
// textures found through base_dir, gives the counts above; messages name the given name.
TEST(ObjImportAssimpModels, SpiderFromMemory) {
  const std::string text = read_text(kAssimpObj + "spider.obj");
  const ImportedModel model = import_obj_text(text, "memory spider", kAssimpObj);
  EXPECT_EQ(model.scene.meshes.size(), 19u);
  EXPECT_EQ(model.scene.materials.size(), 5u);
  EXPECT_EQ(model.scene.textures.size(), 5u);
  ASSERT_EQ(model.warnings.size(), 1u) << all_warnings(model);
  EXPECT_NE(model.warnings[0].find("'memory spider' line 1560"), std::string::npos)
      << model.warnings[0];
  // Without its folder, the material library is missing (a warning, as for a file).
  const ImportedModel alone = import_obj_text(text, "memory spider", "/nonexistent");
  EXPECT_NE(all_warnings(alone).find("material library '/nonexistent/spider.mtl' not found"),
            std::string::npos)
      << all_warnings(alone);
  ImportOptions options;
  options.max_file_bytes = 1000;
  try {
    import_obj_text(text, "memory spider", kAssimpObj, options);
    ADD_FAILURE() << "the size limit was not applied";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'memory spider' is "), std::string::npos) << e.what();
  }
}

// awk '$1=="f"{t+=NF-3} END{print t}' WusonOBJ.obj                 -> 3732
// awk '$1=="f"{for(i=2;i<=NF;i++) u[$i]=1} END{...}' WusonOBJ.obj -> 2117 (one group, no usemtl)
TEST(ObjImportAssimpModels, WusonCounts) {
  const ImportedModel model = import_obj(kAssimpObj + "WusonOBJ.obj");
  ASSERT_EQ(model.scene.meshes.size(), 1u);
  EXPECT_EQ(model.scene.meshes[0].triangle_count(), 3732u);
  EXPECT_EQ(model.scene.meshes[0].positions.size(), 2117u);
  EXPECT_EQ(model.scene.materials.size(), 1u);
  EXPECT_TRUE(model.scene.textures.empty());
}

/// A camera and light framing the model's bounding box from the front, above and right.
void frame(Scene& scene) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const Mesh& m : scene.meshes) {
    for (const glm::vec3& p : m.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  const glm::vec3 centre = (lo + hi) * 0.5f;
  const float radius = glm::length(hi - lo) * 0.5f;
  const float fov = glm::radians(40.0f);
  scene.camera.target = centre;
  scene.camera.position =
      centre + glm::normalize(glm::vec3(0.6f, 0.5f, 1.0f)) * (radius / std::sin(fov / 2));
  // The box's corners lie outside most models (the spider's legs), so come closer than the
  // distance that fits the whole sphere.
  scene.camera.position = glm::mix(centre, scene.camera.position, 0.7f);
  scene.camera.vertical_fov = fov;
  scene.camera.near_plane = radius * 0.05f;
  Light sun;
  sun.kind = LightKind::directional;
  sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.6f));
  sun.intensity = 3.0f;
  scene.lights.push_back(sun);
  scene.ambient = glm::vec3(0.15f);
  scene.background = glm::vec3(0.05f, 0.06f, 0.08f);
}

class ObjImportRendering : public test::VulkanTest {};

// Compared with the reference, then kept as a golden image (tests/golden/obj_spider.png).
TEST_F(ObjImportRendering, SpiderAgreesWithTheReference) {
  Scene scene = import_obj(kAssimpObj + "spider.obj").scene;
  frame(scene);
  Renderer renderer(context());
  const test::AccuracyReport r =
      test::expect_reference_and_golden(renderer, scene, 160, 120, "obj_spider");
  EXPECT_GT(r.covered, 160u * 120u / 10) << "the spider fills a good part of the frame";
}

}  // namespace
}  // namespace tessera
