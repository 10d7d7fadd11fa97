// Loading throughput of OBJ import: tinyobjloader alone (parse and triangulate) against
// import_obj (scan, parse, triangulate, build de-duplicated meshes). The file is
// bench/large_obj.h's grid with TESSERA_OBJ_BENCH_TRIANGLES triangles (default 10^6), written
// once to $TMPDIR (and reused by later runs). Counters: MB/s of OBJ text and triangles/s.
// glTF: tinygltf alone (LoadBinaryFromFile, images decoded by its stb_image loader) against
// import_gltf, on $TESSERA_GLB_BENCH_FILE (default the largest sample glb of Debian's assimp
// models, 2CylinderEngine.glb).
// Each case also reports peak_MB, the process's peak resident memory (getrusage ru_maxrss; it
// only grows, so run one case per process (--benchmark_filter) to read it for that case), and
// added_peak_MB, the peak during the case above the resident memory at its start (the kernel's
// high-water mark reset through /proc/self/clear_refs after malloc_trim), which is what the
// reader itself needed.
// Times are process CPU time (MeasureProcessCPUTime): the importers use several threads, and
// the machine may be shared, so wall time would mislead.
#include <malloc.h>
#include <sys/resource.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <benchmark/benchmark.h>
#include <tiny_gltf.h>
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
    // The file is the same for the same count: written once, under another name until whole.
    std::error_code ec;
    if (std::filesystem::exists(f.path, ec)) {
      f.triangles = tessera::bench::large_obj_triangles(wanted);
    } else {
      f.triangles = tessera::bench::write_large_obj(f.path + ".part", wanted);
      std::filesystem::rename(f.path + ".part", f.path);
    }
    f.bytes = std::filesystem::file_size(f.path);
    return f;
  }();
  return file;
}

// A /proc/self/status field in kB, as MB.
double status_mb(const std::string& field) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(field + ":", 0) == 0) return std::stod(line.substr(field.size() + 1)) / 1024.0;
  }
  return 0.0;
}

// Resident memory at the start of a case, with the high-water mark reset to it.
struct PeakScope {
  double start_mb = 0.0;
  PeakScope() {
    malloc_trim(0);  // freed heap goes back, so that it does not hide the case's own growth
    std::ofstream("/proc/self/clear_refs") << "5";  // resets VmHWM to VmRSS (Linux 4.0+)
    start_mb = status_mb("VmRSS");
  }
  double added_mb() const { return status_mb("VmHWM") - start_mb; }
};

void set_counters(benchmark::State& state, const BenchFile& f, const PeakScope& peak) {
  state.counters["added_peak_MB"] = peak.added_mb();
  state.counters["MB/s"] =
      benchmark::Counter(double(f.bytes) / 1e6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["triangles/s"] =
      benchmark::Counter(double(f.triangles), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["triangles"] = double(f.triangles);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_MB"] = double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB
}

void BM_TinyObjLoaderAlone(benchmark::State& state) {
  const BenchFile& f = bench_file();
  const PeakScope peak;
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
  set_counters(state, f, peak);
}
BENCHMARK(BM_TinyObjLoaderAlone)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

void BM_ImportObj(benchmark::State& state) {
  const BenchFile& f = bench_file();
  const PeakScope peak;
  for (auto _ : state) {
    tessera::ImportedModel model = tessera::import_obj(f.path);
    benchmark::DoNotOptimize(model.scene.meshes.data());
  }
  set_counters(state, f, peak);
}
BENCHMARK(BM_ImportObj)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

const BenchFile& glb_file() {
  static const BenchFile file = [] {
    const char* env = std::getenv("TESSERA_GLB_BENCH_FILE");
    BenchFile f;
    f.path = env ? env
                 : "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/"
                   "2CylinderEngine.glb";
    f.bytes = std::filesystem::file_size(f.path);
    const tessera::ImportedModel model = tessera::import_gltf(f.path);
    for (const tessera::Object& o : model.scene.objects)
      f.triangles += model.scene.meshes[o.mesh].triangle_count();
    return f;
  }();
  return file;
}

void BM_TinyGltfAlone(benchmark::State& state) {
  const BenchFile& f = glb_file();
  const PeakScope peak;
  for (auto _ : state) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string warn, err;
    if (!loader.LoadBinaryFromFile(&model, &err, &warn, f.path)) {
      state.SkipWithError(err.c_str());
      return;
    }
    benchmark::DoNotOptimize(model.buffers.data());
  }
  set_counters(state, f, peak);
}
BENCHMARK(BM_TinyGltfAlone)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

void BM_ImportGltf(benchmark::State& state) {
  const BenchFile& f = glb_file();
  const PeakScope peak;
  for (auto _ : state) {
    tessera::ImportedModel model = tessera::import_gltf(f.path);
    benchmark::DoNotOptimize(model.scene.meshes.data());
  }
  set_counters(state, f, peak);
}
BENCHMARK(BM_ImportGltf)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

}  // namespace

BENCHMARK_MAIN();
