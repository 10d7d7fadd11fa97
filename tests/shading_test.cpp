// The shading model: the GPU's BRDF against the formulas, reciprocity, the energy a
// single-scattering GGX lobe loses, and every light type and BRDF variant against the
// reference renderer.
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "compute/baselines/brdf_probe.h"
#include "compute/pipelines.h"
#include "core/builtin_scenes.h"
#include "core/image_metrics.h"
#include "core/reference_renderer.h"
#include "shaders/shader_registry.h"
#include "tests/accuracy_support.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr Brdf kVariants[] = {Brdf::classic, Brdf::filament, Brdf::blinn_phong};
const char* variant_name(Brdf b) {
  return b == Brdf::classic ? "classic" : b == Brdf::filament ? "filament" : "blinn-phong";
}

class Shading : public test::VulkanTest {};

glm::vec3 random_upper_direction(std::mt19937& rng, float min_cos) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float z = min_cos + (1.0f - min_cos) * u(rng);
  const float phi = 2.0f * float(kPi) * u(rng);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

std::vector<BrdfSample> random_samples(uint32_t seed, size_t count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<BrdfSample> samples;
  const float extremes[] = {0.0f, 1.0f};
  for (size_t i = 0; i < count; ++i) {
    BrdfSample s;
    s.n = {0.0f, 0.0f, 1.0f};
    s.v = random_upper_direction(rng, 0.02f);
    s.l = random_upper_direction(rng, 0.02f);
    s.material.base_color = {u(rng), u(rng), u(rng)};
    s.material.metallic = i % 3 == 0 ? extremes[i % 2] : u(rng);
    // Rough enough that fp32 and double agree to 1e-4 away from the peak (see the next test).
    s.material.roughness = i % 5 == 0 ? 1.0f : 0.2f + 0.8f * u(rng);
    samples.push_back(s);
  }
  return samples;
}

TEST_F(Shading, GpuBrdfMatchesTheFormulas) {
  const std::vector<BrdfSample> samples = random_samples(3, 4000);
  for (Brdf variant : kVariants) {
    const std::vector<glm::vec3> gpu = evaluate_brdf_on_gpu(context(), variant, samples);
    double worst = 0.0;
    for (size_t i = 0; i < samples.size(); ++i) {
      const BrdfSample& s = samples[i];
      const glm::dvec3 expected =
          reference_brdf(variant, glm::dvec3(s.n), glm::dvec3(s.v), glm::dvec3(s.l), s.material) *
          double(glm::dot(s.n, s.l));
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst,
                         std::abs(gpu[i][c] - expected[c]) / std::max(std::abs(expected[c]), 1e-3));
      }
    }
    std::printf("BRDF %s: worst relative difference to the formulas %.2e\n", variant_name(variant),
                worst);
    EXPECT_LT(worst, 1e-4) << variant_name(variant);
  }
}

TEST_F(Shading, BrdfIsReciprocal) {
  std::vector<BrdfSample> samples = random_samples(11, 2000);
  std::vector<BrdfSample> swapped = samples;
  for (BrdfSample& s : swapped) std::swap(s.v, s.l);
  for (Brdf variant : kVariants) {
    const std::vector<glm::vec3> a = evaluate_brdf_on_gpu(context(), variant, samples);
    const std::vector<glm::vec3> b = evaluate_brdf_on_gpu(context(), variant, swapped);
    double worst = 0.0;
    for (size_t i = 0; i < samples.size(); ++i) {
      // The probe returns f * N.L; f(l, v) = a / (n.l) and f(v, l) = b / (n.v).
      const glm::vec3 f_lv = a[i] / glm::dot(samples[i].n, samples[i].l);
      const glm::vec3 f_vl = b[i] / glm::dot(samples[i].n, samples[i].v);
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst,
                         double(std::abs(f_lv[c] - f_vl[c]) / std::max(std::abs(f_lv[c]), 1e-3f)));
      }
    }
    std::printf("BRDF %s: worst reciprocity error %.2e\n", variant_name(variant), worst);
    EXPECT_LT(worst, 1e-5) << variant_name(variant);
  }
}

