// Texture maps: mip chains and filtering against hand calculation, tangents, the textured
// scene against the reference, anisotropic filtering against a supersampled ground truth, and
// normal maps that tilt the normal below the horizon.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "core/builtin_scenes.h"
#include "core/check.h"
#include "core/image.h"
#include "core/mesh.h"
#include "core/procedural_textures.h"
#include "core/reference_renderer.h"
#include "core/texture.h"
#include "tests/accuracy_support.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

Texture texture_of(uint32_t w, uint32_t h, std::vector<glm::u8vec4> texels, bool srgb = false) {
  Texture t;
  t.width = w;
  t.height = h;
  t.texels = std::move(texels);
  t.srgb = srgb;
  return t;
}

// A texture file whose header says it is over the largest side is refused from its header,
// before decoding (tests/data/huge_header.png: a 68-byte RGB PNG that claims 17000 x 17000; a real
// one took 7 s and 1.4 GB to decode before it was refused). huge_header_100000.png (69 bytes)
// claims 100000 x 100000, whose header stb_image refuses itself (over 2^30 bytes), saying "too
// large" or, asked for the image's size, "unknown image type": the size is read from the PNG's
// IHDR chunk instead.
// A PNG cut short is said to be (stb_image's own reason is the tag "outofdata").
TEST(TextureMaps, TruncatedFileSaysItEndsEarly) {
  Image8 image{64, 64, std::vector<glm::u8vec4>(64 * 64)};
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = glm::u8vec4(uint8_t(i * 7), uint8_t(i * 13), uint8_t(i), 255);
  const std::string whole = test::output_path("whole.png");
  write_png(whole, image);
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes(std::istreambuf_iterator<char>(in), {});
  const std::string cut = test::output_path("cut.png");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  try {
    load_texture(cut, true);
    ADD_FAILURE() << "no error for a truncated PNG";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "cannot read texture '" + cut + "': the data ends early (a truncated file?)");
  }
}

TEST(TextureMaps, OversizedFileIsRefusedFromItsHeader) {
  for (const auto& [file, size] : {std::pair{"huge_header.png", "17000x17000"},
                                   std::pair{"huge_header_100000.png", "100000x100000"}}) {
    const std::string path = std::string(TESSERA_TEST_DATA_DIR) + "/" + file;
    try {
      load_texture(path, true);
      ADD_FAILURE() << "loaded " << path;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), "texture '" + path + "' is " + size +
                                           ", over the largest side of " +
                                           std::to_string(kMaxTextureSide));
    }
  }
}

TEST(TextureMaps, SrgbDecodingMatchesTheStandard) {
  EXPECT_EQ(srgb_to_linear(0), 0.0);
  EXPECT_EQ(srgb_to_linear(255), 1.0);
  // IEC 61966-2-1: 10/255 is on the linear segment; 128/255 on the power segment.
  EXPECT_NEAR(srgb_to_linear(10), (10.0 / 255.0) / 12.92, 1e-12);
  EXPECT_NEAR(srgb_to_linear(128), 0.2158605, 1e-6);
}

TEST(TextureMaps, MipLevelsAverageInLinearSpace) {
  // 2x2 sRGB: black and white texels. Level 1 is their linear mean, 0.5 (not sRGB 128/255).
  const glm::u8vec4 b(0, 0, 0, 255), w(255, 255, 255, 255);
  const MipChain chain = build_mip_chain(texture_of(2, 2, {b, w, w, b}, true));
  ASSERT_EQ(chain.levels.size(), 2u);
  EXPECT_FLOAT_EQ(chain.levels[1].texels[0].r, 0.5f);
  // 5x3: levels 2x1 and 1x1 (sides halve, rounding down, never below 1).
  const MipChain odd = build_mip_chain(texture_of(5, 3, std::vector<glm::u8vec4>(15, w)));
  ASSERT_EQ(odd.levels.size(), 3u);
  EXPECT_EQ(odd.levels[1].width, 2u);
  EXPECT_EQ(odd.levels[1].height, 1u);
  EXPECT_EQ(odd.levels[2].width, 1u);
}

