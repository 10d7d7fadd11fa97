// Where the grid's 1-sample error against the ground truth comes from (issue 12;
// docs/tradeoffs.md, "The grid family"): renders the lavapipe chart's scene (grid, 100
// spheres, 128 x 72) on the compute path and the CPU reference in several ways, prints which
// pixels carry the mean relative error and what those pixels integrate to, and with a second
// argument writes false-colour images of the per-pixel error. Not a benchmark: a diagnostic,
// kept so that the figures in the docs can be made again.
//
//   grid_error_probe [OBJECTS [PREFIX]]   (lavapipe; about 30 s on one core)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "compute/context.h"
#include "compute/renderer.h"
#include "core/bench_scenes.h"
#include "core/image.h"
#include "core/image_metrics.h"
#include "core/pick.h"
#include "core/reference_brdf.h"
#include "core/reference_renderer.h"

using namespace tessera;

namespace {

double brightest(glm::vec4 v) {
  return std::max({std::abs(double(v.r)), std::abs(double(v.g)), std::abs(double(v.b))});
}

// radiance_error's per-pixel terms (core/image_metrics.cpp), kept apart; `guard` receives
// its denominator floor.
std::vector<double> per_pixel_errors(const ImageF& a, const ImageF& e, double* guard) {
  double sum = 0.0;
  for (const glm::vec4& p : e.pixels) sum += brightest(p);
  *guard = 0.01 * sum / double(e.pixels.size());
  std::vector<double> out;
  for (size_t i = 0; i < e.pixels.size(); ++i) {
    double err = 0.0;
    for (int c = 0; c < 3; ++c)
      err = std::max(err, std::abs(double(a.pixels[i][c]) - double(e.pixels[i][c])));
    out.push_back(err / std::max(brightest(e.pixels[i]), *guard));
  }
  return out;
}

void summary(const char* name, const ImageF& a, const ImageF& truth) {
  double guard = 0.0;
  const std::vector<double> err = per_pixel_errors(a, truth, &guard);
  const double total = std::accumulate(err.begin(), err.end(), 0.0);
  std::vector<double> sorted = err;
  std::sort(sorted.rbegin(), sorted.rend());
  auto share = [&](size_t k) {
    return std::accumulate(sorted.begin(), sorted.begin() + ptrdiff_t(k), 0.0) / total;
  };
  std::printf(
      "%-34s mean %.4f  share of the worst 1: %.3f, 2: %.3f, 10: %.3f  max %.1f  mean without "
      "the worst 2: %.4f\n",
      name, total / double(err.size()), share(1), share(2), share(10), sorted[0],
      (total - sorted[0] - sorted[1]) / double(err.size() - 2));
}

std::string rgb(glm::vec4 v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.4f %.4f %.4f)", v.r, v.g, v.b);
  return b;
}

struct Ray {
  glm::dvec3 origin, dir;
};

