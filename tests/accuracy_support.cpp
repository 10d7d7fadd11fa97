#include "tests/accuracy_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/golden.h"
#include "tests/support/image_assertions.h"

namespace tessera::test {

namespace {

bool meets_bars(const AccuracyReport& r) {
  return r.unexplained == 0 && r.finite && r.ldr.max_abs_error <= kMaxLevelError &&
         r.ldr.fraction_over <= kMaxFractionOverOneLevel;
}

// Compares the frame `renderer` last rendered (with `fs`, `cull`) with the reference.
AccuracyReport compare_rendered(Renderer& renderer, const Scene& scene, const FrameSettings& fs,
                                CullMode cull, const std::string& name,
                                uint32_t environment_samples) {
  const uint32_t width = fs.width;
  const ImageF hdr = renderer.read_hdr();
  const Image8 ldr = renderer.read_ldr();
  const std::vector<uint64_t> vis = renderer.read_visibility();

  ReferenceSettings rs;
  rs.frame = fs;
  rs.cull = cull;
  rs.environment_samples = environment_samples;
  const ReferenceFrame ref = render_reference(scene, rs);

  AccuracyReport r;
  r.name = name;
  r.pixels = vis.size();
  std::vector<uint8_t> agree(vis.size(), 1);
  std::vector<double> relative;
  relative.reserve(3 * vis.size());
  for (size_t i = 0; i < vis.size(); ++i) {
    for (int c = 0; c < 4; ++c) r.finite = r.finite && std::isfinite(hdr.pixels[i][c]);
    const uint32_t gpu = vis[i] == ~0ull ? kNoTriangle : uint32_t(vis[i]);
    r.covered += gpu != kNoTriangle;
    const uint32_t x = uint32_t(i % width), y = uint32_t(i / width);
    if (gpu != ref.owner[i]) {
      agree[i] = 0;
      r.ownership_mismatches++;
      double edge = 1e300;
      double depth_gpu = 0.0, depth_ref = 0.0;
      if (gpu != kNoTriangle) {
        ReferenceProbe p = probe_reference(scene, rs, gpu, x, y);
        edge = std::min(edge, p.edge_distance_px);
        depth_gpu = p.depth;
      }
      if (ref.owner[i] != kNoTriangle) {
        ReferenceProbe p = probe_reference(scene, rs, ref.owner[i], x, y);
        edge = std::min(edge, p.edge_distance_px);
        depth_ref = p.depth;
      }
      if (edge <= kSnapAmbiguityPx) {
        r.explained_by_snapping++;
      } else if (gpu != kNoTriangle && ref.owner[i] != kNoTriangle &&
                 std::abs(depth_gpu - depth_ref) <=
                     kDepthAmbiguity * std::max(depth_gpu, depth_ref)) {
        r.explained_by_depth++;
      } else {
        r.unexplained++;
        if (r.unexplained <= 5) {
          std::printf(
              "%s: unexplained owner at (%u, %u): compute %u, reference %u, edge %.6f px, depths "
              "%.9g %.9g\n",
              name.c_str(), x, y, gpu, ref.owner[i], edge, depth_gpu, depth_ref);
        }
      }
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      const double e = ref.hdr.pixels[i][c];
      relative.push_back(std::abs(double(hdr.pixels[i][c]) - e) / std::max(std::abs(e), 1e-3));
    }
  }
  r.ldr = compare_images(ldr, ref.ldr, 1.0, &agree);
  if (!relative.empty()) {
    // The elements a full sort would put at these places, found by selection: at 4096 x 4096
    // the sort of 50 million errors took a sixth of the test's time. The second selection
    // searches only the part the first left in front (every element there is at most its).
    const auto median = relative.begin() + ptrdiff_t(relative.size() / 2);
    const auto p999 = relative.begin() + ptrdiff_t(double(relative.size() - 1) * 0.999);
    const auto [lo, hi] = std::minmax(median, p999);
    r.hdr_max_relative = *std::max_element(relative.begin(), relative.end());
    std::nth_element(relative.begin(), hi, relative.end());
    std::nth_element(relative.begin(), lo, hi);
    r.hdr_median_relative = *median;
    r.hdr_p999_relative = *p999;
  }
  if (!meets_bars(r)) {
    const std::string stem = name;
    write_png(testing::test_output_path(stem + "_compute.png"), ldr);
    write_png(testing::test_output_path(stem + "_reference.png"), ref.ldr);
    write_png(testing::test_output_path(stem + "_difference.png"),
              difference_image(ldr, ref.ldr, 4.0, &agree));
  }
  std::printf("ACCURACY %s\n", describe(r).c_str());
  return r;
}

}  // namespace

AccuracyReport compare_with_reference(Context& ctx, const Scene& scene, uint32_t width,
                                      uint32_t height, const std::string& name,
                                      RendererOptions options, Brdf brdf, uint32_t anisotropy,
                                      uint32_t environment_samples) {
  Renderer renderer(ctx, options);
  renderer.set_scene(scene);
  FrameSettings fs;
  fs.width = width;
  fs.height = height;
  fs.brdf = brdf;
  fs.max_anisotropy = anisotropy;
  renderer.render(fs);
  return compare_rendered(renderer, scene, fs, options.cull, name, environment_samples);
}

AccuracyReport expect_reference_and_golden(Renderer& renderer, const Scene& scene, uint32_t width,
                                           uint32_t height, const std::string& name) {
  renderer.set_scene(scene);
  FrameSettings fs;
  fs.width = width;
  fs.height = height;
  renderer.render(fs);
  const AccuracyReport r = compare_rendered(renderer, scene, fs, CullMode::back, name, 1024);
  expect_meets_bars(r);
  if (meets_bars(r)) expect_golden(renderer, name);
  return r;
}

void expect_meets_bars(const AccuracyReport& r) {
  EXPECT_TRUE(r.finite) << r.name << ": NaN or Inf in the HDR image";
  EXPECT_EQ(r.unexplained, 0u)
      << r.name << ": ownership differs where neither snapping nor depth precision explains it";
  EXPECT_LE(r.ldr.max_abs_error, kMaxLevelError)
      << r.name << ": 8-bit error too large at (" << r.ldr.worst_x << ", " << r.ldr.worst_y << ")";
  EXPECT_LE(r.ldr.fraction_over, kMaxFractionOverOneLevel)
      << r.name << ": more than 0.01 % of pixels off by 2 levels";
}

std::string describe(const AccuracyReport& r) {
  std::ostringstream s;
  s << r.name << ": " << r.pixels << " px, " << r.covered << " covered, owner mismatches "
    << r.ownership_mismatches << " (snapping " << r.explained_by_snapping << ", depth "
    << r.explained_by_depth << ", unexplained " << r.unexplained << "), 8-bit max "
    << r.ldr.max_abs_error << " levels, " << r.ldr.pixels_over << " px over 1, PSNR "
    << r.ldr.psnr_db << " dB, HDR relative error median " << r.hdr_median_relative << " p99.9 "
    << r.hdr_p999_relative << " max " << r.hdr_max_relative;
  return s.str();
}

}  // namespace tessera::test
