#pragma once
// `tessera tradeoff`: every setting of each speed-against-accuracy knob rendered by the compute
// path, its GPU time against its error with respect to a ground truth from the CPU reference,
// and the Pareto front of each knob (docs/tradeoffs.md). The knobs are listed here; measuring
// is in host/tradeoff_measure.cpp, reporting (table, JSON, chart) in host/tradeoff_report.cpp.

#include <string>
#include <utility>
#include <vector>

#include "compute/renderer.h"
#include "core/frame_settings.h"
#include "core/image_metrics.h"
#include "core/scene.h"
#include "core/statistics.h"
#include "core/warmup.h"
#include "host/cli.h"

namespace tessera {

/// One setting of a knob: the frame settings and renderer options it renders with.
struct KnobSetting {
  std::string knob;   // the knob's name, e.g. "brdf"
  std::string label;  // the setting, e.g. "filament+ec"
  FrameSettings frame;
  RendererOptions renderer;
  /// The tessellation knob: spheres (meshes with Mesh::analytic_sphere) are remade as uv
  /// spheres of this many slices and half as many stacks; 0 keeps the scene's meshes.
  uint32_t sphere_segments = 0;
  /// True for the setting that equals the defaults the command line gave.
  bool is_default = false;
  /// A knob that trades speed only: every setting must give the default's image bit for bit.
  bool speed_only = false;
};

struct KnobInfo {
  const char* name;
  const char* description;
};

/// The knobs, in the order they are documented.
const std::vector<KnobInfo>& knobs();

/// Why knob `knob` cannot change the image of `scene` rendered with `frame` (every setting
/// would give the same image and the same time but for noise), e.g. "the scene has no
/// environment" for env-size; "" where it can. Only reasons known before rendering: a knob
/// whose effect depends on the image's content (hdr: radiance past fp16's range) is measured.
std::string knob_cannot_matter(const std::string& knob, const Scene& scene,
                               const FrameSettings& frame);

/// The settings of knob `knob`, each starting from `frame` and `options` (the command line's,
/// with every device choice made: tuned_for_device). The setting equal to theirs is the
/// default; with RendererOptions::shade_tiles unset, neither of that knob's is. With `scene`,
/// the tessellation knob's default is labelled with its spheres' tessellation
/// ("scene's own (64 slices)": scene_sphere_tessellation).
/// Throws Error naming the known knobs if `knob` is not one of knobs().
std::vector<KnobSetting> knob_settings(const std::string& knob, const FrameSettings& frame,
                                       const RendererOptions& options,
                                       const Scene* scene = nullptr);

/// A warning where the ground truth (`truth_samples` x `truth_samples` samples per pixel) has
/// no more samples than a setting of `knobs` (from `frame`) measures: those settings' errors
/// then measure the truth's own coverage error as much as theirs (a new user's trial saw 16
/// samples ranked worse than 4 against a 4 x 4 truth). "" where the truth has more.
std::string coarse_truth_warning(const std::vector<std::string>& knobs, const FrameSettings& frame,
                                 uint32_t truth_samples);

/// The tessellation of the spheres (meshes with Mesh::analytic_sphere) the objects of `scene`
/// draw, as the tessellation knob's settings name theirs: "64 slices" (a uv sphere of 64
/// segments and 32 stacks), "64 slices, 20 stacks", "icosphere level 3", "960 triangles" (a
/// sphere no builder of core/mesh.h makes as it is); "mixed: A; B" (and "; N more") where they
/// differ; "" where the scene draws no sphere.
std::string scene_sphere_tessellation(const Scene& scene);

/// The BRDF the ground truth of a knob shades with. The brdf knob's truth is the most faithful
/// model, filament with energy compensation, so that the knob shows each model's error; every
/// other knob's truth shades with `frame`'s BRDF (the settings'), so that its error is its own
/// and not the BRDF's. The knobs' errors are therefore not against one truth.
struct TruthShading {
  Brdf brdf;
  bool energy_compensation;
};
TruthShading truth_shading(const std::string& knob, const FrameSettings& frame);

/// `shading` named as the brdf knob's settings are: "filament+ec", "classic", "blinn-phong".
std::string brdf_label(TruthShading shading);

/// One measured setting.
struct TradeoffPoint {
  KnobSetting setting;
  Summary gpu_ms;    // GPU time of a frame, over every timed frame of every round
  TruthError error;  // against the ground truth of its knob (truth_shading)
  /// The BRDF of that truth (brdf_label), or "" where no BRDF shades the scene.
  std::string truth_brdf;
  /// Mean relative error over the pixels the truth shows a single object (or only the
  /// background) in all its samples: the shading's error, apart from the edges'.
  double interior_mean_relative = 0.0;
  bool identical_to_default = false;  // the 8-bit image equals the knob's default setting's
  bool on_front = false;              // on the Pareto front of its knob (time, mean_relative)
  uint64_t triangles_rasterized = 0;
  /// GPU time of the environment's precomputation (the first frame after set_scene only): what
  /// the env-size and env-samples knobs cost, which the per-frame time does not show.
  double precompute_ms = 0.0;
  /// The warm-up before each round's timed frames (core/warmup.h; `--warmup`, `--warmup-ms`):
  /// one per round measured, fewer than --rounds where an interruption stopped the rounds.
  std::vector<WarmupStats> warmups;
};

/// A knob asked for but not measured, and why (knob_cannot_matter).
struct SkippedKnob {
  std::string knob, reason;
};

/// The scene a tradeoff measures and the frame its knobs start from: the command line's, with
/// what it left unset from the scene file's "render" block.
struct TradeoffScene {
  Scene scene;
  FrameSettings frame;
  std::string size_place;  // where the file gave the size (RenderDefaults::size_place), or ""
  std::vector<SkippedKnob> skipped;  // the knobs of --knob that cannot matter for it, in order
};

/// Loads `args.scene` (a bench family, a built-in scene or a scene file) and finds which of
/// `args.knobs` cannot matter for it (knob_cannot_matter). Throws Error for a bad scene.
TradeoffScene load_tradeoff_scene(const TradeoffArgs& args);

/// The ground truth as configured for `scene`, in words: only what applies to it (analytic
/// spheres where it has spheres, texture filtering where it has texture maps, environment
/// directions where it has an environment, the BRDFs where lights or an environment go
/// through one). `knobs`: those measured; the brdf knob's truth shades with filament and
/// energy compensation, every other knob's with `frame`'s BRDF.
std::string describe_truth(const Scene& scene, const FrameSettings& frame,
                           const std::vector<std::string>& knobs, uint32_t truth_samples,
                           uint32_t environment_directions);

struct TradeoffResults {
  std::string device, driver;
  uint32_t width = 0, height = 0;     // the image size measured (the command line's or the file's)
  std::vector<SkippedKnob> skipped;   // knobs asked for that cannot matter for the scene
  std::string truth;                  // how the ground truth was made, in words
  double truth_seconds = 0.0;         // CPU wall time of the ground truths, all together
  std::vector<TradeoffPoint> points;  // by knob in the order asked, then by setting
  /// The signal (SIGINT, SIGTERM: host/stop_signal.h) that stopped the rounds before their
  /// end, 0 when they ran to the end. `points` then holds the settings measured in at least one
  /// round, against their ground truth.
  int interrupted = 0;
  size_t measurements_planned = 0;  // settings x rounds
  size_t measurements_made = 0;
};

/// The renderer options every knob's settings start from: `ctx`'s device's (tuned_for_device)
/// with the command line's tile size and environment sizes, and a --quality preset's
/// small-triangle area where it applies (preset_sets_small_triangle_area).
RendererOptions tradeoff_base_options(const Context& ctx, const TradeoffArgs& args);

/// Renders every setting of every knob of `args` that can matter for `scene` (the others are
/// listed in TradeoffResults::skipped) on `ctx` (rounds interleave the settings so that a clock
/// change affects them alike) and the ground truth on the CPU. After stop_signal()
/// (host/stop_signal.h) no further setting is timed: the ground truth is rendered for those
/// timed so far (TradeoffResults::interrupted). Throws Error for a bad knob, ImageSizeError for
/// a size the device cannot take.
TradeoffResults measure_tradeoff(Context& ctx, const TradeoffArgs& args,
                                 const TradeoffScene& scene);

/// The runs of consecutive `points` of one knob (measure_tradeoff orders them knob by knob), as
/// [begin, end) index pairs in order.
std::vector<std::pair<size_t, size_t>> knob_runs(const std::vector<TradeoffPoint>& points);

/// The table print_tradeoff_table prints.
std::string tradeoff_table(const TradeoffResults& results, const TradeoffArgs& args);

void print_tradeoff_table(const TradeoffResults& results, const TradeoffArgs& args);
void write_tradeoff_json(const std::string& path, const TradeoffResults& results,
                         const TradeoffArgs& args, const std::string& command_line);
/// Error (mean relative, log) against GPU ms (log), a series per knob, the front joined.
void write_tradeoff_chart(const std::string& path, const TradeoffResults& results,
                          const TradeoffArgs& args);

/// The command: measures, prints, writes the files asked for. Returns the exit status.
int run_tradeoff(const TradeoffArgs& args, const std::string& command_line);

}  // namespace tessera