TEST(TextureMaps, FilteringByHand) {
  // 2x1 texture: red 0 and 1. At u = 0.25 (texel 0's centre) bilinear gives texel 0; at
  // u = 0.5, halfway between the centres, 0.5; at u = 0 the repeat wrap mixes texels 1 and 0.
  const MipChain chain =
      build_mip_chain(texture_of(2, 1, {glm::u8vec4(0, 0, 0, 255), glm::u8vec4(255, 0, 0, 255)}));
  const glm::dvec2 tiny(1e-6, 0.0);  // footprint far below a texel: level 0
  EXPECT_NEAR(sample_texture(chain, {0.25, 0.5}, tiny, glm::dvec2(0.0, 1e-6), 1).r, 0.0, 1e-12);
  EXPECT_NEAR(sample_texture(chain, {0.5, 0.5}, tiny, glm::dvec2(0.0, 1e-6), 1).r, 0.5, 1e-12);
  EXPECT_NEAR(sample_texture(chain, {0.0, 0.5}, tiny, glm::dvec2(0.0, 1e-6), 1).r, 0.5, 1e-12);
  // A footprint of 2 texels per pixel: lod log2(2) = 1, the 1x1 level, the mean 0.5.
  EXPECT_NEAR(sample_texture(chain, {0.25, 0.5}, {1.0, 0.0}, {0.0, 0.5}, 1).r, 0.5, 1e-12);
  // An infinite footprint (an edge-on triangle): the coarsest level.
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_NEAR(sample_texture(chain, {0.25, 0.5}, {inf, 0.0}, {0.0, 0.0}, 1).r, 0.5, 1e-12);
}

TEST(TextureMaps, WrapModesByHand) {
  // The 2x1 texture of FilteringByHand, red 0 and 1, outside [0, 1] (v stays inside).
  // u = 1.6: repeat reads u = 0.6, texel coordinate 0.6 * 2 - 0.5 = 0.7 between the centres,
  // 0.7; clamp to edge reads u = 1, coordinate 1.5, texel 1 and the clamped texel 2 -> 1, so 1;
  // mirrored repeat reads 2 - 1.6 = 0.4, coordinate 0.3, so 0.3.
  // u = -0.4: repeat 0.6 -> 0.7; clamp 0 -> coordinate -0.5, texels -1 and 0 -> both 0, so 0;
  // mirrored -0.4 + 2 = 1.6 -> 2 - 1.6 = 0.4 -> 0.3.
  struct Case {
    TextureWrap mode;
    double at_1_6, at_minus_0_4;
  };
  for (const Case& c :
       {Case{TextureWrap::repeat, 0.7, 0.7}, Case{TextureWrap::clamp_to_edge, 1.0, 0.0},
        Case{TextureWrap::mirrored_repeat, 0.3, 0.3}}) {
    Texture t = texture_of(2, 1, {glm::u8vec4(0, 0, 0, 255), glm::u8vec4(255, 0, 0, 255)});
    t.wrap_u = c.mode;
    t.wrap_v = TextureWrap::clamp_to_edge;
    const MipChain chain = build_mip_chain(t);
    const glm::dvec2 tiny(1e-6, 0.0), tiny_v(0.0, 1e-6);
    EXPECT_NEAR(sample_texture(chain, {1.6, 0.5}, tiny, tiny_v, 1).r, c.at_1_6, 1e-9)
        << int(c.mode);
    EXPECT_NEAR(sample_texture(chain, {-0.4, 0.5}, tiny, tiny_v, 1).r, c.at_minus_0_4, 1e-9)
        << int(c.mode);
    // Far outside, v clamps to the only row and u stays defined.
    EXPECT_TRUE(std::isfinite(sample_texture(chain, {1e30, -1e30}, tiny, tiny_v, 1).r));
  }
}

