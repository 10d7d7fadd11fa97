// Measuring `tessera tradeoff`: the compute path at every knob setting, interleaved in rounds,
// and the ground truths from the CPU reference renderer (docs/accuracy.md, "Ground truth").
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>

#include <unistd.h>

#include "core/bench_scenes.h"
#include "core/check.h"
#include "core/lod.h"
#include "core/mesh.h"
#include "core/pareto.h"
#include "core/pick.h"
#include "core/reference_renderer.h"
#include "core/warmup.h"
#include "host/report.h"
#include "host/scene_source.h"
#include "host/stop_signal.h"
#include "host/tradeoff.h"

namespace tessera {
namespace {

// `scene` with every sphere remade with `segments` slices (0: unchanged).
Scene with_sphere_segments(const Scene& scene, uint32_t segments) {
  Scene out = scene;
  if (segments == 0) return out;
  for (Mesh& mesh : out.meshes) {
    if (mesh.analytic_sphere) mesh = make_uv_sphere(segments, segments / 2);
  }
  return out;
}

// Which object (index into Scene::objects, kNoObject for none) each pixel of a compute frame
// shows, from its visibility buffer (numbered by the levels of detail the frame chose).
Ownership compute_ownership(const Renderer& renderer, uint32_t width, uint32_t height) {
  const ObjectNumbering numbering = renderer.triangle_numbering();
  const std::vector<uint64_t> keys = renderer.read_visibility();
  std::vector<uint32_t> objects(keys.size());
  for (size_t i = 0; i < keys.size(); ++i) {
    const std::optional<uint32_t> o = pick_object(numbering, keys[i]);
    objects[i] = o ? *o : kNoObject;
  }
  // FrameSettings::samples keys per pixel, each pixel's together.
  return make_ownership(width, height, uint32_t(keys.size() / (size_t(width) * height)), objects);
}

// The reference's ownership is by ObjectNumbering slot; the compute one's by Scene::objects.
Ownership by_scene_object(Ownership ownership, const Scene& scene) {
  const ObjectNumbering numbering = number_objects(scene);
  for (OwnerShare& share : ownership.shares) {
    if (share.object != kNoObject) share.object = numbering.objects[share.object];
  }
  // Shares of a pixel stay sorted by object only if the numbering kept the order; resort.
  for (size_t i = 0; i + 1 < ownership.first.size(); ++i) {
    std::sort(ownership.shares.begin() + ptrdiff_t(ownership.first[i]),
              ownership.shares.begin() + ptrdiff_t(ownership.first[i + 1]),
              [](const OwnerShare& a, const OwnerShare& b) { return a.object < b.object; });
  }
  return ownership;
}

// Blinn-Phong has none (shaders/lighting.glsl).
bool has_energy_compensation(TruthShading s) {
  return s.energy_compensation && s.brdf != Brdf::blinn_phong;
}

struct Candidate {
  KnobSetting setting;
  Scene scene;
  std::unique_ptr<Renderer> renderer;
  std::vector<double> times;
  uint64_t triangles = 0;
  double precompute_ms = 0.0;
  std::vector<WarmupStats> warmups;  // one per round
};

}  // namespace

TradeoffScene load_tradeoff_scene(const TradeoffArgs& args) {
  TradeoffScene out;
  out.frame = args.frame;
  if (is_bench_family(args.scene)) {
    const uint32_t n = args.objects ? args.objects : 100;
    const float aspect = float(out.frame.width) / float(out.frame.height);
    // Every family grows linearly with N: checked from one object, as bench checks its counts.
    check_triangle_numbering(
        lod_triangle_count(make_bench_scene(args.scene, 1, 32, aspect), {}, FrameSettings{}), n,
        "object", "objects");
    out.scene = make_bench_scene(args.scene, n, 32, aspect);
  } else {
    // The command line refuses --objects here (cli.cpp); a caller that sets it gets the same.
    if (args.objects) {
      throw Error("--objects applies to the benchmark families (" + bench_family_names() +
                  "), not to '" + args.scene + "'");
    }
    SceneFile file = load_scene_argument(args.scene, args.strict, args.quiet);
    // The file's render defaults fill in what the command left unset.
    apply_render_defaults(file.render, out.frame, args.size_given, false, false, args.brdf_given,
                          true);
    if (!args.size_given) out.size_place = file.render.size_place;
    frame_model_camera(file.scene, args.scene, false, out.frame.width, out.frame.height);
    out.scene = std::move(file.scene);
  }
  validate_scene(out.scene);
  for (const std::string& knob : args.knobs) {
    std::string why = knob_cannot_matter(knob, out.scene, out.frame);
    // Its frames' samples and level of detail are a preset's where --quality gave it (tradeoff
    // has no option for either, and a scene file's "render" block sets neither).
    if (knob == "raster-shade" && !why.empty() && args.quality != Quality::none)
      why += " (" +
             std::string(out.frame.samples != 1
                             ? option_source(args.quality, false, "--samples",
                                             std::to_string(out.frame.samples))
                             : option_source(args.quality, false, "--lod", "auto")) +
             ")";
    if (!why.empty()) out.skipped.push_back({knob, std::move(why)});
  }
  return out;
}

std::string describe_truth(const Scene& scene, const FrameSettings& frame,
                           const std::vector<std::string>& knobs, uint32_t truth_samples,
                           uint32_t environment_directions) {
  const std::string n = std::to_string(truth_samples);
  std::string out = "CPU reference, double precision: ";
  if (knob_cannot_matter("tessellation", scene, frame).empty()) out += "analytic spheres, ";
  out += n + "x" + n + " samples per pixel (box filter), ";
  if (knob_cannot_matter("anisotropy", scene, frame).empty())
    out += "16x anisotropic texture filtering, ";
  out += "no level of detail, fp32 HDR range";
  if (scene.environment)
    out += ", " + std::to_string(environment_directions) +
           " environment directions per lobe and pixel";
  // Without lights or an environment no BRDF shades anything: the truth names none.
  if (!knob_cannot_matter("brdf", scene, frame).empty()) return out;
  auto described = [](TruthShading s) {
    return "the " + std::string(brdf_name(s.brdf)) + " BRDF" +
           (has_energy_compensation(s) ? " with energy compensation" : "");
  };
  const std::string faithful = described(truth_shading("brdf", frame));
  const std::string given = described(truth_shading("", frame)) + " (the settings')";
  const bool brdf_knob = std::find(knobs.begin(), knobs.end(), "brdf") != knobs.end();
  if (!brdf_knob) return out + "; " + given;
  if (knobs.size() == 1) return out + "; " + faithful;
  return out + "; the brdf knob against " + faithful + ", the others against " + given;
}

TruthShading truth_shading(const std::string& knob, const FrameSettings& frame) {
  if (knob == "brdf") return {Brdf::filament, true};
  return {frame.brdf, frame.energy_compensation};
}

std::string brdf_label(TruthShading s) {
  return brdf_name(s.brdf) + std::string(has_energy_compensation(s) ? "+ec" : "");
}

RendererOptions tradeoff_base_options(const Context& ctx, const TradeoffArgs& args) {
  RendererOptions options = tuned_for_device(ctx, {});
  options.environment = args.env_options;
  options.tile_size = args.tile_size;
  if (args.quality != Quality::none && preset_sets_small_triangle_area(ctx.properties.deviceType))
    options.small_triangle_max_area = args.small_triangle_area;
  return options;
}

TradeoffResults measure_tradeoff(Context& ctx, const TradeoffArgs& args,
                                 const TradeoffScene& loaded) {
  TradeoffResults results;
  results.device = ctx.properties.deviceName;
  results.driver = ctx.driver;
  const FrameSettings& frame = loaded.frame;
  const Scene& scene = loaded.scene;
  results.width = frame.width;
  results.height = frame.height;
  results.skipped = loaded.skipped;
  std::vector<std::string> measured;
  for (const std::string& knob : args.knobs) {
    if (std::none_of(results.skipped.begin(), results.skipped.end(),
                     [&](const SkippedKnob& s) { return s.knob == knob; }))
      measured.push_back(knob);
  }
  const RendererOptions options = tradeoff_base_options(ctx, args);

  std::vector<KnobSetting> settings;
  for (const std::string& knob : measured) {
    for (KnobSetting& s : knob_settings(knob, frame, options, &scene)) settings.push_back(s);
  }
  results.measurements_planned = settings.size() * args.rounds;
  // A stop signal is heeded between settings, never inside a frame: then only the settings
  // timed so far go on to the ground truth, and nothing at all before the first is timed.
  std::vector<Candidate> candidates;
  for (KnobSetting& s : settings) {
    if (stop_signal()) {
      results.interrupted = stop_signal();
      return results;
    }
    Candidate c;
    c.scene = with_sphere_segments(scene, s.sphere_segments);
    c.setting = std::move(s);
    c.renderer = std::make_unique<Renderer>(ctx, c.setting.renderer);
    try {
      c.renderer->set_scene(c.scene);
    } catch (const SceneSizeError& e) {
      // A family's count is the option that made the buffer too large.
      if (!args.objects) throw;
      throw Error("--objects " + std::to_string(args.objects) + ": " + e.what());
    }
    candidates.push_back(std::move(c));
  }
  const size_t total = results.measurements_planned;
  const bool progress_in_place = !args.quiet && isatty(fileno(stderr));
  size_t& done = results.measurements_made;
  for (uint32_t round = 0; round < args.rounds && !results.interrupted; ++round) {
    for (Candidate& c : candidates) {
      if (stop_signal()) {
        results.interrupted = stop_signal();
        break;
      }
      // The first round's first frame pays for pipeline compilation and the environment's
      // precomputation, which warm_up's clock leaves out; every round warms up again after
      // the other settings ran, by time as `tessera bench` does (core/warmup.h).
      if (round == 0) {
        try {
          const FrameStats stats = c.renderer->render(c.setting.frame);
          c.precompute_ms = stats.precompute_ms;
        } catch (const ImageSizeError& e) {
          // The samples knob's own samples are the knob's; the others' are --quality's.
          if (c.setting.knob == "samples" || c.setting.frame.samples != frame.samples) throw;
          throw with_samples_source(e, args.quality, false, frame.samples);
        }
      }
      WarmupRule rule;
      rule.min_frames = args.warmup;
      rule.ms = args.warmup_ms;
      c.warmups.push_back(warm_up(
          [&c] {
            const FrameStats stats = c.renderer->render(c.setting.frame);
            return stats.has_timestamps ? stats.gpu_total_ms : 0.0;
          },
          rule));
      for (uint32_t i = 0; i < args.repeat; ++i) {
        const FrameStats stats = c.renderer->render(c.setting.frame);
        if (!stats.has_timestamps) throw Error("the device's queue cannot write timestamps");
        c.times.push_back(stats.gpu_total_ms);
        c.triangles = stats.raster_triangles;
      }
      // Rewritten in place on a terminal; into a log, a line per round.
      ++done;
      if (progress_in_place) std::fprintf(stderr, "\rmeasured %zu of %zu", done, total);
    }
    if (!progress_in_place && !args.quiet && !results.interrupted)
      std::fprintf(stderr, "measured %zu of %zu\n", done, total);
  }
  if (progress_in_place) std::fprintf(stderr, "\n");
  if (results.interrupted) {
    // A setting the rounds never reached has no time: it is left out, and said to be.
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                    [](const Candidate& c) { return c.warmups.empty(); }),
                     candidates.end());
    if (candidates.empty()) return results;
    std::fprintf(stderr,
                 "tessera: %s received after %zu of %zu measurements: the ground truth for the "
                 "%zu setting%s timed follows (a second one ends at once)\n",
                 stop_signal_name(results.interrupted), done, total, candidates.size(),
                 candidates.size() == 1 ? "" : "s");
  }

  // The ground truths: exact spheres, N x N samples per pixel, the environment integrated by
  // Monte Carlo, and each knob's BRDF (truth_shading).
  ReferenceSettings truth;
  truth.frame = frame;
  truth.frame.max_anisotropy = 16;
  truth.frame.samples = 1;                   // the truth's own N x N supersampling instead
  truth.frame.lod = Lod::off;                // the meshes as they are, spheres exact
  truth.frame.hdr_format = HdrFormat::fp32;  // no clamp at fp16's 65504
  truth.ground_truth.analytic_spheres = true;
  truth.ground_truth.supersampling = args.truth_samples;
  const uint32_t per_sample = args.truth_env_samples / (args.truth_samples * args.truth_samples);
  truth.environment_samples = std::max(16u, per_sample);
  results.truth =
      describe_truth(scene, frame, measured, args.truth_samples,
                     truth.environment_samples * args.truth_samples * args.truth_samples);
  struct Truth {
    ReferenceFrame frame;
    Ownership ownership;            // by index into Scene::objects
    std::vector<uint8_t> interior;  // pixels the truth shows one object in, in all samples
  };
  std::map<std::pair<Brdf, bool>, Truth> truths;
  auto truth_key = [&](const KnobSetting& s) {
    const TruthShading t = truth_shading(s.knob, frame);
    return std::pair{t.brdf, t.energy_compensation};
  };
  // Without lights or an environment the BRDF shades nothing: the message names none.
  const bool lit = knob_cannot_matter("brdf", scene, frame).empty();
  const auto start = std::chrono::steady_clock::now();
  for (const Candidate& c : candidates) {
    const auto key = truth_key(c.setting);
    if (truths.count(key)) continue;
    if (!args.quiet && !lit) {
      std::fprintf(stderr, "rendering the ground truth\n");
    } else if (!args.quiet) {
      const TruthShading shading{key.first, key.second};
      std::fprintf(stderr, "rendering the ground truth for the %s BRDF%s\n",
                   brdf_name(shading.brdf),
                   has_energy_compensation(shading) ? " with energy compensation" : "");
    }
    ReferenceSettings settings = truth;
    settings.frame.brdf = key.first;
    settings.frame.energy_compensation = key.second;
    Truth t{render_reference(scene, settings), {}, {}};
    t.ownership = by_scene_object(t.frame.ownership, scene);
    t.interior.resize(t.ownership.first.size() - 1);
    for (size_t i = 0; i < t.interior.size(); ++i)
      t.interior[i] = t.ownership.first[i + 1] - t.ownership.first[i] == 1;
    truths.emplace(key, std::move(t));
  }
  results.truth_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Each knob's default image, for the speed-only knobs' check.
  std::map<std::string, Image8> default_image;
  std::vector<Image8> images;
  for (Candidate& c : candidates) {
    c.renderer->render(c.setting.frame);
    images.push_back(c.renderer->read_ldr());
    if (c.setting.is_default) default_image[c.setting.knob] = images.back();
  }
  for (size_t i = 0; i < candidates.size(); ++i) {
    Candidate& c = candidates[i];
    TradeoffPoint p;
    p.setting = c.setting;
    p.gpu_ms = summarize(c.times);
    p.triangles_rasterized = c.triangles;
    if (lit) p.truth_brdf = brdf_label(truth_shading(c.setting.knob, frame));
    p.precompute_ms = c.precompute_ms;
    p.warmups = c.warmups;
    const Truth& t = truths.at(truth_key(c.setting));
    const Ownership own =
        compute_ownership(*c.renderer, c.setting.frame.width, c.setting.frame.height);
    const ImageF hdr = c.renderer->read_hdr();
    p.error = error_against_truth(hdr, images[i], t.frame.hdr, t.frame.ldr, &own, &t.ownership);
    p.interior_mean_relative = radiance_error(hdr, t.frame.hdr, &t.interior).mean_relative;
    const auto d = default_image.find(c.setting.knob);
    p.identical_to_default = d != default_image.end() && d->second.pixels == images[i].pixels;
    results.points.push_back(std::move(p));
    c.renderer.reset();
  }
  // The front of each knob.
  for (const auto& [first, last] : knob_runs(results.points)) {
    std::vector<CostError> points;
    for (size_t i = first; i < last; ++i)
      points.push_back({results.points[i].gpu_ms.median, results.points[i].error.mean_relative});
    const std::vector<bool> front = pareto_front(points);
    for (size_t i = first; i < last; ++i) results.points[i].on_front = front[i - first];
  }
  return results;
}

std::vector<std::pair<size_t, size_t>> knob_runs(const std::vector<TradeoffPoint>& points) {
  std::vector<std::pair<size_t, size_t>> runs;
  for (size_t first = 0; first < points.size();) {
    size_t end = first;
    while (end < points.size() && points[end].setting.knob == points[first].setting.knob) ++end;
    runs.push_back({first, end});
    first = end;
  }
  return runs;
}

}  // namespace tessera
