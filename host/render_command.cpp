#include "host/render_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "compute/context.h"
#include "compute/renderer.h"
#include "core/builtin_scenes.h"
#include "core/check.h"
#include "core/image.h"
#include "core/reference_renderer.h"
#include "host/scene_source.h"

namespace tessera {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// What a frame looks like, from the command line (the same for every backend).
FrameSettings settings_of(const RenderArgs& args) {
  FrameSettings settings;
  settings.width = args.width;
  settings.height = args.height;
  settings.exposure_ev = args.exposure_ev;
  settings.tonemap = args.tonemap;
  settings.view = args.view;
  settings.brdf = args.brdf;
  settings.energy_compensation = args.energy_compensation;
  settings.max_anisotropy = args.anisotropy;
  return settings;
}

// The scene with the environment --env asks for; the file's render defaults fill in what the
// command line left unset.
Scene scene_of(RenderArgs& args) {
  SceneFile file = load_scene_argument(args.scene, args.strict, args.quiet);
  const RenderDefaults& r = file.render;
  if (!args.size_given) {
    args.width = r.width.value_or(args.width);
    args.height = r.height.value_or(args.height);
  }
  if (!args.exposure_given) args.exposure_ev = r.exposure_ev.value_or(args.exposure_ev);
  if (!args.tonemap_given) args.tonemap = r.tonemap.value_or(args.tonemap);
  if (!args.brdf_given) args.brdf = r.brdf.value_or(args.brdf);
  Scene scene = std::move(file.scene);
  if (args.env == "none") {
    scene.environment.reset();
  } else if (args.env == "sky") {
    scene.environment = std::make_shared<const Environment>(make_sky_environment(1024));
  } else if (!args.env.empty()) {
    scene.environment = std::make_shared<const Environment>(load_environment(args.env));
  }
  return scene;
}

void write_outputs(const RenderArgs& args, const Image8& ldr, const ImageF& hdr) {
  write_png(args.out, ldr);
  if (!args.hdr_out.empty()) write_hdr_image(args.hdr_out, hdr);
}

// The CPU reference renderer (core/reference_renderer.h): same options, same files.
int run_reference(const Scene& scene, const RenderArgs& args) {
  const FrameSettings frame_settings = settings_of(args);
  ReferenceSettings settings;
  settings.width = frame_settings.width;
  settings.height = frame_settings.height;
  settings.exposure_ev = frame_settings.exposure_ev;
  settings.tonemap = frame_settings.tonemap;
  settings.view = frame_settings.view;
  settings.brdf = frame_settings.brdf;
  settings.energy_compensation = frame_settings.energy_compensation;
  settings.max_anisotropy = frame_settings.max_anisotropy;
  settings.environment_samples = args.env_reference_samples;
  std::vector<double> times;
  ReferenceFrame frame;
  for (uint32_t i = 0; i < args.repeat; ++i) {
    const auto start = std::chrono::steady_clock::now();
    frame = render_reference(scene, settings);
    times.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }
  write_outputs(args, frame.ldr, frame.hdr);
  if (!args.quiet) {
    std::printf("wrote %s (%ux%u, scene '%s', device 'reference (CPU, double precision)')\n",
                args.out.c_str(), args.width, args.height, args.scene.c_str());
    if (!args.hdr_out.empty()) std::printf("wrote %s (linear HDR)\n", args.hdr_out.c_str());
    std::printf("triangles: %llu rasterized\n", (unsigned long long)frame.raster_triangles);
    std::printf("CPU time, median of %u frame%s: %.1f ms\n", args.repeat,
                args.repeat > 1 ? "s" : "", median(times));
  }
  return 0;
}

}  // namespace

int run_render(const RenderArgs& given) {
  RenderArgs args = given;
  const Scene scene = scene_of(args);
  // Check outputs before spending time on a render.
  if (!can_write_file(args.out)) throw Error("cannot write output file '" + args.out + "'");
  if (!args.hdr_out.empty() && !can_write_file(args.hdr_out)) {
    throw Error("cannot write HDR output file '" + args.hdr_out + "'");
  }

  if (args.device == "reference") return run_reference(scene, args);

  ContextOptions options;
  options.device = args.device;
  options.validation = args.validate;
  std::unique_ptr<Context> ctx = create_context(options);
  RendererOptions renderer_options;
  renderer_options.environment = args.env_options;
  Renderer renderer(*ctx, renderer_options);
  renderer.set_scene(scene);

  const FrameSettings settings = settings_of(args);

  std::vector<FrameStats> frames;
  for (uint32_t i = 0; i < args.repeat; ++i) frames.push_back(renderer.render(settings));

  write_outputs(args, renderer.read_ldr(), args.hdr_out.empty() ? ImageF{} : renderer.read_hdr());

  if (!args.quiet) {
    const FrameStats& last = frames.back();
    std::printf("wrote %s (%ux%u, scene '%s', device '%s')\n", args.out.c_str(), args.width,
                args.height, args.scene.c_str(), ctx->properties.deviceName);
    if (!args.hdr_out.empty()) std::printf("wrote %s (linear HDR)\n", args.hdr_out.c_str());
    std::printf(
        "triangles: %llu submitted, %llu rasterized (%llu small, %llu binned), %llu back-facing, "
        "%llu outside, %llu empty, %llu clipped\n",
        (unsigned long long)last.triangles_submitted, (unsigned long long)last.raster_triangles,
        (unsigned long long)last.small_triangles, (unsigned long long)last.big_triangles,
        (unsigned long long)last.culled_backface, (unsigned long long)last.culled_frustum,
        (unsigned long long)last.culled_empty, (unsigned long long)last.clipped);
    if (last.has_timestamps) {
      std::printf("GPU time, median of %u frame%s (ms):", args.repeat, args.repeat > 1 ? "s" : "");
      for (size_t p = 0; p < kPassCount; ++p) {
        std::vector<double> v;
        for (const FrameStats& f : frames) v.push_back(f.pass_ms[p]);
        std::printf(" %s %.3f", pass_name(Pass(p)), median(v));
      }
      std::vector<double> totals;
      for (const FrameStats& f : frames) totals.push_back(f.gpu_total_ms);
      std::printf(" | total %.3f\n", median(totals));
      const double precompute = frames.front().pass_ms[size_t(Pass::environment)];
      if (precompute > 0.0) {
        std::printf(
            "environment precomputation (DFG tables, irradiance, prefiltered cube), first "
            "frame only: %.3f ms\n",
            precompute);
      }
    } else {
      std::printf("GPU timings unavailable: the queue has no timestamp support\n");
    }
  }
  if (ctx->validation && (ctx->validation->errors || ctx->validation->warnings)) {
    std::fprintf(stderr, "validation reported %u errors and %u warnings\n",
                 ctx->validation->errors.load(), ctx->validation->warnings.load());
    return 3;
  }
  return 0;
}

}  // namespace tessera
