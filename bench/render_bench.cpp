// GPU timings of the compute renderer (Google Benchmark, manual time = GPU time from
// timestamp queries). Each pass's time is reported as a counter (ms per frame).
//
//   build/bench/tessera_bench [--benchmark_filter=...]   (TESSERA_DEVICE=lavapipe|gpu|N)
#include <cstdlib>
#include <memory>

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

// Renders built-in scene `name` at state.range(0) x state.range(1); the scene is uploaded and
// one warm-up frame rendered outside the timed loop.
void render_scene(benchmark::State& state, const char* name) {
  Context& ctx = bench_context();
  Renderer renderer(ctx);
  renderer.set_scene(make_builtin_scene(name));
  FrameSettings settings;
  settings.width = uint32_t(state.range(0));
  settings.height = uint32_t(state.range(1));
  FrameStats warm = renderer.render(settings);
  std::array<double, kPassCount> pass_sum{};
  double cpu_sum = 0;
  for (auto _ : state) {
    FrameStats f = renderer.render(settings);
    state.SetIterationTime(f.gpu_total_ms * 1e-3);
    for (size_t p = 0; p < kPassCount; ++p) pass_sum[p] += f.pass_ms[p];
    cpu_sum += f.cpu_record_submit_ms;
  }
  const double n = double(state.iterations());
  for (size_t p = 0; p < kPassCount; ++p)
    state.counters[std::string(pass_name(Pass(p))) + "_ms"] = pass_sum[p] / n;
  state.counters["cpu_record_ms"] = cpu_sum / n;
  state.counters["tris_submitted"] = double(warm.triangles_submitted);
  state.counters["tris_rasterized"] = double(warm.raster_triangles);
  state.counters["tris_per_s"] =
      benchmark::Counter(double(warm.triangles_submitted) * n, benchmark::Counter::kIsRate);
  state.SetLabel(ctx.properties.deviceName);
}

BENCHMARK_CAPTURE(render_scene, spheres, "spheres")
    ->Args({512, 512})
    ->Args({1920, 1080})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.5);
BENCHMARK_CAPTURE(render_scene, metals, "metals")
    ->Args({512, 512})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.5);

}  // namespace
}  // namespace tessera

BENCHMARK_MAIN();