// Directional albedo of a white metal (F = 1) under uniform light, averaged over view
// directions with the cosine weight: the energy a single-scattering lobe keeps. Midpoint rule
// in (cos theta, phi) for the light, 24 view angles; the same sum over the double-precision
// formulas must agree, and both must match the published losses (shared/RESEARCH.md): for the
// height-correlated Smith term, 12 % at alpha = 0.25, 30 % at 0.5 and 59 % at 1.
double average_albedo(const std::vector<glm::vec3>& values, int views, int mus, int phis) {
  double total = 0.0;
  for (int iv = 0; iv < views; ++iv) {
    const double mu_o = (iv + 0.5) / views;
    double e = 0.0;
    for (int k = 0; k < mus * phis; ++k) e += values[size_t(iv) * mus * phis + k].x;
    e *= (1.0 / mus) * (2.0 * kPi / phis);  // d omega = d cos(theta) d phi
    total += e * 2.0 * mu_o / views;        // E_avg = 2 * integral of E(mu) mu d mu
  }
  return total;
}

TEST_F(Shading, SingleScatteringEnergyLossMatchesTheLiterature) {
  const int views = 24, mus = 160, phis = 96;
  const struct {
    float alpha;
    double published_loss;
  } cases[] = {{0.25f, 0.12}, {0.5f, 0.30}, {1.0f, 0.59}};
  for (const auto& c : cases) {
    std::vector<BrdfSample> samples;
    for (int iv = 0; iv < views; ++iv) {
      const float mu_o = (iv + 0.5f) / views;
      const glm::vec3 v(std::sqrt(1.0f - mu_o * mu_o), 0.0f, mu_o);
      for (int im = 0; im < mus; ++im) {
        const float mu = (im + 0.5f) / mus;
        for (int ip = 0; ip < phis; ++ip) {
          const float phi = 2.0f * float(kPi) * (ip + 0.5f) / phis;
          const float r = std::sqrt(1.0f - mu * mu);
          BrdfSample s;
          s.n = {0, 0, 1};
          s.v = v;
          s.l = {r * std::cos(phi), r * std::sin(phi), mu};
          s.material = {glm::vec3(1.0f), 1.0f, std::sqrt(c.alpha)};
          samples.push_back(s);
        }
      }
    }
    const std::vector<glm::vec3> gpu = evaluate_brdf_on_gpu(context(), Brdf::filament, samples);
    std::vector<glm::vec3> exact(samples.size());
    for (size_t i = 0; i < samples.size(); ++i) {
      const BrdfSample& s = samples[i];
      exact[i] = glm::vec3(reference_brdf(Brdf::filament, glm::dvec3(s.n), glm::dvec3(s.v),
                                          glm::dvec3(s.l), s.material) *
                           double(s.l.z));
    }
    const double kept_gpu = average_albedo(gpu, views, mus, phis);
    const double kept_exact = average_albedo(exact, views, mus, phis);
    std::printf("alpha %.2f: energy kept %.4f (GPU) %.4f (formulas), published loss %.0f %%\n",
                c.alpha, kept_gpu, kept_exact, c.published_loss * 100);
    EXPECT_NEAR(kept_gpu, kept_exact, 1e-4);
    EXPECT_NEAR(1.0 - kept_exact, c.published_loss, 0.02) << "alpha " << c.alpha;
  }
}

TEST_F(Shading, EveryLightTypeAndVariantAgreesWithTheReference) {
  for (Brdf variant : kVariants) {
    test::AccuracyReport r =
        test::compare_with_reference(context(), make_lights_scene(), 320, 200,
                                     std::string("lights_") + variant_name(variant), {}, variant);
    test::expect_meets_bars(r);
  }
}

TEST_F(Shading, VariantsAgreeWithTheReferenceAtRoughnessZeroAndOne) {
  for (Brdf variant : {Brdf::filament, Brdf::blinn_phong}) {
    test::AccuracyReport r =
        test::compare_with_reference(context(), make_sphere_grid_scene(), 256, 256,
                                     std::string("spheres_") + variant_name(variant), {}, variant);
    test::expect_meets_bars(r);
  }
}

TEST_F(Shading, EmissiveAndOcclusionAddAndDimByHand) {
  // No lights: every covered pixel is ambient * base * occlusion + emissive.
  Scene scene = make_sphere_grid_scene();
  scene.lights.clear();
  scene.ambient = glm::vec3(0.2f);
  for (Material& m : scene.materials) {
    m.base_color = glm::vec3(0.5f);
    m.occlusion = 0.5f;
    m.emissive = {1.0f, 2.0f, 3.0f};
  }
  Frame f = render(scene, 96, 96);
  size_t covered = 0;
  for (size_t i = 0; i < f.hdr.pixels.size(); ++i) {
    if (f.visibility[i] == ~0ull) continue;
    ++covered;
    for (int c = 0; c < 3; ++c) {
      const float expected = 0.2f * 0.5f * 0.5f + float(c + 1);
      ASSERT_NEAR(f.hdr.pixels[i][c], expected, expected * 1e-3f) << "pixel " << i;  // fp16 storage
    }
  }
  EXPECT_GT(covered, 1000u);
}

