#include "host/bench_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include <unistd.h>

#include "compute/baselines/hardware_baseline.h"
#include "compute/context.h"
#include "compute/renderer.h"
#include "core/bench_scenes.h"
#include "core/builtin_scenes.h"
#include "core/check.h"
#include "core/image.h"
#include "core/reference_renderer.h"
#include "host/chart.h"
#include "host/cli.h"

namespace tessera {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(item);
  return out;
}

// One measured point of the sweep: a backend at an object count. Times are medians.
struct Row {
  uint32_t objects = 0;
  std::string backend;
  uint64_t triangles_submitted = 0;
  uint64_t triangles_rasterized = 0;  // after culling and clipping (0: not known)
  uint64_t pixels_shaded = 0;
  uint64_t small_triangles = 0;  // compute: rasterized one thread per triangle
  uint64_t bin_entries = 0;      // compute: blocks of tiles of binned triangles
  uint64_t tile_entries = 0;     // compute: (tile, triangle) pairs the per-tile rasterizer tests
  double total_ms = 0.0;         // GPU time (compute, hardware) or wall time (reference)
  double cpu_record_ms = 0.0;
  std::array<double, kPassCount> pass_ms{};
  uint32_t frames = 0;
  uint32_t batches = 0;
  bool skipped = false;
  std::string note;
  double triangles_per_second() const {
    return total_ms > 0 ? triangles_submitted / (total_ms * 1e-3) : 0.0;
  }
};

class Progress {
 public:
  Progress(size_t total, bool enabled)
      : total_(total), enabled_(enabled && isatty(fileno(stderr))) {}
  void step(const std::string& what) {
    if (!enabled_) return;
    const int width = 30;
    const int filled = int(width * done_ / std::max<size_t>(total_, 1));
    std::fprintf(stderr, "\r[%s%s] %zu/%zu %-40s", std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), done_, total_, what.c_str());
    std::fflush(stderr);
    ++done_;
  }
  ~Progress() {
    if (enabled_) std::fprintf(stderr, "\r%80s\r", "");
  }

 private:
  size_t total_, done_ = 0;
  bool enabled_;
};

Row measure_compute(Renderer& r, const FrameSettings& fs, const BenchArgs& a) {
  Row row;
  for (uint32_t i = 0; i < a.warmup; ++i) r.render(fs);
  std::vector<FrameStats> frames;
  for (uint32_t i = 0; i < a.repeat; ++i) frames.push_back(r.render(fs));
  std::vector<double> total, cpu;
  for (const FrameStats& f : frames) {
    total.push_back(f.gpu_total_ms);
    cpu.push_back(f.cpu_record_submit_ms);
  }
  for (size_t p = 0; p < kPassCount; ++p) {
    std::vector<double> v;
    for (const FrameStats& f : frames) v.push_back(f.pass_ms[p]);
    row.pass_ms[p] = median(v);
  }
  row.total_ms = median(total);
  row.cpu_record_ms = median(cpu);
  row.triangles_submitted = frames.back().triangles_submitted;
  row.triangles_rasterized = frames.back().raster_triangles;
  row.small_triangles = frames.back().small_triangles;
  row.bin_entries = frames.back().big_triangles;
  row.tile_entries = frames.back().tile_entries;
  row.batches = frames.back().batches;
  row.frames = a.repeat;
  if (!frames.back().has_timestamps) row.note = "no timestamps";
  return row;
}

Row measure_hardware(Renderer& r, const FrameSettings& fs, const BenchArgs& a) {
  Row row;
  HardwareBaseline hardware(r);
  for (uint32_t i = 0; i < a.warmup; ++i) hardware.render(fs);
  std::vector<double> pass, cpu;
  for (uint32_t i = 0; i < a.repeat; ++i) {
    BaselineStats s = hardware.render(fs);
    pass.push_back(s.render_pass_ms);
    cpu.push_back(s.cpu_record_submit_ms);
  }
  // The yardstick: timestamps around the render pass (clear, draws, shading).
  row.total_ms = median(pass);
  row.cpu_record_ms = median(cpu);
  row.frames = a.repeat;
  return row;
}

