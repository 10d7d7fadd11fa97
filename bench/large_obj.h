#pragma once
// A large OBJ file for the loading-throughput benchmarks (bench/import_bench.cpp,
// bench/make_large_obj.cpp).

#include <cstdint>
#include <string>

namespace tessera::bench {

/// Writes a height-field grid of quads with positions, uvs and normals (`v`, `vt`, `vn`, faces
/// `f v/vt/vn` x 4), the shape of a scanned or tessellated surface, with at least `triangles`
/// triangles once each quad is split in two (rounded up to whole rows of 1024 quads). Returns
/// the number of triangles. Throws Error if the file cannot be written.
uint64_t write_large_obj(const std::string& path, uint64_t triangles);

/// The number of triangles write_large_obj writes for `triangles`.
uint64_t large_obj_triangles(uint64_t triangles);

}  // namespace tessera::bench
