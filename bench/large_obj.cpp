#include "bench/large_obj.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/check.h"

namespace tessera::bench {

namespace {
constexpr uint64_t nx = 1024;
uint64_t rows(uint64_t triangles) {
  return std::max<uint64_t>(1, (triangles / 2 + nx - 1) / nx);
}
}  // namespace

uint64_t large_obj_triangles(uint64_t triangles) {
  return 2 * nx * rows(triangles);
}

uint64_t write_large_obj(const std::string& path, uint64_t triangles) {
  const uint64_t ny = rows(triangles);
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), std::fclose);
  if (!f) throw Error("cannot write '" + path + "'");
  std::fprintf(f.get(), "# Tessera benchmark grid: %llu x %llu quads\n", (unsigned long long)nx,
               (unsigned long long)ny);
  // A gentle wave, so positions and normals are not all the same number.
  const auto height = [](double x, double y) {
    return 0.05 * std::sin(7.0 * x) * std::cos(5.0 * y);
  };
  for (uint64_t j = 0; j <= ny; ++j) {
    for (uint64_t i = 0; i <= nx; ++i) {
      const double x = double(i) / nx, y = double(j) / ny;
      std::fprintf(f.get(), "v %.6f %.6f %.6f\n", x, y, height(x, y));
    }
  }
  for (uint64_t j = 0; j <= ny; ++j) {
    for (uint64_t i = 0; i <= nx; ++i) {
      std::fprintf(f.get(), "vt %.6f %.6f\n", double(i) / nx, double(j) / ny);
    }
  }
  for (uint64_t j = 0; j <= ny; ++j) {
    for (uint64_t i = 0; i <= nx; ++i) {
      const double x = double(i) / nx, y = double(j) / ny;
      const double dx = 0.35 * std::cos(7.0 * x) * std::cos(5.0 * y);
      const double dy = -0.25 * std::sin(7.0 * x) * std::sin(5.0 * y);
      const double l = std::sqrt(dx * dx + dy * dy + 1.0);
      std::fprintf(f.get(), "vn %.6f %.6f %.6f\n", -dx / l, -dy / l, 1.0 / l);
    }
  }
  for (uint64_t j = 0; j < ny; ++j) {
    for (uint64_t i = 0; i < nx; ++i) {
      const unsigned long long a = j * (nx + 1) + i + 1, b = a + 1, c = b + nx + 1, d = a + nx + 1;
      std::fprintf(f.get(), "f %llu/%llu/%llu %llu/%llu/%llu %llu/%llu/%llu %llu/%llu/%llu\n", a, a,
                   a, b, b, b, c, c, c, d, d, d);
    }
  }
  if (std::ferror(f.get())) throw Error("cannot write '" + path + "'");
  return 2 * nx * ny;
}

}  // namespace tessera::bench