// The reference's camera ray through the point (px, py) of the image, in pixels
// (core/reference_renderer.cpp, camera_ray_at).
Ray camera_ray(const Camera& c, uint32_t width, uint32_t height, double px, double py) {
  const glm::dvec3 eye(c.position), forward = glm::normalize(glm::dvec3(c.target) - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(c.up)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tan_y = std::tan(double(c.vertical_fov) / 2.0), tan_x = tan_y * width / height;
  return {eye, glm::normalize(forward + (px / width * 2.0 - 1.0) * tan_x * right -
                              (py / height * 2.0 - 1.0) * tan_y * up)};
}

// The spheres a ray through pixel (x, y) can meet: those within 1.5 radii of its centre ray
// (a pixel spans about 0.3 units at the grid's distance).
std::vector<const Object*> candidates_of(const Scene& scene, uint32_t width, uint32_t height,
                                         uint32_t x, uint32_t y) {
  const Ray r = camera_ray(scene.camera, width, height, x + 0.5, y + 0.5);
  std::vector<const Object*> out;
  for (const Object& o : scene.objects) {
    const glm::dvec3 k = glm::dvec3(o.transform[3]) - r.origin;
    if (glm::length(k - glm::dot(k, r.dir) * r.dir) < 1.5) out.push_back(&o);
  }
  return out;
}

struct PixelIntegral {
  glm::dvec3 radiance{0.0};
  double bright_fraction = 0.0;  // of the positions brighter than `bright` (red)
  double bright_share = 0.0;     // of the red they carry
};

// Pixel (x, y)'s radiance averaged over n x n stratified positions, written here from the
// scene (unit spheres intersected exactly, point lights, ambient, no shadows: the reference's
// shading model for the grid, with its BRDF functions), apart from the reference renderer, to
// see what the truth's 8 x 8 positions make of a pixel.
PixelIntegral integrate_pixel(const Scene& scene, uint32_t width, uint32_t height, uint32_t x,
                              uint32_t y, uint32_t n, double bright = 0.0) {
  const std::vector<const Object*> candidates = candidates_of(scene, width, height, x, y);
  PixelIntegral out;
  double bright_red = 0.0;
  size_t bright_count = 0;
  for (uint32_t j = 0; j < n; ++j) {
    for (uint32_t i = 0; i < n; ++i) {
      const Ray r = camera_ray(scene.camera, width, height, x + (i + 0.5) / n, y + (j + 0.5) / n);
      double best = std::numeric_limits<double>::infinity();
      const Object* hit = nullptr;
      for (const Object* o : candidates) {
        const glm::dvec3 k = glm::dvec3(o->transform[3]) - r.origin;
        const double b = glm::dot(k, r.dir), disc = b * b - (glm::dot(k, k) - 1.0);
        if (disc < 0.0) continue;
        const double t = b - std::sqrt(disc);
        if (t > 0.0 && t < best) best = t, hit = o;
      }
      glm::dvec3 colour(scene.background);
      if (hit) {
        const Material& m = scene.materials[hit->material];
        const glm::dvec3 p = r.origin + best * r.dir;
        const glm::dvec3 normal = glm::normalize(p - glm::dvec3(hit->transform[3]));
        colour = glm::dvec3(scene.ambient) * glm::dvec3(m.base_color);
        for (const Light& light : scene.lights) {
          const glm::dvec3 to_light = glm::dvec3(light.position) - p;
          const double d2 = glm::dot(to_light, to_light);
          const glm::dvec3 l = to_light / std::sqrt(d2);
          const double n_dot_l = glm::dot(normal, l);
          if (n_dot_l <= 0.0) continue;
          const BrdfLobes f = reference_brdf_lobes(Brdf::classic, normal, -r.dir, l, m);
          colour += (f.diffuse + f.specular) * glm::dvec3(light.color) * double(light.intensity) /
                    d2 * n_dot_l;
        }
      }
      out.radiance += colour;
      if (bright > 0.0 && colour.r > bright) bright_count++, bright_red += colour.r;
    }
  }
  out.bright_fraction = double(bright_count) / double(n * n);
  out.bright_share = bright_red / out.radiance.r;
  out.radiance /= double(n * n);
  return out;
}

// The truth converged: each pixel on 32 x 32 and 64 x 64 positions, and on 256 x 256 where
// those differ by more than 1 % or a near-mirror sphere is in reach (its highlights can fall
// between both grids' positions).
ImageF converged_truth(const Scene& scene, uint32_t width, uint32_t height, size_t* refined) {
  ImageF out{width, height, std::vector<glm::vec4>(size_t(width) * height)};
  *refined = 0;
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      const glm::dvec3 a = integrate_pixel(scene, width, height, x, y, 32).radiance;
      glm::dvec3 b = integrate_pixel(scene, width, height, x, y, 64).radiance;
      bool smooth = false;
      for (const Object* o : candidates_of(scene, width, height, x, y))
        smooth = smooth || scene.materials[o->material].roughness < 0.1f;
      const double diff = std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
      if (smooth || diff > 0.01 * std::max({b.r, b.g, b.b})) {
        b = integrate_pixel(scene, width, height, x, y, 256).radiance;
        ++*refined;
      }
      out.pixels[size_t(y) * width + x] = glm::vec4(glm::vec3(b), 1.0f);
    }
  }
  return out;
}

// log10 of the relative error as colour: black up to 0.001, then blue (0.01), green (0.1),
// yellow (1), red (10 to 100), white (1000 and above); each pixel `scale` x `scale`.
Image8 error_image(const std::vector<double>& err, uint32_t width, uint32_t height,
                   uint32_t scale) {
  const glm::vec3 stops[] = {{0, 0, 0}, {0, 0, 1}, {0, 0.8f, 0}, {1, 1, 0},
                             {1, 0, 0}, {1, 0, 0}, {1, 1, 1}};
  Image8 out{width * scale, height * scale,
             std::vector<glm::u8vec4>(size_t(width) * height * scale * scale)};
  for (uint32_t y = 0; y < out.height; ++y) {
    for (uint32_t x = 0; x < out.width; ++x) {
      const double e = err[size_t(y / scale) * width + x / scale];
      const double t = std::clamp(std::log10(std::max(e, 1e-3)) + 3.0, 0.0, 6.0);
      const int k = std::min(int(t), 5);
      const glm::vec3 c = glm::mix(stops[k], stops[k + 1], float(t - k));
      out.pixels[size_t(y) * out.width + x] = glm::u8vec4(glm::round(c * 255.0f), 255);
    }
  }
  return out;
}

