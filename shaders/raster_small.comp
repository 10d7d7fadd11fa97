#version 460
#extension GL_GOOGLE_include_directive : require
// Rasterizer for small triangles: one thread per entry of the list setup and clip append walks
// its triangle's pixel box (or every walks-th row of it, for a box dealt out among several
// walks: small_walks), stepping the integer edge functions from pixel centre to pixel centre
// (in int32 where that is exact, edges_fit_int32), and atomicMin's each covered sample
// (SAMPLES per pixel) into the visibility buffer.
// With hierarchical depth rejection (REJECTION, raster_common.glsl) it first compares the
// triangle's nearest depth with the bounds of the tiles its box touches (tile_far, lowered by
// fill and raster_tiles, which ran before) and skips a triangle behind all of them.
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_GROUP_SIZE) in;

// Whether the triangle's box can be walked in 32-bit arithmetic (half the instructions of int64
// on a GPU) with the same keys: every edge value at every sample point of the box lies in
// int32's range, and every covered sample's edge values convert to float exactly.
// E_ab(p) = dx * (p.y - a.y) - dy * (p.x - a.x) with a, b vertices and p a sample point of the
// box: all lie in the rectangle `w` wide that holds the vertices and the box's sample points,
// so |dx|, |p.x - a.x| <= w.x and |dy|, |p.y - a.y| <= w.y, and |E| <= 2 * w.x * w.y. At a
// covered sample each of the three values is >= 0 and they sum to the doubled area, which is
// at most the area of the vertices' bounding box (a triangle fills at most half of it), so at
// most w.x * w.y. With w.x * w.y <= 2^24: |E| <= 2^25, far inside int32 with the threshold
// taken off (<= 1), and a covered sample's values are integers <= 2^24, which float holds
// exactly, so converting the int32 value gives the float that converting the int64 one does
// whatever rounding the implementation uses (Vulkan leaves it open).
// Nothing else bounds this: the small-triangle area (RendererOptions::small_triangle_max_area)
// is that of the box, which is clamped to the image, and the vertices may lie anywhere in the
// guard band (+-TS_GUARD_BAND_PX, 2^23 fixed-point units). Where the box is not clamped,
// setup's rounding puts the vertices and the box's sample points within (n + 2) * 256 on each
// axis of a box n pixels wide, so a box of n.x * n.y <= 64 pixels (the default limit) has
// w.x * w.y < (n.x + 2) * (n.y + 2) * 2^16 <= 198 * 2^16 < 2^24 (64 x 1 is the worst): the
// default scenes' small triangles all take the int32 walk. A sliver reaching far out of the
// image, or a box under a raised limit, takes the int64 one.
// Vertices and sample points lie within 2^23 of the origin, so w < 2^24 fits an int and the
// product an int64.
bool edges_fit_int32(RasterTri t) {
  ivec2 lo = min(min(min(t.v0, t.v1), t.v2), t.box_min * TS_SUBPIXEL_ONE + sample_offset_min());
  ivec2 hi = max(max(max(t.v0, t.v1), t.v2), t.box_max * TS_SUBPIXEL_ONE + sample_offset_max());
  ivec2 w = hi - lo;
  return int64_t(w.x) * int64_t(w.y) <= (1l << 24);
}

// What the int32 walk of a triangle needs besides its edge values: steps from pixel to pixel,
// each sample's offset from its pixel centre's values, and their largest.
struct Walk32 {
  ivec3 step_x, step_y;  // one pixel right, one pixel down
  ivec3 pixel_reach;     // the largest of the samples' offsets on each edge
  ivec3 threshold;       // edge_threshold of each edge (0 or 1)
  float area;            // the doubled area, as depth_at divides by it
};

