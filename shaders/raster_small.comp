#version 460
#extension GL_GOOGLE_include_directive : require
// Rasterizer for small triangles: one thread walks its triangle's pixel box, stepping the
// integer edge functions from pixel centre to pixel centre (in int32 where that is exact,
// edges_fit_int32), and atomicMin's each covered sample (SAMPLES per pixel) into the
// visibility buffer.
// With hierarchical depth rejection (REJECTION, raster_common.glsl) it first compares the
// triangle's nearest depth with the bounds of the tiles its box touches (tile_far, lowered by
// fill and raster_tiles, which ran before) and skips a triangle behind all of them; per
// sample, a key that cannot win is not computed.
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

// The visibility buffer again, a pixel's keys two at a time (bindings.glsl has the one declaration
// that the other passes use; Vulkan lets variables of one binding alias): a pixel's SAMPLES keys
// are contiguous and, SAMPLES being even, start on a 16-byte boundary.
layout(set = 0, binding = TS_BINDING_VISIBILITY, std430) readonly buffer VisibilityPairs {
  u64vec2 visibility_pairs[];
};

// The current keys of pixel p's samples, read together before any is lowered: one wait for
// memory per pixel instead of one per covered sample (each atomicMin between two plain reads
// of the same buffer kept them apart). The read is a filter only (atomicMin decides), so a
// stale value, never below the true one, costs an atomic at most.
void load_pixel_keys(uint p, out uint64_t keys[SAMPLES]) {
  if (SAMPLES == 1u) {
    keys[0] = visibility[p];
    return;
  }
  for (uint k = 0u; k < SAMPLES / 2u; ++k) {
    u64vec2 pair = visibility_pairs[sample_index(p, 0u) / 2u + k];
    keys[2u * k] = pair.x;
    keys[2u * k + 1u] = pair.y;
  }
}

#define EDGE_VEC ivec3
#define RASTER_BOX raster_box_32
#include "raster_small_box.glsl"
#undef EDGE_VEC
#undef RASTER_BOX
#define EDGE_VEC i64vec3
#define RASTER_BOX raster_box_64
#include "raster_small_box.glsl"

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
  if (edges_fit_int32(t)) {
    raster_box_32(t, near_high);
  } else {
    raster_box_64(t, near_high);
  }
}