// The display image of `hdr` as the frames' default resolve makes it: ACES (Narkowicz 2015)
// then sRGB (IEC 61966-2-1), exposure 0.
Image8 display_image(const ImageF& hdr) {
  Image8 out{hdr.width, hdr.height, std::vector<glm::u8vec4>(hdr.pixels.size())};
  for (size_t i = 0; i < hdr.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double x = hdr.pixels[i][c];
      const double t = std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
      const double s = t <= 0.0031308 ? 12.92 * t : 1.055 * std::pow(t, 1.0 / 2.4) - 0.055;
      out.pixels[i][c] = uint8_t(std::lround(s * 255.0));
    }
    out.pixels[i].a = 255;
  }
  return out;
}

// Pixels [x0, x0 + size) x [y0, y0 + size) of `image`, each `scale` x `scale`.
Image8 crop(const Image8& image, uint32_t x0, uint32_t y0, uint32_t size, uint32_t scale) {
  Image8 out{size * scale, size * scale,
             std::vector<glm::u8vec4>(size_t(size * scale) * size * scale)};
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x)
      out.pixels[size_t(y) * out.width + x] =
          image.pixels[size_t(y0 + y / scale) * image.width + x0 + x / scale];
  return out;
}

// The images side by side, 4 px of grey between them; all of one height.
Image8 side_by_side(const std::vector<Image8>& images) {
  Image8 out{0, images[0].height, {}};
  for (const Image8& i : images) out.width += i.width + (out.width ? 4 : 0);
  out.pixels.assign(size_t(out.width) * out.height, glm::u8vec4(128, 128, 128, 255));
  uint32_t x0 = 0;
  for (const Image8& i : images) {
    for (uint32_t y = 0; y < i.height; ++y)
      for (uint32_t x = 0; x < i.width; ++x)
        out.pixels[size_t(y) * out.width + x0 + x] = i.pixels[size_t(y) * i.width + x];
    x0 += i.width + 4;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const uint32_t width = 128, height = 72;
  const uint32_t objects = argc > 1 ? uint32_t(std::stoul(argv[1])) : 100;
  const Scene scene = make_bench_scene("grid", objects, 32, float(width) / float(height));
  FrameSettings frame;
  frame.width = width;
  frame.height = height;

  // The truth as host/tradeoff_measure.cpp makes it (the grid has no environment).
  ReferenceSettings truth;
  truth.frame = frame;
  truth.frame.max_anisotropy = 16;
  truth.frame.hdr_format = HdrFormat::fp32;
  truth.ground_truth.analytic_spheres = true;
  truth.ground_truth.supersampling = 8;
  const ReferenceFrame t = render_reference(scene, truth);
  double guard = 0.0;
  per_pixel_errors(t.hdr, t.hdr, &guard);
  std::printf("truth: mean of the brightest channel %.5f, guard (1 %% of it) %.6f\n", guard / 0.01,
              guard);

  // The compute path on lavapipe: 1 sample, level of detail at 0.25 px, 4 samples.
  ContextOptions co;
  co.device = "lavapipe";
  auto ctx = create_context(co);
  Renderer renderer(*ctx);
  renderer.set_scene(scene);
  renderer.render(frame);
  const ImageF compute = renderer.read_hdr();
  const Image8 compute_ldr = renderer.read_ldr();
  const std::vector<uint64_t> keys = renderer.read_visibility();
  const ObjectNumbering numbering = renderer.triangle_numbering();
  FrameSettings lod_frame = frame;
  lod_frame.lod = Lod::automatic;
  lod_frame.lod_error_px = 0.25f;
  renderer.render(lod_frame);
  const ImageF compute_lod = renderer.read_hdr();
  FrameSettings aa_frame = frame;
  aa_frame.samples = 4;
  renderer.render(aa_frame);
  const ImageF compute_aa = renderer.read_hdr();

  // The reference at 1 sample: the meshes (rasterized by the compute path's rules), and the
  // exact spheres; and the meshes supersampled as the truth is.
  ReferenceSettings ref;
  ref.frame = frame;
  const ReferenceFrame mesh1 = render_reference(scene, ref);
  ReferenceSettings exact1 = truth;
  exact1.ground_truth.supersampling = 1;
  const ReferenceFrame sphere1 = render_reference(scene, exact1);
  ReferenceSettings mesh8 = truth;
  mesh8.ground_truth.analytic_spheres = false;
  const ReferenceFrame mesh_ss = render_reference(scene, mesh8);

  std::printf("\nagainst the truth (exact spheres, 8 x 8 positions per pixel):\n");
  summary("compute, 1 sample", compute, t.hdr);
  summary("compute, lod 0.25 px", compute_lod, t.hdr);
  summary("compute, 4 samples", compute_aa, t.hdr);
  summary("reference mesh, 1 sample", mesh1.hdr, t.hdr);
  summary("reference exact spheres, 1 sample", sphere1.hdr, t.hdr);
  summary("reference mesh, 8x8 positions", mesh_ss.hdr, t.hdr);
  summary("compute against reference mesh 1", compute, mesh1.hdr);

  // The pixels carrying the compute image's error.
  const std::vector<double> err = per_pixel_errors(compute, t.hdr, &guard);
  std::vector<size_t> order(err.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return err[a] > err[b]; });
  const double total = std::accumulate(err.begin(), err.end(), 0.0);
  std::printf("\nthe compute image's worst pixels (share of the summed error):\n");
  for (size_t k = 0; k < 6; ++k) {
    const size_t i = order[k];
    const std::optional<uint32_t> tri = triangle_of_key(keys[i]);
    std::string owners;
    for (size_t s = t.ownership.first[i]; s < t.ownership.first[i + 1]; ++s) {
      const OwnerShare o = t.ownership.shares[s];
      owners += (o.object == kNoObject ? std::string("bg") : "slot " + std::to_string(o.object)) +
                " x" + std::to_string(o.samples) + " ";
    }
    std::printf(
        "(%u,%u) error %.2f (%.3f): compute %s, triangle %s of object %s | truth %s [%s] | "
        "reference mesh 1 %s | exact sphere 1 %s\n",
        uint32_t(i % width), uint32_t(i / width), err[i], err[i] / total,
        rgb(compute.pixels[i]).c_str(), tri ? std::to_string(*tri).c_str() : "-",
        tri ? std::to_string(object_of_triangle(numbering, *tri)).c_str() : "-",
        rgb(t.hdr.pixels[i]).c_str(), owners.c_str(), rgb(mesh1.hdr.pixels[i]).c_str(),
        rgb(sphere1.hdr.pixels[i]).c_str());
  }

  // The normal each sees at the worst pixels' centres: the mesh's interpolated over the
  // triangle the compute path drew, the exact sphere's; and how far each is from the half
  // vector of the light it comes closest to (the GGX lobe's width is alpha = 0.045^2 rad).
  for (size_t k = 0; k < 2; ++k) {
    const uint32_t x = uint32_t(order[k] % width), y = uint32_t(order[k] / width);
    const uint32_t tri = *triangle_of_key(keys[order[k]]);
    const uint32_t object = object_of_triangle(numbering, tri);
    size_t slot = 0;
    while (numbering.objects[slot] != object) ++slot;
    const Object& o = scene.objects[object];
    const Mesh& mesh = scene.meshes[o.mesh];
    const size_t local = size_t(tri - numbering.first_triangle[slot]);
    const glm::dvec3 centre(o.transform[3]);
    glm::dvec3 p[3], n[3];
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = mesh.indices[local * 3 + size_t(c)];
      p[c] = glm::dvec3(mesh.positions[v]) + centre;
      n[c] = glm::dvec3(mesh.normals[v]);
    }
    const Ray r = camera_ray(scene.camera, width, height, x + 0.5, y + 0.5);
    const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0], q = glm::cross(r.dir, e2);
    const double det = glm::dot(e1, q);
    const double u = glm::dot(r.origin - p[0], q) / det;
    const double w = glm::dot(r.dir, glm::cross(r.origin - p[0], e1)) / det;
    const glm::dvec3 mesh_n = glm::normalize((1.0 - u - w) * n[0] + u * n[1] + w * n[2]);
    const glm::dvec3 k2 = centre - r.origin;
    const double b = glm::dot(k2, r.dir);
    const glm::dvec3 hit = r.origin + (b - std::sqrt(b * b - glm::dot(k2, k2) + 1.0)) * r.dir;
    const glm::dvec3 sphere_n = glm::normalize(hit - centre);
    auto to_half = [&](glm::dvec3 normal) {
      double best = 10.0;
      for (const Light& l : scene.lights) {
        const glm::dvec3 h = glm::normalize(glm::normalize(glm::dvec3(l.position) - hit) - r.dir);
        best = std::min(best, std::acos(std::min(1.0, glm::dot(normal, h))));
      }
      return best * 1000.0;
    };
    std::printf(
        "(%u,%u): triangle %zu of the mesh, barycentrics (%.3f %.3f %.3f); normals "
        "%.2f mrad apart; from the nearest half vector: mesh %.2f mrad, sphere %.2f mrad "
        "(alpha %.2f mrad)\n",
        x, y, local, 1.0 - u - w, u, w,
        1000.0 * std::acos(std::min(1.0, glm::dot(mesh_n, sphere_n))), to_half(mesh_n),
        to_half(sphere_n), 1000.0 * 0.045 * 0.045);
  }

  // The chart's interior figure: pixels all of whose truth positions see one object.
  std::vector<uint8_t> interior(err.size());
  for (size_t i = 0; i < err.size(); ++i)
    interior[i] = t.ownership.first[i + 1] - t.ownership.first[i] == 1;
  const RadianceError in = radiance_error(compute, t.hdr, &interior);
  std::printf("interior: %zu pixels, mean %.4f, of it the worst 2 pixels %.4f\n", in.pixels,
              in.mean_relative,
              (interior[order[0]] * err[order[0]] + interior[order[1]] * err[order[1]]) /
                  double(in.pixels));  // both far above either guard: the same terms

  // What the worst pixels integrate to on ever finer grids (n = 1: the centre; 8: the truth's).
  for (size_t k = 0; k < 3; ++k) {
    const uint32_t x = uint32_t(order[k] % width), y = uint32_t(order[k] / width);
    const std::optional<uint32_t> tri = triangle_of_key(keys[order[k]]);
    const Material& m =
        scene.materials[scene.objects[object_of_triangle(numbering, *tri)].material];
    const PixelIntegral fine = integrate_pixel(scene, width, height, x, y, 2048, 10.0);
    std::printf(
        "\npixel (%u,%u): roughness %.3f, metallic %.3f; positions brighter than 10 "
        "(of 2048 x 2048): %.2e of the pixel (%.4f px across if a disc), %.1f %% of its "
        "red\n  red channel on n x n positions:",
        x, y, m.roughness, m.metallic, fine.bright_fraction,
        2.0 * std::sqrt(fine.bright_fraction / 3.14159265358979), 100.0 * fine.bright_share);
    for (uint32_t n : {1u, 8u, 16u, 32u, 64u, 128u, 256u, 512u, 1024u, 2048u})
      std::printf(" %u: %.4f", n, integrate_pixel(scene, width, height, x, y, n).radiance.r);
    std::printf("\n");
  }

  size_t refined = 0;
  const ImageF converged = converged_truth(scene, width, height, &refined);
  std::printf("\nagainst the converged truth (%zu pixels refined to 256 x 256):\n", refined);
  summary("truth (8x8)", t.hdr, converged);
  summary("compute, 1 sample", compute, converged);
  summary("compute, lod 0.25 px", compute_lod, converged);
  summary("compute, 4 samples", compute_aa, converged);
  summary("reference exact spheres, 1 sample", sphere1.hdr, converged);

  {
    const std::vector<double> e8 = per_pixel_errors(t.hdr, converged, &guard);
    const size_t worst = size_t(std::max_element(e8.begin(), e8.end()) - e8.begin());
    std::printf(
        "truth pixels more than 5 %% off: %zu; the worst, (%zu,%zu): truth %s, converged "
        "%s\n",
        size_t(std::count_if(e8.begin(), e8.end(), [](double e) { return e > 0.05; })),
        worst % width, worst / width, rgb(t.hdr.pixels[worst]).c_str(),
        rgb(converged.pixels[worst]).c_str());
  }
  if (argc > 2) {
    const std::string prefix = argv[2];
    write_png(prefix + "_image.png", compute_ldr);
    write_png(prefix + "_error.png", error_image(err, width, height, 4));
    write_png(prefix + "_error_converged.png",
              error_image(per_pixel_errors(compute, converged, &guard), width, height, 4));
    // Around the worst pixel: the compute image, the truth, the converged truth, the error
    // against the truth.
    const uint32_t size = 16, scale = 10;
    const uint32_t cx = uint32_t(order[0] % width), cy = uint32_t(order[0] / width);
    const uint32_t x0 = std::min(cx - std::min(cx, size / 2), width - size);
    const uint32_t y0 = std::min(cy - std::min(cy, size / 2), height - size);
    std::printf("crop: x %u..%u, y %u..%u\n", x0, x0 + size - 1, y0, y0 + size - 1);
    write_png(
        prefix + "_crop.png",
        side_by_side({crop(compute_ldr, x0, y0, size, scale), crop(t.ldr, x0, y0, size, scale),
                      crop(display_image(converged), x0, y0, size, scale),
                      crop(error_image(err, width, height, 1), x0, y0, size, scale)}));
  }
  return 0;
}
