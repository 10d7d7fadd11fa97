#include "host/render_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "compute/context.h"
#include "compute/renderer.h"
#include "core/builtin_scenes.h"
#include "core/check.h"
#include "core/image.h"
#include "core/reference_renderer.h"
#include "core/statistics.h"
#include "host/heap_reuse.h"
#include "host/report.h"
#include "host/scene_source.h"
#include "host/stop_signal.h"
#include "host/tradeoff.h"

namespace tessera {
namespace {

// The scene with the environment --env asks for; the file's render defaults fill in what the
// command line left unset. `size_place` is where the file gave the size, if it did;
// `env_removed` whether the scene had an environment that --env none took away.
Scene scene_of(RenderArgs& args, std::string& size_place, bool& env_removed) {
  SceneFile file = load_scene_argument(args.scene, args.strict, args.quiet);
  if (args.camera_given) use_model_camera(file, args.camera, "tessera render --help");
  apply_render_defaults(file.render, args.frame, args.size_given, args.exposure_given,
                        args.tonemap_given, args.brdf_given, args.view_given);
  if (!args.size_given) size_place = file.render.size_place;
  frame_model_camera(file.scene, args.scene, args.camera_given, args.frame.width,
                     args.frame.height);
  Scene scene = std::move(file.scene);
  if (args.env == "none") {
    env_removed = scene.environment != nullptr;
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
  if (args.hdr_out.empty()) return;
  write_hdr_image(args.hdr_out, hdr);
  // fp16 saturates at its largest finite value: the file holds exactly what the image held, but
  // a radiance brighter than that is lost (a new user's trial found most of an image clamped).
  if (args.frame.hdr_format != HdrFormat::fp16 || args.quiet) return;
  constexpr float kHalfMax = 65504.0f;
  size_t clamped = 0;
  for (const glm::vec4& p : hdr.pixels)
    for (int c = 0; c < 3; ++c) clamped += p[c] >= kHalfMax;
  if (clamped > 0) {
    std::fprintf(stderr,
                 "tessera: note: %zu of %zu colour values of %s are 65504, the largest an fp16 "
                 "HDR image holds: brighter radiance was clamped there (--hdr-format fp32 keeps "
                 "it, or lower the lights)\n",
                 clamped, hdr.pixels.size() * 3, args.hdr_out.c_str());
  }
}

// The settings of --quality's preset, as the frame used them (the options given and the scene
// file included): nothing else shows what the preset chose. The CPU reference (`compute`
// false) has no prefiltered environment or tiles.
void print_written(const RenderArgs& args, const std::string& device, bool compute) {
  std::printf("wrote %s (%ux%u, scene '%s', device '%s')\n", args.out.c_str(), args.frame.width,
              args.frame.height, args.scene.c_str(), device.c_str());
  if (!args.hdr_out.empty()) std::printf("wrote %s (linear HDR)\n", args.hdr_out.c_str());
  if (args.quality != Quality::none)
    std::printf("%s\n", quality_settings_line(args.quality, args.frame,
                                              compute ? &args.env_options : nullptr, args.tile_size)
                            .c_str());
}

// The --repeat frames after the first: `render_one()` for each of `count`, stopping early
// at Ctrl+C or SIGTERM (host/stop_signal.h), so that the frames rendered are still reported
// and the image written; with `progress`, a line every 2 s or more, as frames can take seconds
// each on the CPU. Returns the frames rendered and, if one stopped them, the signal.
struct RepeatedFrames {
  uint32_t rendered = 0;
  int interrupted = 0;
};
template <class RenderOne>
RepeatedFrames render_repeated(uint32_t count, bool progress, RenderOne&& render_one) {
  catch_stop_signals();
  RepeatedFrames done;
  using Clock = std::chrono::steady_clock;
  auto last_line = Clock::now();
  for (; done.rendered < count; ++done.rendered) {
    if ((done.interrupted = stop_signal()) != 0) break;
    render_one();
    if (progress && Clock::now() - last_line >= std::chrono::seconds(2)) {
      std::printf("rendered %u of %u frames after the first\n", done.rendered + 1, count);
      last_line = Clock::now();
    }
  }
  return done;  // a signal during the last frame stopped nothing: every frame was rendered
}

// What an interrupted --repeat prints (standard error), and the exit status it gives.
int report_interrupted(const RepeatedFrames& done, uint32_t count) {
  std::fprintf(stderr,
               "tessera: interrupted by %s after %u of %u frames after the first: the image and "
               "the times of the frames rendered are written and printed\n",
               stop_signal_name(done.interrupted), done.rendered, count);
  return interrupted_exit_status(done.interrupted);
}

// The CPU reference renderer (core/reference_renderer.h): same options, same files.
int run_reference(const Scene& scene, const RenderArgs& args) {
  ReferenceSettings settings;
  settings.frame = args.frame;
  settings.environment_samples = args.env_reference_samples;
  // The first frame also pays what later frames find in place (the energy-compensation
  // tables, built once per process, and the heap's pages), so it is reported apart, as the
  // Vulkan devices' first frame is; the --repeat frames after it are rendered only when asked
  // for (RenderArgs::repeat_given): each is the whole CPU render again.
  const uint32_t repeat = args.repeat_given ? args.repeat : 0;
  keep_freed_memory_for_reuse();  // each frame freed before the next takes its pages
  std::vector<double> times;
  ReferenceFrame frame;
  const auto render_one = [&] {
    frame = ReferenceFrame{};
    const auto start = std::chrono::steady_clock::now();
    frame = render_reference(scene, settings);
    times.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  };
  render_one();
  const RepeatedFrames done =
      repeat ? render_repeated(repeat, !args.quiet, render_one) : RepeatedFrames{};
  const double first_ms = times.front();
  times.erase(times.begin());
  write_outputs(args, frame.ldr, frame.hdr);
  if (!args.quiet) {
    print_written(args, "reference (CPU, double precision)", false);
    std::printf("triangles: %llu rasterized\n", (unsigned long long)frame.raster_triangles);
    std::printf(
        "CPU time, first frame, including one-time setup that later frames reuse: %.1f ms\n",
        first_ms);
    if (!times.empty()) {
      const Summary time = summarize(times);
      std::printf("CPU time, median of %zu frame%s after the first: %.1f ms", time.count,
                  time.count > 1 ? "s" : "", time.median);
      if (time.count > 1) std::printf(" (min %.1f, max %.1f)", time.min, time.max);
      std::printf("\n");
    }
  }
  return done.interrupted ? report_interrupted(done, repeat) : 0;
}

// A scene whose objects all fell to culling draws only the background, with status 0: a black
// or empty image is otherwise a puzzle (a flat model seen edge-on, a mesh wound the other way,
// a camera looking away).
std::string nothing_drawn_note(const FrameStats& frame, const std::string& name) {
  if (frame.triangles_submitted == 0 || frame.raster_triangles > 0) return "";
  std::string why;
  const auto add = [&](uint64_t count, const char* what) {
    if (count == 0) return;
    why += (why.empty() ? "" : ", ") + std::to_string(count) + " " + what;
  };
  add(frame.culled_backface, "back-facing (a material's double_sided draws them)");
  add(frame.culled_frustum, "outside the view");
  add(frame.culled_empty, "empty (no pixel centre inside, or zero area: seen edge-on)");
  return "note: no triangle of " + name + " was drawn, of " +
         std::to_string(frame.triangles_submitted) + " submitted: " + why +
         "; the image shows only the background";
}

void print_frames(const RenderArgs& args, const Context& ctx, const FrameStats& first,
                  const std::vector<FrameStats>& timed) {
  const FrameStats& last = timed.empty() ? first : timed.back();  // empty: stopped at once
  print_written(args, ctx.properties.deviceName, true);
  // A frame rasterized and shaded in one pass sorts nothing into small and binned triangles
  // (RendererOptions::raster_shade).
  if (last.rasterized_and_shaded) {
    std::printf(
        "triangles: %llu submitted, %llu rasterized and shaded in one pass (a small frame), "
        "%llu back-facing, %llu outside, %llu empty, %llu clipped\n",
        (unsigned long long)last.triangles_submitted, (unsigned long long)last.raster_triangles,
        (unsigned long long)last.culled_backface, (unsigned long long)last.culled_frustum,
        (unsigned long long)last.culled_empty, (unsigned long long)last.clipped);
  } else {
    std::printf(
        "triangles: %llu submitted, %llu rasterized (%llu small, %llu binned in %llu bin entries), "
        "%llu back-facing, %llu outside, %llu empty, %llu clipped\n",
        (unsigned long long)last.triangles_submitted, (unsigned long long)last.raster_triangles,
        (unsigned long long)last.small_triangles,
        (unsigned long long)(last.raster_triangles -
                             std::min(last.small_triangles, last.raster_triangles)),
        (unsigned long long)last.big_triangles, (unsigned long long)last.culled_backface,
        (unsigned long long)last.culled_frustum, (unsigned long long)last.culled_empty,
        (unsigned long long)last.clipped);
    std::printf("depth rejection: %llu of %llu tile entries, %llu of %llu small triangles\n",
                (unsigned long long)last.rejected_entries, (unsigned long long)last.tile_entries,
                (unsigned long long)last.rejected_small, (unsigned long long)last.small_triangles);
  }
  if (last.tile_list_stride > 0) {
    std::printf("tile lists: direct, room for %u entries a tile\n", last.tile_list_stride);
  } else {
    std::printf("tile lists: counted\n");
  }
  if (last.shaded_tiles + last.background_tiles > 0) {
    std::printf("shading by tiles: %llu of %llu tiles shaded, the rest background only\n",
                (unsigned long long)last.shaded_tiles,
                (unsigned long long)(last.shaded_tiles + last.background_tiles));
  }
  if (!last.has_timestamps) {
    std::printf("GPU timings unavailable: the queue has no timestamp support\n");
    return;
  }
  print_pass_times(
      "GPU time, first frame, including pipeline compilation and other first-use costs", {first});
  if (!timed.empty()) {
    print_pass_times("GPU time, median of " + std::to_string(timed.size()) + " frame" +
                         (timed.size() > 1 ? "s" : "") + " after the first",
                     timed);
  }
  const double precompute = first.precompute_ms;
  if (precompute > 0.0) {
    std::printf(
        "precomputation (the background's colours; DFG tables, irradiance and prefiltered cube "
        "where used), first frame only: %.3f ms\n",
        precompute);
  }
}

// The options given that this render does not use, each with why: they were accepted without
// a word (a new user's trial), so a value typed in to change the image changed nothing.
std::vector<std::string> ignored_options(const RenderArgs& a, const Scene& scene) {
  std::vector<std::string> out;
  if (a.lod_error_given && a.frame.lod != Lod::automatic)
    out.push_back("--lod-error: level of detail is off for this render (--lod auto turns it on)");
  const auto unused = [&](bool given, const char* option, const char* knob) {
    if (!given) return;
    if (const std::string why = knob_cannot_matter(knob, scene, a.frame); !why.empty())
      out.push_back(std::string(option) + ": " + why);
  };
  unused(a.anisotropy_given, "--anisotropy", "anisotropy");
  unused(a.env_size_given, "--env-size", "env-size");
  unused(a.env_samples_given, "--env-samples", "env-samples");
  unused(a.env_reference_samples_given, "--env-reference-samples", "env-samples");
  if (a.device == "reference") {
    if (a.validate)
      out.push_back("--validate: --device reference makes no Vulkan calls to validate");
    for (const auto& [given, option] : {std::pair{a.depth_rejection_given, "--depth-rejection"},
                                        {a.shade_tiles_given, "--shade-tiles"},
                                        {a.tile_lists_given, "--tile-lists"},
                                        {a.raster_shade_given, "--raster-shade"}}) {
      if (given)
        out.push_back(std::string(option) +
                      ": it tunes the Vulkan devices' passes; --device reference has none");
    }
  }
  if (!scene.environment) return out;
  // The reference integrates the environment by sampling; the compute path prefilters it.
  const bool reference = a.device == "reference";
  if (a.env_reference_samples_given && !reference)
    out.push_back("--env-reference-samples: only --device reference samples the environment");
  for (const auto& [given, option] :
       {std::pair{a.env_size_given, "--env-size"}, {a.env_samples_given, "--env-samples"}}) {
    if (given && reference)
      out.push_back(std::string(option) +
                    ": --device reference samples the environment itself "
                    "(--env-reference-samples)");
  }
  return out;
}

}  // namespace

int run_render(const RenderArgs& given) {
  RenderArgs args = given;
  std::string size_place;
  bool env_removed = false;
  const Scene scene = scene_of(args, size_place, env_removed);
  // Said before the render, which may take long: a black image is otherwise a puzzle.
  if (const std::string note = unlit_scene_note(scene, args.scene, args.frame.view, env_removed);
      !note.empty() && !args.quiet)
    std::fprintf(stderr, "tessera: %s\n", note.c_str());
  // The reference computes in double: the grain is the GPU's.
  if (const std::string note = coarse_positions_note(scene, args.scene);
      !note.empty() && !args.quiet && args.device != "reference")
    std::fprintf(stderr, "tessera: %s\n", note.c_str());
  // The reference floors the distance as the GPU does.
  if (const std::string note = near_lights_note(scene, args.scene); !note.empty() && !args.quiet)
    std::fprintf(stderr, "tessera: %s\n", note.c_str());
  if (!args.quiet)
    for (const std::string& why : ignored_options(args, scene))
      std::fprintf(stderr, "tessera: warning: %s; the option changes nothing\n", why.c_str());
  // Check outputs before spending time on a render.
  if (std::string why = unwritable_reason(args.out); !why.empty()) {
    throw Error("cannot write output file '" + args.out + "': " + why);
  }
  if (std::string why = args.hdr_out.empty() ? "" : unwritable_reason(args.hdr_out); !why.empty()) {
    throw Error("cannot write HDR output file '" + args.hdr_out + "': " + why);
  }

  if (args.device == "reference") return run_reference(scene, args);

  ContextOptions options;
  options.device = args.device;
  options.validation = args.validate;
  std::unique_ptr<Context> ctx = create_context(options);
  RendererOptions renderer_options = tuned_for_device(*ctx, {});
  renderer_options.environment = args.env_options;
  renderer_options.tile_size = args.tile_size;
  if (args.depth_rejection_given) renderer_options.depth_rejection = args.depth_rejection;
  if (args.shade_tiles_given) renderer_options.shade_tiles = args.shade_tiles;
  if (args.raster_shade_given) renderer_options.raster_shade = args.raster_shade;
  if (args.tile_lists_given) renderer_options.tile_lists = args.tile_lists;
  Renderer renderer(*ctx, renderer_options);
  try {
    renderer.set_scene(scene);
  } catch (const SceneSizeError& e) {
    throw Error(args.scene + ": " + e.what());  // which scene is too large for this device
  }

  const FrameSettings& settings = args.frame;

  // The first frame pays for what the driver defers to first use (compiling pipelines,
  // allocating) and for precomputing the environment; it is reported apart from the others.
  FrameStats first;
  try {
    first = renderer.render(settings);
  } catch (const ImageSizeError& e) {
    throw_image_size_error(
        with_samples_source(e, args.quality, args.samples_given, settings.samples), args.size_given,
        size_place, "tessera render --help");
  }
  std::vector<FrameStats> timed;
  const RepeatedFrames done = render_repeated(args.repeat, !args.quiet && args.repeat_given,
                                              [&] { timed.push_back(renderer.render(settings)); });

  write_outputs(args, renderer.read_ldr(), args.hdr_out.empty() ? ImageF{} : renderer.read_hdr());
  if (!args.quiet) {
    print_frames(args, *ctx, first, timed);
    const FrameStats& last = timed.empty() ? first : timed.back();
    if (const std::string note = nothing_drawn_note(last, args.scene); !note.empty())
      std::fprintf(stderr, "tessera: %s\n", note.c_str());
  }
  const int validation = validation_exit_status(ctx.get());
  if (done.interrupted) {
    const int status = report_interrupted(done, args.repeat);
    return validation != 0 ? validation : status;
  }
  return validation;
}

}  // namespace tessera
