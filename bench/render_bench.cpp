// GPU timings of the compute renderer and the hardware baseline (Google Benchmark, manual
// time = GPU time from timestamp queries), by scene and by object count.
//
//   build/bench/tessera_bench [--benchmark_filter=...]   (TESSERA_DEVICE=lavapipe|gpu|N)
//
// Each iteration renders kFrames frames and reports their median GPU time, so rare slow frames
// (clock changes, other work) do not move the figure; counters are per-pass medians. Runs use
// a fixed number of iterations: with manual (GPU) time, a minimum time would need thousands of
// sub-millisecond frames, each with its own submission and wait.
// `tessera bench` runs the same measurements as a sweep with CSV, JSON and charts.
#include <algorithm>
#include <cstdlib>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "compute/baselines/hardware_baseline.h"
#include "compute/context.h"
#include "compute/renderer.h"
#include "core/bench_scenes.h"
#include "core/builtin_scenes.h"
#include "core/statistics.h"

namespace tessera {
namespace {

constexpr int kFrames = 11;

Context& bench_context() {
  static std::unique_ptr<Context> ctx = [] {
    ContextOptions options;
    if (const char* d = std::getenv("TESSERA_DEVICE")) options.device = d;
    return create_context(options);
  }();
  return *ctx;
}

void report_counters(benchmark::State& state, const std::vector<FrameStats>& frames,
                     uint64_t triangles) {
  for (size_t p = 0; p < kPassCount; ++p) {
    std::vector<double> v;
    for (const FrameStats& f : frames) v.push_back(f.pass_ms[p]);
    state.counters[std::string(pass_name(Pass(p))) + "_ms"] = median(v);
  }
  std::vector<double> cpu;
  for (const FrameStats& f : frames) cpu.push_back(f.cpu_record_submit_ms);
  state.counters["cpu_record_ms"] = median(cpu);
  state.counters["tris_submitted"] = double(triangles);
  state.counters["tris_rasterized"] = double(frames.back().raster_triangles);
  state.counters["tris_per_s"] =
      benchmark::Counter(double(triangles), benchmark::Counter::kIsIterationInvariantRate);
}

// The compute path on `scene` at width x height.
void run_compute(benchmark::State& state, const Scene& scene, uint32_t width, uint32_t height,
                 RendererOptions options = {}) {
  Context& ctx = bench_context();
  Renderer renderer(ctx, options);
  renderer.set_scene(scene);
  FrameSettings settings;
  settings.width = width;
  settings.height = height;
  renderer.render(settings);  // warm-up: pipelines compiled, buffers grown
  std::vector<FrameStats> frames(kFrames);
  for (auto _ : state) {
    for (FrameStats& f : frames) f = renderer.render(settings);
    std::vector<double> totals;
    for (const FrameStats& f : frames) totals.push_back(f.gpu_total_ms);
    state.SetIterationTime(median(totals) * 1e-3);
  }
  report_counters(state, frames, frames.back().triangles_submitted);
  state.SetLabel(ctx.properties.deviceName);
}

// The hardware baseline: timestamps around its render pass.
void run_hardware(benchmark::State& state, const Scene& scene, uint32_t width, uint32_t height) {
  Context& ctx = bench_context();
  Renderer renderer(ctx);
  renderer.set_scene(scene);
  FrameSettings settings;
  settings.width = width;
  settings.height = height;
  HardwareBaseline hardware(renderer);
  hardware.render(settings);
  uint64_t triangles = 0;
  for (const Object& o : scene.objects) triangles += scene.meshes[o.mesh].triangle_count();
  for (auto _ : state) {
    std::vector<double> pass;
    for (int i = 0; i < kFrames; ++i) pass.push_back(hardware.render(settings).render_pass_ms);
    state.SetIterationTime(median(pass) * 1e-3);
  }
  state.counters["tris_submitted"] = double(triangles);
  state.counters["tris_per_s"] =
      benchmark::Counter(double(triangles), benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(ctx.properties.deviceName);
}

// A scene pays only for what it uses: the shading pass specialized to the scene (light counts,
// texture maps used, environment or not) against the generic one with every feature enabled
// and decided at run time (state.range(2): 1 specialized, 0 generic). Compare the shade_ms
// counters of the two.
void ShadingSpecialization(benchmark::State& state, const char* name) {
  RendererOptions options;
  options.specialize_lights = state.range(2) != 0;
  run_compute(state, make_builtin_scene(name), uint32_t(state.range(0)), uint32_t(state.range(1)),
              options);
}

void BuiltinScene(benchmark::State& state, const char* name) {
  run_compute(state, make_builtin_scene(name), uint32_t(state.range(0)), uint32_t(state.range(1)));
}

// Families by object count (range 0), at 512x512 so lavapipe can run them too.
void ComputeGrid(benchmark::State& state) {
  run_compute(state, make_bench_scene("grid", uint32_t(state.range(0)), 32, 1.0f), 512, 512);
}
void HardwareGrid(benchmark::State& state) {
  run_hardware(state, make_bench_scene("grid", uint32_t(state.range(0)), 32, 1.0f), 512, 512);
}
void ComputeScatter(benchmark::State& state) {
  run_compute(state, make_bench_scene("scatter", uint32_t(state.range(0)), 16, 1.0f), 512, 512);
}
void ComputeHuge(benchmark::State& state) {
  run_compute(state, make_bench_scene("huge", uint32_t(state.range(0)), 16, 1.0f), 512, 512);
}

BENCHMARK_CAPTURE(BuiltinScene, spheres, "spheres")
    ->Args({512, 512})
    ->Args({1920, 1080})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK_CAPTURE(BuiltinScene, metals, "metals")
    ->Args({512, 512})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK_CAPTURE(ShadingSpecialization, spheres, "spheres")
    ->Args({512, 512, 0})
    ->Args({512, 512, 1})
    ->Args({1920, 1080, 0})
    ->Args({1920, 1080, 1})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK_CAPTURE(ShadingSpecialization, lights, "lights")
    ->Args({512, 512, 0})
    ->Args({512, 512, 1})
    ->Args({1920, 1080, 0})
    ->Args({1920, 1080, 1})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK_CAPTURE(ShadingSpecialization, textured, "textured")
    ->Args({512, 512, 0})
    ->Args({512, 512, 1})
    ->Args({1920, 1080, 0})
    ->Args({1920, 1080, 1})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK_CAPTURE(ShadingSpecialization, environment, "environment")
    ->Args({512, 512, 0})
    ->Args({512, 512, 1})
    ->Args({1920, 1080, 0})
    ->Args({1920, 1080, 1})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK(ComputeGrid)
    ->RangeMultiplier(10)
    ->Range(1, 1000)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK(HardwareGrid)
    ->RangeMultiplier(10)
    ->Range(1, 1000)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK(ComputeScatter)
    ->RangeMultiplier(10)
    ->Range(10, 1000)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK(ComputeHuge)
    ->Arg(1)
    ->Arg(4)
    ->Arg(16)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);

}  // namespace
}  // namespace tessera

BENCHMARK_MAIN();