TEST_F(Shading, EmissiveAndOccludedMaterialsAgreeWithTheReference) {
  Scene scene = make_lights_scene();
  scene.materials[1].emissive = {0.6f, 0.1f, 0.0f};
  scene.materials[2].occlusion = 0.2f;
  scene.ambient = glm::vec3(0.3f);
  test::AccuracyReport r =
      test::compare_with_reference(context(), scene, 320, 200, "emissive_occlusion");
  test::expect_meets_bars(r);
}

// A pipeline whose scene samples no texture map is built from a module compiled without the
// texture code (lavapipe translates and inlines a module whole before specialization would
// remove it); every other from the shader's own. The images are the same:
// SpecializedAndGenericShadingGiveTheSameImage below compares the generic pipeline (every map,
// the textured module) with the specialized one (no map, the untextured module) on four scenes
// without maps, and the golden images did not change.
TEST(ShaderModules, ScenesWithoutMapsBuildFromModulesWithoutTextureCode) {
  Specialization none;
  none.texture_maps = 0;
  EXPECT_EQ(shader_module("shade", none), "shade_untextured");
  EXPECT_EQ(shader_module("raster_shade", none), "raster_shade_untextured");
  EXPECT_EQ(shader_module("setup", none), "setup");  // no texture code, no variant
  Specialization wrap_modes_only = none;
  wrap_modes_only.texture_maps = TS_MAP_WRAP_MODES;  // a mode of no sampled map: nothing to sample
  EXPECT_EQ(shader_module("shade", wrap_modes_only), "shade_untextured");
  Specialization samples = none;
  samples.samples = 4;
  EXPECT_EQ(shader_module("shade", samples), "shade_samples_untextured");

  Specialization normal_map = none;
  normal_map.texture_maps = TS_MAP_NORMAL;
  EXPECT_EQ(shader_module("shade", normal_map), "shade");
  normal_map.samples = 4;
  EXPECT_EQ(shader_module("shade", normal_map), "shade_samples");
  EXPECT_EQ(shader_module("shade", Specialization{}), "shade");  // generic: every map

  // The variants hold less code: the texture functions are gone, not merely unreached.
  for (const char* name : {"shade", "shade_samples", "raster_shade"}) {
    const size_t textured = find_shader(name).size();
    const size_t untextured = find_shader(std::string(name) + "_untextured").size();
    EXPECT_GT(untextured, 0u) << name;
    EXPECT_LT(untextured, textured * 9 / 10) << name;
  }
}

TEST_F(Shading, SpecializedAndGenericShadingGiveTheSameImage) {
  RendererOptions generic;
  generic.specialize_lights = false;
  // One renderer of each kind for every scene: their pipelines cost more than the frames.
  Renderer specialized_renderer(context()), generic_renderer(context(), generic);
  for (const char* name : {"spheres", "lights", "metals", "textured", "environment"}) {
    Frame a = render(specialized_renderer, make_builtin_scene(name), 160, 120);
    Frame b = render(generic_renderer, make_builtin_scene(name), 160, 120);
    EXPECT_EQ(a.ldr.pixels, b.ldr.pixels) << name;
    double worst = 0.0;
    for (size_t i = 0; i < a.hdr.pixels.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, double(std::abs(a.hdr.pixels[i][c] - b.hdr.pixels[i][c])) /
                                    std::max(1e-3, double(std::abs(b.hdr.pixels[i][c]))));
      }
    }
    EXPECT_LT(worst, 1e-3) << name << ": within one fp16 step";
  }
}

