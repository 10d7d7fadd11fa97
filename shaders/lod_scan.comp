#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Level of detail, second pass (one workgroup): exclusive prefix sum of the triangle counts of
// the lod pass's workgroups (in place), the frame's triangle total, and each batch's triangle
// count and setup dispatch size, so that setup is dispatched indirectly with no read-back.
// 10^6 objects make 3,907 workgroup sums: each thread sums a chunk, as scan.comp does.
#include "bindings.glsl"

layout(local_size_x = TS_SCAN_GROUP_SIZE) in;

layout(set = 0, binding = TS_BINDING_LOD_SUMS, std430) buffer LodSums { uint lod_sums[]; };

// Sums in 64 bits: levels finer than the meshes can make more than 2^32 triangle instances,
// which cannot be numbered (the host reports it).
shared uint64_t partial[TS_SCAN_GROUP_SIZE];

void main() {
  uint n = (frame.object_count + TS_LOD_GROUP_SIZE - 1u) / TS_LOD_GROUP_SIZE;
  uint t = gl_LocalInvocationID.x;
  uint chunk = (n + TS_SCAN_GROUP_SIZE - 1u) / TS_SCAN_GROUP_SIZE;
  uint begin = min(t * chunk, n);
  uint end = min(begin + chunk, n);
  uint64_t sum = 0ul;
  for (uint i = begin; i < end; ++i) sum += uint64_t(lod_sums[i]);
  partial[t] = sum;
  barrier();
  for (uint offset = 1u; offset < TS_SCAN_GROUP_SIZE; offset <<= 1) {
    uint64_t v = t >= offset ? partial[t - offset] : 0ul;
    barrier();
    partial[t] += v;
    barrier();
  }
  uint64_t total = partial[TS_SCAN_GROUP_SIZE - 1];
  bool numbered = total < 0xFFFFFFFFul;  // the all-ones id marks empty pixels
  uint64_t running = partial[t] - sum;
  for (uint i = begin; i < end; ++i) {
    uint64_t count = uint64_t(lod_sums[i]);
    lod_sums[i] = uint(running);
    running += count;
  }
  for (uint b = t; b < frame.batch_count; b += TS_SCAN_GROUP_SIZE) {
    uint64_t first = uint64_t(b) * frame.batch_triangles;
    uint count = numbered && total > first ? uint(min(total - first, uint64_t(frame.batch_triangles))) : 0u;
    counters[b].lod_triangles = count;
    counters[b].setup_dispatch = uvec4((count + TS_SETUP_GROUP_SIZE - 1u) / TS_SETUP_GROUP_SIZE, 1u, 1u, 0u);
  }
  if (t == 0u) counters[0].lod_total = numbered ? uint(total) : 0xFFFFFFFFu;
}
