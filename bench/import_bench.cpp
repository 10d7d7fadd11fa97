// Loading throughput of OBJ import: tinyobjloader alone (LoadObj: parse and triangulate; and
// LoadObjWithCallback, the streaming parser import_obj is built on, with callbacks that only
// count) against import_obj (scan, parse, triangulate, build de-duplicated meshes). The file is
// bench/large_obj.h's grid with TESSERA_OBJ_BENCH_TRIANGLES triangles (default 10^6), written
// once to $TMPDIR (and reused by later runs). Counters: MB/s of OBJ text and triangles/s.
// glTF: tinygltf alone (LoadBinaryFromFile, images decoded by its stb_image loader) against
// import_gltf, on $TESSERA_GLB_BENCH_FILE (default the largest sample glb of Debian's assimp
// models, 2CylinderEngine.glb).
// Textures: a scene file with kBenchTextures PNG textures of kBenchTextureSide^2 texels (noise,
// so that they compress as photographs do, not as flat colour), written once to $TMPDIR. Its
// cases time decoding (load_scene_file) and mip building (flatten_scene, the CPU part of an
// upload) on every core and on one thread (parallel_thread_limit), as wall time: the speed-up
// of the parallel steps is the ratio of the two on an idle machine; caller_cpu_share shows how
// evenly the work was divided whether or not the machine had cores free.
// Each case also reports peak_MB, the process's peak resident memory (getrusage ru_maxrss; it
// only grows, so run one case per process (--benchmark_filter) to read it for that case), and
// added_peak_MB, the peak during the case's first iteration above the resident memory at its
// start (the kernel's high-water mark reset through /proc/self/clear_refs after malloc_trim),
// which is what one load needed, and added_peak_all_MB, the same over all its iterations: a
// process that loads file after file also holds the heap that earlier loads freed but glibc
// kept (small blocks, under the mmap threshold, freed below live ones).
// Large allocations always get fresh pages (kFixedMmapThreshold), whatever ran before.
// Times are process CPU time (MeasureProcessCPUTime): the importers use several threads, and
// the machine may be shared, so wall time would mislead.
#include <malloc.h>
#include <sys/resource.h>
#include <time.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <benchmark/benchmark.h>
#include <tiny_gltf.h>
#include <tiny_obj_loader.h>
#include <nlohmann/json.hpp>

#include "bench/large_obj.h"
#include "compute/scene_upload.h"
#include "core/image.h"
#include "core/mapped_file.h"
#include "core/model_import.h"
#include "core/parallel.h"
#include "core/scene_file.h"

namespace {

// glibc raises its mmap threshold to the size of each large block freed, so whether a case's
// megabyte-sized buffers get fresh pages (a page fault per 4 KiB) or reuse freed heap depended on
// which cases ran before: tinygltf alone on 2CylinderEngine.glb took 1.9 ms in one process and
// 3.1 ms in another. Setting the threshold to glibc's initial 128 KiB turns the adjustment off:
// every large buffer gets fresh pages in every iteration, as in a process that loads one file.
// Malloc settings given through GLIBC_TUNABLES are left alone, so that the same cases can be
// timed with the heap kept warm (docs/performance.md).
const int kFixedMmapThreshold =
    std::getenv("GLIBC_TUNABLES") ? 0 : mallopt(M_MMAP_THRESHOLD, 128 * 1024);

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
  double first_mb = -1.0;  // the added peak after the first iteration
  PeakScope() {
    malloc_trim(0);  // freed heap goes back, so that it does not hide the case's own growth
    std::ofstream("/proc/self/clear_refs") << "5";  // resets VmHWM to VmRSS (Linux 4.0+)
    start_mb = status_mb("VmRSS");
  }
  // Called at the end of each iteration: the first one's peak is one load's.
  void iteration_done() {
    if (first_mb < 0.0) first_mb = added_mb();
  }
  double added_mb() const { return status_mb("VmHWM") - start_mb; }
};

void set_counters(benchmark::State& state, const BenchFile& f, const PeakScope& peak) {
  state.counters["added_peak_MB"] = peak.first_mb >= 0.0 ? peak.first_mb : peak.added_mb();
  state.counters["added_peak_all_MB"] = peak.added_mb();
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
  PeakScope peak;
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
    peak.iteration_done();
  }
  set_counters(state, f, peak);
}
BENCHMARK(BM_TinyObjLoaderAlone)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