// White furnace with compensation: a white metal's specular lobe scaled by 1 / E from the GPU's
// DFG table (bilinear, as lighting.glsl reads it) keeps E_exact / E_table of the energy, where
// E_exact is the reference's own quadrature. Within 1 % of 1 at every roughness and angle.
TEST_F(Shading, EnergyCompensationRestoresTheFurnaceWithinOnePercent) {
  Renderer renderer(context());
  renderer.set_scene(make_sphere_grid_scene());
  FrameSettings fs;
  fs.width = fs.height = 16;
  fs.energy_compensation = true;
  renderer.render(fs);  // computes the tables
  const std::vector<glm::vec4> table = renderer.read_dfg_table();
  const int n = 64;                                  // TS_DFG_SIZE
  ASSERT_EQ(table.size(), size_t(2 * (n + 1) * n));  // two tables, then a row of means each
  auto lookup = [&](int variant, double n_dot_v, double roughness) {
    const double px = std::clamp(n_dot_v, 0.0, 1.0) * (n - 1),
                 py = std::clamp(roughness, 0.0, 1.0) * (n - 1);
    const int x0 = int(px), y0 = int(py), x1 = std::min(x0 + 1, n - 1),
              y1 = std::min(y0 + 1, n - 1);
    const double tx = px - x0, ty = py - y0;
    auto at = [&](int x, int y) { return double(table[size_t((variant * n + y) * n + x)].y); };
    return (at(x0, y0) * (1 - tx) + at(x1, y0) * tx) * (1 - ty) +
           (at(x0, y1) * (1 - tx) + at(x1, y1) * tx) * ty;
  };
  for (int variant = 0; variant < 2; ++variant) {
    const Brdf brdf = variant == 0 ? Brdf::classic : Brdf::filament;
    double worst = 0.0, lowest_e = 1.0;
    for (double roughness : {0.05, 0.1, 0.25, 0.4, 0.5, 0.6, 0.75, 0.9, 1.0}) {
      for (double n_dot_v : {0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 0.85, 1.0}) {
        const double e = reference_specular_albedo(brdf, n_dot_v, roughness);
        lowest_e = std::min(lowest_e, e);
        const double err = std::abs(e / lookup(variant, n_dot_v, roughness) - 1.0);
        if (err > 0.01)
          std::printf("  r %.2f nv %.2f: E %.4f table %.4f\n", roughness, n_dot_v, e,
                      lookup(variant, n_dot_v, roughness));
        worst = std::max(worst, err);
      }
    }
    std::printf(
        "%s: compensated white furnace within %.2f %% of 1 (uncompensated energy down to %.3f)\n",
        variant_name(brdf), worst * 100.0, lowest_e);
    EXPECT_LT(worst, 0.01) << variant_name(brdf);
    // The means over N.V that the diffuse layer divides by (rows after the tables), against
    // the reference's own quadrature of them.
    double worst_mean = 0.0;
    for (int row : {3, 16, 32, 48, 63}) {
      const glm::dvec3 expected = reference_specular_albedo_table(brdf, row / 63.0).means;
      const glm::vec4 got = table[size_t(2 * n * n + variant * n + row)];
      for (int c = 0; c < 3; ++c)
        worst_mean = std::max(worst_mean, std::abs(got[c] / expected[c] - 1.0));
    }
    std::printf("%s: means of E, E_Fc, E_Fc / E within %.2f %% of the reference\n",
                variant_name(brdf), worst_mean * 100.0);
    EXPECT_LT(worst_mean, 0.01) << variant_name(brdf);
  }
}

TEST_F(Shading, EnergyCompensatedRendersAgreeWithTheReference) {
  for (Brdf variant : {Brdf::classic, Brdf::filament}) {
    Scene scene = make_lights_scene();
    Renderer renderer(context());
    renderer.set_scene(scene);
    FrameSettings fs;
    fs.width = 160;
    fs.height = 100;
    fs.brdf = variant;
    fs.energy_compensation = true;
    renderer.render(fs);
    const Image8 gpu = renderer.read_ldr();
    fs.energy_compensation = false;
    renderer.render(fs);
    const Image8 uncompensated = renderer.read_ldr();
    ReferenceSettings rs;
    rs.frame.width = fs.width;
    rs.frame.height = fs.height;
    rs.frame.brdf = variant;
    rs.frame.energy_compensation = true;
    const ReferenceFrame ref = render_reference(scene, rs);
    const ImageDifference d = compare_images(gpu, ref.ldr, 1.0);
    std::printf("%s with compensation: 8-bit max %.0f, %zu px over 1 level, PSNR %.1f dB\n",
                variant_name(variant), d.max_abs_error, d.pixels_over, d.psnr_db);
    EXPECT_LE(d.max_abs_error, 2.0);
    EXPECT_LE(d.fraction_over, 1e-3);
    // And it does something: rough metals get brighter.
    EXPECT_GT(compare_images(gpu, uncompensated, 0.0).pixels_over, 100u);
  }
}

}  // namespace
}  // namespace tessera