Row measure_reference(const Scene& scene, const FrameSettings& fs, const BenchArgs& a) {
  Row row;
  ReferenceSettings rs;
  rs.width = fs.width;
  rs.height = fs.height;
  const uint32_t frames =
      std::min<uint32_t>(a.repeat, 3);  // it is slow; 3 frames suffice for a median
  std::vector<double> wall;
  ReferenceFrame f;
  for (uint32_t i = 0; i < frames; ++i) {
    const auto start = std::chrono::steady_clock::now();
    f = render_reference(scene, rs);
    wall.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }
  row.total_ms = median(wall);
  row.triangles_rasterized = f.raster_triangles;
  row.frames = frames;
  row.note = "CPU wall time";
  return row;
}

void write_csv(const std::string& path, const std::vector<Row>& rows, const BenchArgs& a,
               const std::string& device) {
  std::ofstream f(path);
  f << "scene,objects,backend,width,height,triangles_submitted,triangles_rasterized,pixels_shaded,"
       "total_ms,"
       "cpu_record_ms,triangles_per_s";
  for (size_t p = 0; p < kPassCount; ++p) f << "," << pass_name(Pass(p)) << "_ms";
  f << ",batches,frames,device,note\n";
  for (const Row& r : rows) {
    if (r.skipped) continue;
    f << a.scene << "," << r.objects << "," << r.backend << "," << a.width << "," << a.height << ","
      << r.triangles_submitted << "," << r.triangles_rasterized << "," << r.pixels_shaded << ","
      << r.total_ms << "," << r.cpu_record_ms << "," << r.triangles_per_second();
    for (double ms : r.pass_ms) f << "," << ms;
    f << "," << r.batches << "," << r.frames << ",\"" << device << "\",\"" << r.note << "\"\n";
  }
  if (!f) throw Error("cannot write CSV '" + path + "'");
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (uint8_t(c) < 0x20) continue;
    out += c;
  }
  return out + "\"";
}

void write_json(const std::string& path, const std::vector<Row>& rows, const BenchArgs& a,
                const std::string& device, const std::string& driver,
                const std::string& command_line,
                const std::vector<std::pair<uint32_t, double>>& ratios) {
  std::ofstream f(path);
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof(date), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  f << "{\n  \"device\": " << json_string(device) << ",\n  \"driver\": " << json_string(driver)
    << ",\n  \"command\": " << json_string(command_line) << ",\n  \"date\": " << json_string(date)
    << ",\n  \"scene\": " << json_string(a.scene) << ",\n  \"width\": " << a.width
    << ",\n  \"height\": " << a.height << ",\n  \"segments\": " << a.segments
    << ",\n  \"small_triangle_area\": " << a.small_triangle_area << ",\n  \"frames\": " << a.repeat
    << ",\n  \"statistic\": \"median\",\n  \"results\": [";
  bool first = true;
  for (const Row& r : rows) {
    if (r.skipped) continue;
    f << (first ? "\n" : ",\n") << "    {\"objects\": " << r.objects
      << ", \"backend\": " << json_string(r.backend)
      << ", \"triangles_submitted\": " << r.triangles_submitted
      << ", \"triangles_rasterized\": " << r.triangles_rasterized
      << ", \"small_triangles\": " << r.small_triangles << ", \"bin_entries\": " << r.bin_entries
      << ", \"tile_entries\": " << r.tile_entries << ", \"pixels_shaded\": " << r.pixels_shaded
      << ", \"total_ms\": " << r.total_ms << ", \"cpu_record_ms\": " << r.cpu_record_ms
      << ", \"triangles_per_s\": " << r.triangles_per_second() << ", \"batches\": " << r.batches
      << ", \"frames\": " << r.frames << ", \"passes_ms\": {";
    for (size_t p = 0; p < kPassCount; ++p)
      f << (p ? ", " : "") << json_string(pass_name(Pass(p))) << ": " << r.pass_ms[p];
    f << "}, \"note\": " << json_string(r.note) << "}";
    first = false;
  }
  f << "\n  ],\n  \"compute_over_hardware\": [";
  for (size_t i = 0; i < ratios.size(); ++i) {
    f << (i ? ", " : "") << "{\"objects\": " << ratios[i].first
      << ", \"ratio\": " << ratios[i].second << "}";
  }
  f << "]\n}\n";
  if (!f) throw Error("cannot write JSON '" + path + "'");
}