// tinyobjloader's LoadObj as import_obj called it before it was built on LoadObjWithCallback
// (without its triangulation, through a stream).
void BM_TinyObjLoaderAsImported(benchmark::State& state) {
  const BenchFile& f = bench_file();
  PeakScope peak;
  for (auto _ : state) {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    std::ifstream in(f.path, std::ios::binary);
    tinyobj::MaterialFileReader reader(std::filesystem::path(f.path).parent_path().string());
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &reader,
                          /*triangulate=*/false, /*default_vcols_fallback=*/false)) {
      state.SkipWithError(err.c_str());
      return;
    }
    benchmark::DoNotOptimize(shapes.data());
    peak.iteration_done();
  }
  set_counters(state, f, peak);
}
BENCHMARK(BM_TinyObjLoaderAsImported)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

// tinyobjloader's streaming parser, as import_obj calls it (LoadObjWithCallback through a
// stream), with callbacks that only count: the parser import_obj is built on, without any
// arrays of its own.
void BM_TinyObjLoaderCallback(benchmark::State& state) {
  const BenchFile& f = bench_file();
  PeakScope peak;
  struct Counts {
    uint64_t attributes = 0, corners = 0;
  };
  tinyobj::callback_t cb;
  cb.vertex_cb = [](void* c, float, float, float, float) { ++static_cast<Counts*>(c)->attributes; };
  cb.normal_cb = [](void* c, float, float, float) { ++static_cast<Counts*>(c)->attributes; };
  cb.texcoord_cb = [](void* c, float, float, float) { ++static_cast<Counts*>(c)->attributes; };
  cb.index_cb = [](void* c, tinyobj::index_t*, int n) {
    static_cast<Counts*>(c)->corners += uint64_t(n);
  };
  for (auto _ : state) {
    Counts counts;
    std::string warn, err;
    std::ifstream in(f.path, std::ios::binary);
    tinyobj::MaterialFileReader reader(std::filesystem::path(f.path).parent_path().string());
    if (!tinyobj::LoadObjWithCallback(in, cb, &counts, &reader, &warn, &err)) {
      state.SkipWithError(err.c_str());
      return;
    }
    benchmark::DoNotOptimize(counts);
    peak.iteration_done();
  }
  set_counters(state, f, peak);
}
BENCHMARK(BM_TinyObjLoaderCallback)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

void BM_ImportObj(benchmark::State& state) {
  const BenchFile& f = bench_file();
  PeakScope peak;
  for (auto _ : state) {
    tessera::ImportedModel model = tessera::import_obj(f.path);
    benchmark::DoNotOptimize(model.scene.meshes.data());
    peak.iteration_done();
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
  PeakScope peak;
  for (auto _ : state) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string warn, err;
    if (!loader.LoadBinaryFromFile(&model, &err, &warn, f.path)) {
      state.SkipWithError(err.c_str());
      return;
    }
    benchmark::DoNotOptimize(model.buffers.data());
    peak.iteration_done();
  }
  set_counters(state, f, peak);
}
BENCHMARK(BM_TinyGltfAlone)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

// tinygltf on the file mapped as import_gltf maps it (map_file): the parser's own work without
// LoadBinaryFromFile's read into fresh memory, so that import_gltf's time over this one is what
// its checks and conversion add, its faster read left out.
void BM_TinyGltfOnMappedFile(benchmark::State& state) {
  const BenchFile& f = glb_file();
  PeakScope peak;
  for (auto _ : state) {
    const tessera::MappedFile bytes = tessera::map_file(f.path, UINT32_MAX);
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string warn, err;
    const std::string base_dir = std::filesystem::path(f.path).parent_path().string();
    if (!loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()),
                                     base_dir)) {
      state.SkipWithError(err.c_str());
      return;
    }
    benchmark::DoNotOptimize(model.buffers.data());
    peak.iteration_done();
  }
  set_counters(state, f, peak);
}
BENCHMARK(BM_TinyGltfOnMappedFile)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

// import_gltf's own parse of the document (nlohmann::json, before TinyGLTF parses it again),
// which gives its errors their JSON paths: its share of import_gltf's time.
void BM_GltfJsonParseAlone(benchmark::State& state) {
  const BenchFile& f = glb_file();
  std::ifstream in(f.path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);  // the JSON chunk's (glTF 2.0, 4.4)
  const std::string text = bytes.substr(20, length);
  PeakScope peak;
  for (auto _ : state) {
    const nlohmann::json doc = nlohmann::json::parse(text);
    benchmark::DoNotOptimize(&doc);
    peak.iteration_done();
  }
  set_counters(state, f, peak);
}
BENCHMARK(BM_GltfJsonParseAlone)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

void BM_ImportGltf(benchmark::State& state) {
  const BenchFile& f = glb_file();
  PeakScope peak;
  for (auto _ : state) {
    tessera::ImportedModel model = tessera::import_gltf(f.path);
    benchmark::DoNotOptimize(model.scene.meshes.data());
    peak.iteration_done();
  }
  set_counters(state, f, peak);
}
BENCHMARK(BM_ImportGltf)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