// The walk's constants and the edge values (less nothing) at the centre of the box's first
// pixel.
Walk32 walk32_of(RasterTri t, out ivec3 first, out ivec3 to_sample[SAMPLES]) {
  Walk32 w;
  Thresholds h = thresholds_of(t);
  i64vec3 threshold = i64vec3(h.t0, h.t1, h.t2);
  w.threshold = ivec3(threshold);
  Edges e = edges_at(t, pixel_centre(t.box_min));
  // The three edge functions sum to the doubled area at every point (barycentric weights sum
  // to one), so float(e0 + e1 + e2), which depth_at divides by, is the same for every sample.
  w.area = float(e.e0 + e.e1 + e.e2);
  first = ivec3(i64vec3(e.e0, e.e1, e.e2));
  // One pixel right changes E_ab by -(b.y - a.y) * 256, one pixel down by (b.x - a.x) * 256.
  ivec3 dx = ivec3(t.v2.x - t.v1.x, t.v0.x - t.v2.x, t.v1.x - t.v0.x);
  ivec3 dy = ivec3(t.v2.y - t.v1.y, t.v0.y - t.v2.y, t.v1.y - t.v0.y);
  w.step_x = ivec3(-i64vec3(dy) * TS_SUBPIXEL_ONE);
  w.step_y = ivec3(i64vec3(dx) * TS_SUBPIXEL_ONE);
  // Each sample's edge values less the thresholds differ from its pixel centre's by the same
  // amounts in every pixel; `reach` is their largest on each edge, so that one test per pixel
  // tells whether any of its samples can be covered (the largest value on each edge is that
  // of some sample: a sample point's value less its threshold, in range like the others).
  i64vec3 reach;
  for (uint s = 0u; s < SAMPLES; ++s) {
    Edges d = edges_moved(t, Edges(0l, 0l, 0l), sample_offset(s) - TS_SUBPIXEL_ONE / 2);
    i64vec3 moved = i64vec3(d.e0, d.e1, d.e2) - threshold;
    to_sample[s] = ivec3(moved);
    reach = s == 0u ? moved : max(reach, moved);
  }
  w.pixel_reach = ivec3(reach);
  return w;
}

// Writes the keys of the samples of `pixel` that the triangle covers, `e` being the edge values
// at the pixel's centre; returns whether any sample may be covered (the row test of the walk).
// Every covered sample's key goes to an atomicMin whose result is not read, so that no step of
// a walk waits for memory. Reading the pixel's keys first, to skip the atomics of samples
// already nearer (and, with depth rejection, the keys' depths), made each pixel wait for a
// load: a thread walking a 64-pixel box waited 64 times in a row, the whole pass's time for a
// frame of few small triangles. On the H200 at 1920x1080 (docs/performance.md, "Issue 13,
// sixth round") the pass went from 0.021 to 0.013 ms for one grid sphere, from 0.042 to
// 0.027 ms for 1,000, and was unchanged on scatter at 10^5 and 10^6 objects, whose hidden
// triangles depth rejection skips before their walk.
bool cover_pixel_int32(RasterTri t, Walk32 w, ivec3 to_sample[SAMPLES], ivec2 pixel, ivec3 e) {
  ivec3 m = e + w.pixel_reach;
  bool passes = (m.x | m.y | m.z) >= 0;
  uint covered = passes && SAMPLES == 1u ? 1u : 0u;  // with one sample, m is the sample's value
  if (passes && SAMPLES > 1u) {
    for (uint s = 0u; s < SAMPLES; ++s) {
      ivec3 es = e + to_sample[s];
      if ((es.x | es.y | es.z) >= 0) covered |= 1u << s;
    }
  }
  if (covered != 0u) {
    uint p = pixel_index(pixel);
    for (uint s = 0u; s < SAMPLES; ++s) {
      if ((covered & (1u << s)) == 0u) continue;
      if (DEBUG_COVERAGE) atomicAdd(coverage[p], 1u);
      ivec3 exact = (SAMPLES == 1u ? m : e + to_sample[s]) + w.threshold;
      uint64_t key = visibility_key(depth_at(t, vec3(exact), w.area), t.id);
      atomicMin(visibility[sample_index(p, s)], key);
    }
  }
  return passes;
}

// Walk `walk` of the triangle's `walks` (small_walks): rows walk, walk + walks, ... of its box,
// in int32 (edges_fit_int32 has shown that exact). Every value is taken in int64 first (exact:
// edge_function's bound) and converted; the walk then only adds and multiplies. SPIR-V defines
// OpIAdd and OpIMul as the low bits of the exact result and OpSConvert to a narrower type as
// truncation, so every value here is exact modulo 2^32, and the values at the box's sample
// points (less a threshold), the only ones compared or converted to float, lie in int32's range
// and are the exact ones (the terms they are summed from need not).
// Thresholds are folded in: a sample is covered when each edge value less its threshold
// (edge_threshold: 0 or 1) is >= 0, that is when the OR of the three has its sign bit clear.
void raster_box_int32(RasterTri t, uint walk, uint walks) {
  ivec3 row;
  ivec3 to_sample[SAMPLES];
  Walk32 w = walk32_of(t, row, to_sample);
  row += int(walk) * w.step_y;
  ivec3 row_step = int(walks) * w.step_y;
  ivec3 e = row;
  ivec2 pixel = ivec2(t.box_min.x, t.box_min.y + int(walk));
  bool entered = false;  // a pixel of this row has passed
  // One loop over the box's pixels, not one per row: the threads of a SIMD group walk boxes of
  // different shapes, and nested loops would hold the group for its widest box's width in
  // every row of its tallest box.
  while (true) {
    bool passes = cover_pixel_int32(t, w, to_sample, pixel, e);
    // Each of m's components is affine in x, so the pixels of a row that pass are one run:
    // after it, the rest of the row cannot pass either.
    bool row_done = pixel.x == t.box_max.x || (entered && !passes);
    entered = entered || passes;
    if (!row_done) {
      pixel.x++;
      e += w.step_x;
    } else if (pixel.y + int(walks) <= t.box_max.y) {
      pixel = ivec2(t.box_min.x, pixel.y + int(walks));
      row += row_step;
      e = row;
      entered = false;
    } else {
      break;
    }
  }
}