TEST(TextureMaps, TangentsFollowTheUvs) {
  // make_plane: u along +x, v along -y (down the image), normal +z: tangent +x, bitangent
  // -y = -cross(n, t), w = -1.
  const Mesh plane = make_plane(2, 2);
  ASSERT_EQ(plane.tangents.size(), plane.positions.size());
  for (const glm::vec4& t : plane.tangents) {
    EXPECT_NEAR(t.x, 1.0f, 1e-6f);
    EXPECT_NEAR(t.y, 0.0f, 1e-6f);
    EXPECT_EQ(t.w, -1.0f);
  }
  // Mirrored v (along +y): the bitangent is cross(n, t), so w = 1.
  Mesh flipped = plane;
  for (glm::vec2& uv : flipped.uvs) uv.y = 1.0f - uv.y;
  for (const glm::vec4& t :
       generate_tangents(flipped.positions, flipped.normals, flipped.uvs, flipped.indices)) {
    EXPECT_EQ(t.w, 1.0f);
  }
  // Every sphere tangent is unit and orthogonal to its normal, poles included.
  const Mesh sphere = make_uv_sphere(16, 8);
  for (size_t v = 0; v < sphere.positions.size(); ++v) {
    const glm::vec3 t(sphere.tangents[v]);
    EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, sphere.normals[v]), 0.0f, 1e-5f);
  }
}

TEST(TextureMaps, BadTexturesAreNamed) {
  Scene scene = make_builtin_scene("textured");
  scene.materials[1].normal_map = 99;
  try {
    validate_scene(scene);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("texture 99 as its normal map"), std::string::npos)
        << e.what();
  }
  scene = make_builtin_scene("textured");
  scene.textures[0].texels.pop_back();
  EXPECT_THROW(validate_scene(scene), Error);
  scene = make_builtin_scene("textured");
  scene.meshes[0].tangents.pop_back();
  EXPECT_THROW(validate_scene(scene), Error);
  try {
    load_texture("/nonexistent/bricks.png", true);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/bricks.png"), std::string::npos);
  }
}

TEST(TextureMaps, LoadsWhatWasWritten) {
  Image8 image{3, 2, {}};
  for (int i = 0; i < 6; ++i) image.pixels.push_back(glm::u8vec4(i * 40, 255 - i * 40, 7, 255));
  const std::string path = test::output_path("texture.png");
  write_png(path, image);
  const Texture t = load_texture(path, true);
  EXPECT_EQ(t.width, 3u);
  EXPECT_EQ(t.height, 2u);
  EXPECT_EQ(t.texels, image.pixels);
  EXPECT_TRUE(t.srgb);
}

class TexturedRendering : public test::VulkanTest {};

TEST_F(TexturedRendering, TexturedSceneAgreesWithTheReference) {
  for (uint32_t anisotropy : {1u, 8u}) {
    const test::AccuracyReport r = test::compare_with_reference(
        context(), make_builtin_scene("textured"), 200, 150,
        "textured_aniso" + std::to_string(anisotropy), {}, Brdf::classic, anisotropy);
    std::printf("%s\n", test::describe(r).c_str());
    test::expect_meets_bars(r);
  }
}

// The textured scene with its uvs spread over [-1, 2] (so that two thirds of each surface
// lies outside the texture) and its textures clamping in u and mirroring in v: the compute path
// agrees with the reference, and differs from the repeating scene over much of the image.
TEST_F(TexturedRendering, WrapModesAgreeWithTheReference) {
  Scene repeating = make_builtin_scene("textured");
  for (Mesh& m : repeating.meshes) {
    for (glm::vec2& uv : m.uvs) uv = uv * 3.0f - 1.0f;
  }
  Scene wrapped = repeating;
  for (Texture& t : wrapped.textures) {
    t.wrap_u = TextureWrap::clamp_to_edge;
    t.wrap_v = TextureWrap::mirrored_repeat;
  }
  const test::AccuracyReport r =
      test::compare_with_reference(context(), wrapped, 160, 120, "textured_wrap_modes");
  std::printf("%s\n", test::describe(r).c_str());
  test::expect_meets_bars(r);
  const Image8 a = render(repeating, 160, 120).ldr, b = render(wrapped, 160, 120).ldr;
  size_t differing = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) differing += a.pixels[i] != b.pixels[i];
  EXPECT_GT(differing, a.pixels.size() / 10) << "the wrap modes changed too few pixels";
}