constexpr int kBenchTextures = 8;
constexpr uint32_t kBenchTextureSide = 2048;

// The textured scene's file: a plane per texture, each texture a base colour map.
const std::string& texture_scene() {
  static const std::string path = [] {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / "tessera_bench_textures";
    const std::filesystem::path scene = dir / "scene.json";
    std::error_code ec;
    if (std::filesystem::exists(scene, ec)) return scene.string();
    std::filesystem::create_directories(dir);
    std::string textures, materials, objects;
    uint32_t state = 12345u;
    for (int t = 0; t < kBenchTextures; ++t) {
      tessera::Image8 image;
      image.width = image.height = kBenchTextureSide;
      image.pixels.resize(size_t(kBenchTextureSide) * kBenchTextureSide);
      for (uint32_t y = 0; y < kBenchTextureSide; ++y) {
        for (uint32_t x = 0; x < kBenchTextureSide; ++x) {
          state = state * 1664525u + 1013904223u;  // Numerical Recipes' LCG: noise in low bits
          const uint32_t noise = (state >> 24) & 31u;
          image.at(x, y) = glm::u8vec4((x >> 3) + noise, (y >> 3) + noise, (t * 32) + noise, 255);
        }
      }
      const std::string name = "t" + std::to_string(t);
      tessera::write_png((dir / (name + ".png")).string(), image);
      const std::string sep = t ? ",\n" : "";
      textures +=
          sep + R"({"name": ")" + name + R"(", "type": "file", "file": ")" + name + ".png\"}";
      materials += sep + R"({"name": ")" + name + R"(", "base_color_map": ")" + name + "\"}";
      objects += sep + R"({"mesh": "plane", "material": ")" + name + R"(", "translation": [)" +
                 std::to_string(2 * t) + ", 0, 0]}";
    }
    std::ofstream(dir / "scene.json.part")
        << "{\"version\": 1,\n\"textures\": [" << textures << "],\n\"materials\": [" << materials
        << "],\n\"meshes\": [{\"name\": \"plane\", \"type\": \"plane\"}],\n\"objects\": ["
        << objects << "]}\n";
    std::filesystem::rename(dir / "scene.json.part", scene);
    return scene.string();
  }();
  return path;
}

// state.range(0): parallel_thread_limit for the case (0: every core).
struct ThreadLimit {
  explicit ThreadLimit(const benchmark::State& state) {
    tessera::parallel_thread_limit = unsigned(state.range(0));
  }
  ~ThreadLimit() { tessera::parallel_thread_limit = 0; }
};

double cpu_seconds(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// The calling thread's share of the process's CPU time over a case: 1 when one thread did all
// the work, 1 / cores when the work was divided evenly. Unlike the wall time, it does not
// depend on whether the shared machine had a core free for the other threads.
struct CallerShare {
  double thread = cpu_seconds(CLOCK_THREAD_CPUTIME_ID);
  double process = cpu_seconds(CLOCK_PROCESS_CPUTIME_ID);
  double share() const {
    return (cpu_seconds(CLOCK_THREAD_CPUTIME_ID) - thread) /
           (cpu_seconds(CLOCK_PROCESS_CPUTIME_ID) - process);
  }
};

void set_texture_counters(benchmark::State& state, const CallerShare& caller) {
  state.counters["caller_cpu_share"] = caller.share();
  state.counters["textures"] = kBenchTextures;
  state.counters["texels/s"] =
      benchmark::Counter(double(kBenchTextures) * kBenchTextureSide * kBenchTextureSide,
                         benchmark::Counter::kIsIterationInvariantRate);
}

void BM_DecodeTextures(benchmark::State& state) {
  const std::string& path = texture_scene();
  const ThreadLimit limit(state);
  const CallerShare caller;
  for (auto _ : state) {
    tessera::SceneFile file = tessera::load_scene_file(path);
    benchmark::DoNotOptimize(file.scene.textures.data());
  }
  set_texture_counters(state, caller);
}
BENCHMARK(BM_DecodeTextures)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

void BM_BuildMipChains(benchmark::State& state) {
  const tessera::SceneFile file = tessera::load_scene_file(texture_scene());
  const ThreadLimit limit(state);
  const CallerShare caller;
  for (auto _ : state) {
    tessera::GpuSceneArrays arrays = tessera::flatten_scene(file.scene);
    benchmark::DoNotOptimize(arrays.texels.data());
  }
  set_texture_counters(state, caller);
}
BENCHMARK(BM_BuildMipChains)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