// The samples of `pixel` tested with their edge values taken anew in int64 (edges_at), for the
// boxes edges_fit_int32 refuses: rare (slivers reaching far out of the image, a raised
// small-triangle limit), so slower per sample, but with few live values, so that it does not
// raise the registers, and lower the occupancy, of the whole shader.
void cover_pixel_int64(RasterTri t, Thresholds h, ivec2 pixel, uint near_high) {
  uint p = pixel_index(pixel);
  for (uint s = 0u; s < SAMPLES; ++s) {
    Edges e = edges_at(t, sample_position(pixel, s));
    if (!is_covered(e, h)) continue;
    if (DEBUG_COVERAGE) atomicAdd(coverage[p], 1u);
    uint v = sample_index(p, s);
    // A plain read first skips most atomics; a stale value is never below the true one.
    uint64_t current = visibility[v];
    if (REJECTION && uint(current >> 32) < near_high) continue;  // the key would be above
    uint64_t key = visibility_key(depth_at(t, e), t.id);
    if (current > key) atomicMin(visibility[v], key);
  }
}

void raster_box_int64(RasterTri t, uint walk, uint walks) {
  Thresholds h = thresholds_of(t);
  uint near_high = nearest_key_high(t.depth);
  for (int y = t.box_min.y + int(walk); y <= t.box_max.y; y += int(walks)) {
    for (int x = t.box_min.x; x <= t.box_max.x; ++x) cover_pixel_int64(t, h, ivec2(x, y), near_high);
  }
}

// Rasterizes entry `i` of the list (a walk of a small triangle).
void raster_entry(uint i) {
  uint entry = small_list[i];
  uint walk = (entry & TS_SMALL_WALK_BIT) != 0u ? entry & ~TS_SMALL_WALK_BIT : 0u;
  RasterTri t = load_raster_tri(walk == 0u ? entry : small_list[i - walk]);
  if (REJECTION) {
    ivec2 first, last;
    tile_range(t, first, last);
    uint far_high = 0u;
    for (int ty = first.y; ty <= last.y; ++ty) {
      for (int tx = first.x; tx <= last.x; ++tx) {
        far_high = max(far_high, tile_far[uint(ty) * frame.tiles.x + uint(tx)]);
      }
    }
    bool hidden = nearest_key_high(t.depth) > far_high;
    // Counted once per triangle, by its first walk. One atomic per subgroup: per-thread atomics
    // on one address would serialize.
    uint n = subgroupBallotBitCount(subgroupBallot(hidden && walk == 0u));
    if (n > 0u && subgroupElect()) atomicAdd(counters[batch.index].rejected_small, n);
    if (hidden) return;
  }
  if (SHADE_TILES != TS_SHADE_TILES_OFF && walk == 0u) {
    // Every tile the box touches, whether or not a sample is covered there: a tile listed
    // without need is only shaded as background by the shading pass's code.
    ivec2 first, last;
    tile_range(t, first, last);
    for (int ty = first.y; ty <= last.y; ++ty) {
      for (int tx = first.x; tx <= last.x; ++tx) tile_drawn[uint(ty) * frame.tiles.x + uint(tx)] = 1u;
    }
  }
  uint walks = small_walks(t);
  if (edges_fit_int32(t)) {
    raster_box_int32(t, walk, walks);
  } else {
    raster_box_int64(t, walk, walks);
  }
}

// A loop over the list's entries, a thread each: dispatched indirectly (small_dispatch) the
// workgroups cover them all once; dispatched directly, sized by the last frame's entries
// (renderer.cpp's direct_groups), the loop takes as many turns as this frame needs.
void main() {
  uint entries = min(counters[batch.index].small_counts.x, frame.raster_capacity);
  for (uint i = gl_GlobalInvocationID.x; i < entries; i += gl_NumWorkGroups.x * TS_GROUP_SIZE) {
    raster_entry(i);
  }
}
