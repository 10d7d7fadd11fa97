// Loading throughput of OBJ import: tinyobjloader alone (parse and triangulate) against
// import_obj (scan, parse, triangulate, build de-duplicated meshes). The file is
// bench/large_obj.h's grid with TESSERA_OBJ_BENCH_TRIANGLES triangles (default 10^6), written
// once to $TMPDIR. Counters: MB/s of OBJ text and triangles/s.
#include <cstdlib>
#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>
#include <tiny_obj_loader.h>

#include "bench/large_obj.h"
#include "core/model_import.h"

namespace {

struct BenchFile {
  std::string path;
  uint64_t bytes = 0;
  uint64_t triangles = 0;
};

const BenchFile& bench_file() {
  static const BenchFile file = [] {
    const char* env = std::getenv("TESSERA_OBJ_BENCH_TRIANGLES");
    const uint64_t wanted = env ? std::strtoull(env, nullptr, 10) : 1000000ull;
    BenchFile f;
    f.path = (std::filesystem::temp_directory_path() /
              ("tessera_bench_" + std::to_string(wanted) + ".obj"))
                 .string();
    f.triangles = tessera::bench::write_large_obj(f.path, wanted);
    f.bytes = std::filesystem::file_size(f.path);
    return f;
  }();
  return file;
}

void set_counters(benchmark::State& state, const BenchFile& f) {
  state.counters["MB/s"] =
      benchmark::Counter(double(f.bytes) / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["triangles/s"] =
      benchmark::Counter(double(f.triangles), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["triangles"] = double(f.triangles);
}

void BM_TinyObjLoaderAlone(benchmark::State& state) {
  const BenchFile& f = bench_file();
  for (auto _ : state) {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, f.path.c_str(), nullptr,
                          /*triangulate=*/true)) {
      state.SkipWithError(err.c_str());
      return;
    }
    benchmark::DoNotOptimize(shapes.data());
  }
  set_counters(state, f);
}
BENCHMARK(BM_TinyObjLoaderAlone)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ImportObj(benchmark::State& state) {
  const BenchFile& f = bench_file();
  for (auto _ : state) {
    tessera::ImportedModel model = tessera::import_obj(f.path);
    benchmark::DoNotOptimize(model.scene.meshes.data());
  }
  set_counters(state, f);
}
BENCHMARK(BM_ImportObj)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
