#version 460
#extension GL_GOOGLE_include_directive : require
// Rasterizer for small triangles: one thread walks its triangle's pixel box, stepping the
// integer edge functions from pixel centre to pixel centre, and atomicMin's each covered sample
// (SAMPLES per pixel) into the visibility buffer.
// With hierarchical depth rejection (REJECTION, raster_common.glsl) it first compares the
// triangle's nearest depth with the bounds of the tiles its box touches (tile_far, lowered by
// fill and raster_tiles, which ran before) and skips a triangle behind all of them; per
// sample, a key that cannot win is not computed.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= min(counters[batch.index].small_tris, frame.raster_capacity)) return;
  RasterTri t = load_raster_tri(small_list[i]);
  uint near_high = nearest_key_high(t.depth);
  if (REJECTION) {
    ivec2 first, last;
    tile_range(t, first, last);
    uint far_high = 0u;
    for (int ty = first.y; ty <= last.y; ++ty) {
      for (int tx = first.x; tx <= last.x; ++tx) {
        far_high = max(far_high, tile_far[uint(ty) * frame.tiles.x + uint(tx)]);
      }
    }
    bool hidden = near_high > far_high;
    // One atomic per subgroup: per-thread atomics on one address would serialize.
    uint n = subgroupBallotBitCount(subgroupBallot(hidden));
    if (n > 0u && subgroupElect()) atomicAdd(counters[batch.index].rejected_small, n);
    if (hidden) return;
  }
  Thresholds h = thresholds_of(t);
  // One pixel right changes E_ab by -(b.y - a.y) * 256, one pixel down by (b.x - a.x) * 256.
  Edges step_x, step_y;
  step_x.e0 = -int64_t(t.v2.y - t.v1.y) * TS_SUBPIXEL_ONE;
  step_x.e1 = -int64_t(t.v0.y - t.v2.y) * TS_SUBPIXEL_ONE;
  step_x.e2 = -int64_t(t.v1.y - t.v0.y) * TS_SUBPIXEL_ONE;
  step_y.e0 = int64_t(t.v2.x - t.v1.x) * TS_SUBPIXEL_ONE;
  step_y.e1 = int64_t(t.v0.x - t.v2.x) * TS_SUBPIXEL_ONE;
  step_y.e2 = int64_t(t.v1.x - t.v0.x) * TS_SUBPIXEL_ONE;

  // Each sample's edge values differ from its pixel centre's by the same amounts in every pixel:
  // taken once here rather than per pixel and sample (six int64 products each).
  Edges to_sample[SAMPLES];
  Edges zero = Edges(0l, 0l, 0l);
  for (uint s = 0u; s < SAMPLES; ++s) {
    to_sample[s] = edges_moved(t, zero, sample_offset(s) - TS_SUBPIXEL_ONE / 2);
  }

  Edges row = edges_at(t, pixel_centre(t.box_min));
  for (int y = t.box_min.y; y <= t.box_max.y; ++y) {
    Edges e = row;
    for (int x = t.box_min.x; x <= t.box_max.x; ++x) {
      for (uint s = 0u; s < SAMPLES; ++s) {
        Edges es = Edges(e.e0 + to_sample[s].e0, e.e1 + to_sample[s].e1, e.e2 + to_sample[s].e2);
        if (!is_covered(es, h)) continue;
        uint p = pixel_index(ivec2(x, y));
        if (DEBUG_COVERAGE) atomicAdd(coverage[p], 1u);
        uint v = sample_index(p, s);
        // A plain read first skips most atomics; a stale value is never below the true one.
        uint64_t current = visibility[v];
        if (REJECTION && uint(current >> 32) < near_high) continue;  // the key would be above
        uint64_t key = visibility_key(depth_at(t, es), t.id);
        if (current > key) atomicMin(visibility[v], key);
      }
      e.e0 += step_x.e0;
      e.e1 += step_x.e1;
      e.e2 += step_x.e2;
    }
    row.e0 += step_y.e0;
    row.e1 += step_y.e1;
    row.e2 += step_y.e2;
  }
}
