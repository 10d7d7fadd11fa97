// GPU timings of the compute renderer (Google Benchmark, manual time = GPU time from
// timestamp queries). Each pass's time is reported as a counter (ms per frame).
//
//   build/bench/tessera_bench [--benchmark_filter=...]   (TESSERA_DEVICE=lavapipe|gpu|N)
#include <algorithm>
#include <cstdlib>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "compute/context.h"
#include "compute/renderer.h"
#include "core/builtin_scenes.h"

namespace tessera {
namespace {

Context& bench_context() {
  static std::unique_ptr<Context> ctx = [] {
    ContextOptions options;
    if (const char* d = std::getenv("TESSERA_DEVICE")) options.device = d;
    return create_context(options);
  }();
  return *ctx;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Renders built-in scene `name` at state.range(0) x state.range(1). The scene is uploaded and
// one warm-up frame rendered outside the timed loop. Each iteration renders kFrames frames and
// reports their median GPU time, so rare slow frames (clock changes, other work) do not move
// the figure; the counters are per-pass medians of the last iteration.
void render_scene(benchmark::State& state, const char* name) {
  constexpr int kFrames = 11;
  Context& ctx = bench_context();
  Renderer renderer(ctx);
  renderer.set_scene(make_builtin_scene(name));
  FrameSettings settings;
  settings.width = uint32_t(state.range(0));
  settings.height = uint32_t(state.range(1));
  FrameStats warm = renderer.render(settings);
  std::vector<FrameStats> frames(kFrames);
  for (auto _ : state) {
    for (FrameStats& f : frames) f = renderer.render(settings);
    std::vector<double> totals;
    for (const FrameStats& f : frames) totals.push_back(f.gpu_total_ms);
    state.SetIterationTime(median(totals) * 1e-3);
  }
  for (size_t p = 0; p < kPassCount; ++p) {
    std::vector<double> v;
    for (const FrameStats& f : frames) v.push_back(f.pass_ms[p]);
    state.counters[std::string(pass_name(Pass(p))) + "_ms"] = median(v);
  }
  std::vector<double> cpu;
  for (const FrameStats& f : frames) cpu.push_back(f.cpu_record_submit_ms);
  state.counters["cpu_record_ms"] = median(cpu);
  state.counters["tris_submitted"] = double(warm.triangles_submitted);
  state.counters["tris_rasterized"] = double(warm.raster_triangles);
  state.counters["tris_per_s"] = benchmark::Counter(double(warm.triangles_submitted),
                                                    benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(ctx.properties.deviceName);
}

BENCHMARK_CAPTURE(render_scene, spheres, "spheres")
    ->Args({512, 512})
    ->Args({1920, 1080})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.2);
BENCHMARK_CAPTURE(render_scene, metals, "metals")
    ->Args({512, 512})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.2);

}  // namespace
}  // namespace tessera

BENCHMARK_MAIN();