std::string human_count(double v) {
  char buf[32];
  if (v >= 1e9)
    std::snprintf(buf, sizeof(buf), "%.2fG", v / 1e9);
  else if (v >= 1e6)
    std::snprintf(buf, sizeof(buf), "%.2fM", v / 1e6);
  else if (v >= 1e3)
    std::snprintf(buf, sizeof(buf), "%.1fk", v / 1e3);
  else
    std::snprintf(buf, sizeof(buf), "%.0f", v);
  return buf;
}

}  // namespace

std::string bench_help() {
  return "usage: tessera bench [options]\n"
         "\n"
         "Renders a benchmark scene family at each object count with each backend, and reports\n"
         "medians of GPU timestamps (per pass for the compute path; around the render pass for\n"
         "the hardware baseline; wall time for the CPU reference).\n"
         "\n"
         "  --scene NAME        grid (default), scatter or huge; or a built-in scene of\n"
         "                      `tessera scenes` (one point: its own object count)\n"
         "  --objects LIST      object counts, e.g. 1,10,100,1000 (default 1,10,100)\n"
         "  --size WxH          image size (default 512x512)\n"
         "  --segments S        sphere slices; S/2 stacks (default 32: 960 triangles)\n"
         "  --device D          lavapipe, gpu or an index (default: a discrete GPU, else "
         "lavapipe)\n"
         "  --backends LIST     compute, hardware, reference (default compute,hardware)\n"
         "  --repeat K          timed frames per point, 1..1000 (default 10)\n"
         "  --warmup K          untimed frames first, 0..100 (default 2)\n"
         "  --reference-max-triangles T   skip the reference above T triangles (default 2000000)\n"
         "  --small-triangle-area A   pixel-box area up to which a triangle is rasterized by one\n"
         "                      thread; larger ones are binned into tiles (default 64)\n"
         "  --generic-shading   shade with the generic pipeline instead of one specialized to\n"
         "                      the scene's light counts, to measure what specialization saves\n"
         "  --csv FILE          write every measurement as CSV\n"
         "  --json FILE         the same as JSON, with device, driver and command\n"
         "  --chart FILE        .svg or .png: time against objects (log-log, one line per "
         "backend)\n"
         "                      and the compute path's per-pass breakdown\n"
         "  --validate          enable the Khronos validation layer (exit status 3 on reports)\n"
         "  --quiet             no progress bar or table\n";
}