// A plane at a grazing angle under a fine checkerboard: the ideal pixel value is the mean of
// the texture over the pixel's footprint. Ground truth: the reference at 16 x 16 samples per
// pixel, box-filtered; each sample filters its own 16x smaller footprint (anisotropically, so
// that the truth is not blurred at the horizon). Anisotropic filtering must come closer to it
// than trilinear, which blurs along the footprint's short axis too.
TEST_F(TexturedRendering, AnisotropicFilteringIsCloserToTheSupersampledTruth) {
  Scene scene;
  scene.camera.position = {0.0f, 0.6f, 4.0f};
  scene.camera.target = {0.0f, 0.0f, -6.0f};
  scene.ambient = glm::vec3(1.0f);  // unlit: the ambient term shows the base colour as it is
  scene.meshes.push_back(make_plane(1, 1));
  scene.textures.push_back(make_checker_texture(512, 64, glm::vec3(1.0f), glm::vec3(0.0f)));
  Material m{glm::vec3(1.0f), 0.0f, 1.0f};
  m.base_color_map = 0;
  scene.materials.push_back(m);
  scene.objects.push_back(
      {0, 0,
       glm::scale(glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(1, 0, 0)),
                  glm::vec3(8.0f))});
  const uint32_t w = 96, h = 64, ss = 16;
  ReferenceSettings truth_settings;
  truth_settings.frame.width = w * ss;
  truth_settings.frame.height = h * ss;
  truth_settings.frame.max_anisotropy = 16;
  const ReferenceFrame fine = render_reference(scene, truth_settings);
  std::vector<glm::dvec3> truth(size_t(w) * h, glm::dvec3(0.0));
  for (uint32_t y = 0; y < h * ss; ++y) {
    for (uint32_t x = 0; x < w * ss; ++x) {
      truth[size_t(y / ss) * w + x / ss] += glm::dvec3(fine.hdr.at(x, y)) / double(ss * ss);
    }
  }
  std::vector<double> errors;
  std::printf("anisotropy, RMS error against the 16x16 supersampled truth (linear):");
  for (uint32_t anisotropy : {1u, 2u, 4u, 16u}) {
    Renderer renderer(context());
    renderer.set_scene(scene);
    FrameSettings fs;
    fs.width = w;
    fs.height = h;
    fs.max_anisotropy = anisotropy;
    renderer.render(fs);
    const ImageF hdr = renderer.read_hdr();
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < truth.size(); ++i) {
      if (fine.owner[(i / w) * ss * w * ss + (i % w) * ss] == kNoTriangle) continue;  // sky
      const double d = hdr.pixels[i].r - truth[i].r;
      sum += d * d;
      ++n;
    }
    const double rmse = std::sqrt(sum / double(n));
    std::printf(" %u: %.4f", anisotropy, rmse);
    errors.push_back(rmse);
  }
  std::printf("\n");
  EXPECT_LT(errors[1], errors[0]) << "2 probes should beat trilinear";
  EXPECT_LT(errors[3], 0.5 * errors[0]) << "16 probes should at least halve trilinear's error";
}

// A normal map with steep slopes (strength 12) at a sphere's silhouette tilts many mapped
// normals away from the viewer: they are bent back above the horizon, never NaN, and the
// reference agrees.
TEST_F(TexturedRendering, NormalMapsTiltingBelowTheHorizonStayFinite) {
  Scene scene = make_builtin_scene("textured");
  TileMaps steep = make_tile_maps(256, 8, glm::vec3(0.7f), 12.0f);
  scene.textures[3] = steep.normal;
  const test::AccuracyReport r =
      test::compare_with_reference(context(), scene, 160, 120, "steep_normal_map");
  std::printf("%s\n", test::describe(r).c_str());
  test::expect_meets_bars(r);
}

}  // namespace
}  // namespace tessera