bool parse_bench_args(const std::vector<std::string>& args, BenchArgs& out) {
  const std::map<std::string, ValueHandler> with_value = {
      {"--scene", [&](const std::string& v) { out.scene = v; }},
      {"--objects",
       [&](const std::string& v) {
         out.objects.clear();
         for (const std::string& item : split(v))
           out.objects.push_back(parse_uint("--objects", item, 1, 100'000'000));
         if (out.objects.empty()) throw Error("--objects needs at least one count");
       }},
      {"--size", [&](const std::string& v) { parse_size(v, out.width, out.height); }},
      {"--segments",
       [&](const std::string& v) { out.segments = parse_uint("--segments", v, 4, 4096); }},
      {"--device", [&](const std::string& v) { out.device = v; }},
      {"--backends",
       [&](const std::string& v) {
         out.backends = split(v);
         for (const std::string& b : out.backends) {
           if (b != "compute" && b != "hardware" && b != "reference") {
             throw Error("--backends expects compute, hardware or reference, got '" + b + "'");
           }
         }
         if (out.backends.empty()) throw Error("--backends needs at least one backend");
       }},
      {"--repeat", [&](const std::string& v) { out.repeat = parse_uint("--repeat", v, 1, 1000); }},
      {"--warmup", [&](const std::string& v) { out.warmup = parse_uint("--warmup", v, 0, 100); }},
      {"--reference-max-triangles",
       [&](const std::string& v) {
         out.reference_max_triangles =
             parse_uint("--reference-max-triangles", v, 1, 4'000'000'000u);
       }},
      {"--small-triangle-area",
       [&](const std::string& v) {
         out.small_triangle_area = parse_uint("--small-triangle-area", v, 0, 1u << 24);
       }},
      {"--csv", [&](const std::string& v) { out.csv = v; }},
      {"--json", [&](const std::string& v) { out.json = v; }},
      {"--chart", [&](const std::string& v) { out.chart = v; }},
  };
  const std::map<std::string, std::function<void()>> flags = {
      {"--quiet", [&] { out.quiet = true; }},
      {"--generic-shading", [&] { out.generic_shading = true; }},
      {"--validate", [&] { out.validate = true; }}};
  if (!parse_options(args, with_value, flags, "tessera bench")) return false;
  if (!is_builtin_scene(out.scene))
    make_bench_scene(out.scene, 1, out.segments, 1.0f);  // unknown: fails early
  for (const std::string* path : {&out.csv, &out.json, &out.chart}) {
    if (!path->empty() && !can_write_file(*path))
      throw Error("cannot write output file '" + *path + "'");
  }
  if (!out.chart.empty() && !(out.chart.ends_with(".svg") || out.chart.ends_with(".png"))) {
    throw Error("--chart must name a .svg or .png file, got '" + out.chart + "'");
  }
  return true;
}

int run_bench(const BenchArgs& a, const std::string& command_line) {
  const bool gpu_backends =
      std::any_of(a.backends.begin(), a.backends.end(),
                  [](const std::string& b) { return b == "compute" || b == "hardware"; });
  std::unique_ptr<Context> ctx;
  std::unique_ptr<Renderer> renderer;
  std::string device = "reference (CPU)", driver;
  if (gpu_backends) {
    ContextOptions options;
    options.device = a.device;
    options.validation = a.validate;
    ctx = create_context(options);
    RendererOptions options_r;
    options_r.small_triangle_max_area = a.small_triangle_area;
    options_r.specialize_lights = !a.generic_shading;
    renderer = std::make_unique<Renderer>(*ctx, options_r);
    device = ctx->properties.deviceName;
    driver = ctx->driver;
  }
  FrameSettings fs;
  fs.width = a.width;
  fs.height = a.height;
  const float aspect = float(a.width) / float(a.height);

  std::vector<Row> rows;
  // A built-in scene has a fixed object count: it is one point of the sweep.
  const bool builtin = is_builtin_scene(a.scene);
  const std::vector<uint32_t> counts =
      builtin ? std::vector<uint32_t>{uint32_t(make_builtin_scene(a.scene).objects.size())}
              : a.objects;
  Progress progress(counts.size() * a.backends.size(), !a.quiet);
  for (uint32_t n : counts) {
    const Scene scene =
        builtin ? make_builtin_scene(a.scene) : make_bench_scene(a.scene, n, a.segments, aspect);
    uint64_t triangles = 0;
    for (const Object& o : scene.objects) triangles += scene.meshes[o.mesh].triangle_count();
    uint64_t pixels_shaded = 0;
    if (renderer) {
      renderer->set_scene(scene);  // uploaded once, outside the timed frames
      renderer->render(fs);
      for (uint64_t key : renderer->read_visibility()) pixels_shaded += key != ~0ull;
    }
    for (const std::string& backend : a.backends) {
      progress.step("objects " + std::to_string(n) + ", " + backend);
      Row row;
      if (backend == "compute") {
        row = measure_compute(*renderer, fs, a);
      } else if (backend == "hardware") {
        row = measure_hardware(*renderer, fs, a);
      } else if (triangles <= a.reference_max_triangles) {
        row = measure_reference(scene, fs, a);
      } else {
        row.skipped = true;
      }
      row.objects = n;
      row.backend = backend;
      row.triangles_submitted = triangles;
      row.pixels_shaded = pixels_shaded;
      rows.push_back(row);
    }
  }

  // compute / hardware per object count, from the same run.
  std::vector<std::pair<uint32_t, double>> ratios;
  for (uint32_t n : counts) {
    const Row* c = nullptr;
    const Row* h = nullptr;
    for (const Row& r : rows) {
      if (r.objects == n && r.backend == "compute") c = &r;
      if (r.objects == n && r.backend == "hardware") h = &r;
    }
    if (c && h && h->total_ms > 0) ratios.push_back({n, c->total_ms / h->total_ms});
  }

  if (!a.quiet) {
    std::printf(
        "scene %s, %ux%u, %u segments, small-triangle area %u, device '%s' (%s), medians of %u "
        "frames\n",
        a.scene.c_str(), a.width, a.height, a.segments, a.small_triangle_area, device.c_str(),
        driver.c_str(), a.repeat);
    std::printf("%10s %10s %12s %12s %10s %12s %10s\n", "objects", "backend", "triangles",
                "rasterized", "ms", "triangles/s", "cpu ms");
    for (const Row& r : rows) {
      if (r.skipped) {
        std::printf("%10u %10s %12s  skipped (over --reference-max-triangles)\n", r.objects,
                    r.backend.c_str(), human_count(double(r.triangles_submitted)).c_str());
        continue;
      }
      std::printf(
          "%10u %10s %12s %12s %10.3f %12s %10.3f\n", r.objects, r.backend.c_str(),
          human_count(double(r.triangles_submitted)).c_str(),
          r.triangles_rasterized ? human_count(double(r.triangles_rasterized)).c_str() : "-",
          r.total_ms, human_count(r.triangles_per_second()).c_str(), r.cpu_record_ms);
    }
    for (const auto& [n, ratio] : ratios) {
      std::printf("objects %u: compute / hardware = %.3f (compute %.2fx %s)\n", n, ratio,
                  ratio < 1 ? 1 / ratio : ratio, ratio < 1 ? "faster" : "slower");
    }
  }
  if (!a.csv.empty()) write_csv(a.csv, rows, a, device);
  if (!a.json.empty()) write_json(a.json, rows, a, device, driver, command_line, ratios);
  if (!a.chart.empty()) {
    ChartSpec spec;
    spec.title = "tessera bench: " + a.scene + ", " + std::to_string(a.width) + "x" +
                 std::to_string(a.height) + ", " + device + " (medians of " +
                 std::to_string(a.repeat) + " frames)";
    spec.x_label = "objects";
    spec.y_label = "frame time (ms)";
    for (const std::string& backend : a.backends) {
      Series s;
      s.name = backend == "reference" ? "reference (CPU wall)" : backend;
      for (const Row& r : rows) {
        if (r.backend != backend) continue;
        s.x.push_back(r.objects);
        s.y.push_back(r.skipped ? 0.0 : r.total_ms);
      }
      spec.lines.push_back(s);
    }
    if (std::find(a.backends.begin(), a.backends.end(), "compute") != a.backends.end()) {
      spec.bars_title = "compute path, GPU time per pass";
      spec.bars_y_label = "ms";
      for (size_t p = 0; p < kPassCount; ++p) spec.bars.layers.push_back(pass_name(Pass(p)));
      for (const Row& r : rows) {
        if (r.backend != "compute") continue;
        spec.bars.categories.push_back(human_count(r.objects));
        spec.bars.values.push_back(std::vector<double>(r.pass_ms.begin(), r.pass_ms.end()));
      }
    }
    write_chart(a.chart, spec);
  }
  if (!a.quiet) {
    for (const std::string* p : {&a.csv, &a.json, &a.chart}) {
      if (!p->empty()) std::printf("wrote %s\n", p->c_str());
    }
  }
  if (ctx && ctx->validation && (ctx->validation->errors || ctx->validation->warnings)) {
    std::fprintf(stderr, "validation reported %u errors and %u warnings\n",
                 ctx->validation->errors.load(), ctx->validation->warnings.load());
    return 3;
  }
  return 0;
}

}  // namespace tessera
