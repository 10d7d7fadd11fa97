// Triangle setup shared by the setup and clip passes: clip planes, snapping, culling of what
// covers no pixel, and storing a raster triangle (small list, or counted into its tiles).
// prepare_triangle only decides; the callers count and append, so that the setup pass can do
// it once per subgroup instead of once per thread.

#include "view_clip.glsl"

// What setup decided for one triangle.
const uint OUTCOME_NONE = 0u;          // no triangle (thread past the batch's end)
const uint OUTCOME_NONFINITE = 1u;
const uint OUTCOME_OUTSIDE = 2u;       // outside the view or behind the near plane
const uint OUTCOME_FACING = 3u;        // culled by facing
const uint OUTCOME_EMPTY = 4u;         // zero area, or no pixel centre covered
const uint OUTCOME_CLIP = 5u;          // crosses the near plane or the guard band
const uint OUTCOME_SMALL = 6u;         // rasterize one thread per triangle
const uint OUTCOME_BIG = 7u;           // bin into tiles

// Snaps a triangle whose corners are in front of the near plane and inside the guard band,
// culls it by facing and by what it covers, and fills `t`. `mirrored`: its object's transform
// has a negative determinant (GpuObject.mirrored); `double_sided`: its material is never culled
// by facing (GpuObject.double_sided). Returns OUTCOME_FACING, _EMPTY, _SMALL or
// _BIG.
uint prepare_triangle(vec4 c0, vec4 c1, vec4 c2, uint id, bool mirrored, bool double_sided,
                      out RasterTri t) {
  float near_plane = frame.near_plane;
  const ivec2 v[3] = ivec2[3](snap_to_subpixels(c0), snap_to_subpixels(c1), snap_to_subpixels(c2));
  int64_t area = edge_function(v[0], v[1], v[2]);
  if (area == 0) return OUTCOME_EMPTY;
  // Front faces wind counter-clockwise in world space; the y-down screen mirrors them, so
  // their doubled area comes out negative here. A mirroring transform has already reversed
  // the winding of its object's triangles once more (glTF 2.0: front faces are then clockwise).
  bool clockwise = area < 0;
  bool front = clockwise != mirrored;
  if (!double_sided &&
      ((front && frame.cull == TS_CULL_FRONT) || (!front && frame.cull == TS_CULL_BACK))) {
    return OUTCOME_FACING;
  }
  // Order the vertices so the area is positive: every edge function is then >= 0 inside.
  // Selects rather than arrays indexed by a variable: the H200's compiler kept such arrays in
  // local memory (80 bytes a thread of setup, TESSERA_PIPELINE_STATISTICS).
  t.v0 = v[0];
  t.v1 = clockwise ? v[2] : v[1];
  t.v2 = clockwise ? v[1] : v[2];
  // The depths are divided only for triangles that pass the facing test: at 10^6 grid objects
  // most do not, and a division is several instructions on a GPU.
  t.depth = vec3(near_plane / c0.w, near_plane / (clockwise ? c2.w : c1.w),
                 near_plane / (clockwise ? c1.w : c2.w));
  t.id = id;

  ivec2 lo = min(min(t.v0, t.v1), t.v2);
  ivec2 hi = max(max(t.v0, t.v1), t.v2);
  // Pixel x has its samples at x*256 + [first, last] offsets (its centre x*256 + 128 with one
  // sample): the first pixel whose last sample is >= lo, the last whose first is <= hi.
  ivec2 first = sample_offset_min();
  ivec2 last = sample_offset_max();
  t.box_min = max((lo - last + (TS_SUBPIXEL_ONE - 1)) >> TS_SUBPIXEL_BITS, ivec2(0));
  t.box_max = min((hi - first) >> TS_SUBPIXEL_BITS, ivec2(frame.image_size) - 1);
  if (any(greaterThan(t.box_min, t.box_max))) return OUTCOME_EMPTY;
  // Slivers and sub-pixel triangles often cover no sample: for boxes of up to 2x2 pixels, test
  // the samples here rather than pay for a raster triangle that writes nothing.
  if (all(lessThanEqual(t.box_max - t.box_min, ivec2(1)))) {
    Thresholds h = thresholds_of(t);
    bool any_covered = false;
    for (int y = t.box_min.y; y <= t.box_max.y; ++y) {
      for (int x = t.box_min.x; x <= t.box_max.x; ++x) {
        for (uint s = 0u; s < SAMPLES; ++s) {
          any_covered = any_covered || is_covered(edges_at(t, sample_position(ivec2(x, y), s)), h);
        }
      }
    }
    if (!any_covered) return OUTCOME_EMPTY;
  }
  uvec2 extent = uvec2(t.box_max - t.box_min) + 1u;
  return extent.x * extent.y <= frame.small_triangle_max_area ? OUTCOME_SMALL : OUTCOME_BIG;
}

// The counters of every batch as 64-bit words, for the atomic that appends to both halves of
// GpuCounters::small_counts at once.
layout(set = 0, binding = TS_BINDING_COUNTERS, std430) buffer CounterWords { uint64_t counter_words[]; };

// Appends `walks` entries of `triangles` small triangles to the batch's list; returns the first
// entry's slot.
uint append_small(uint triangles, uint walks) {
  uint64_t both = (uint64_t(triangles) << 32) | uint64_t(walks);
  return uint(atomicAdd(counter_words[batch.index * TS_COUNTERS_WORDS + TS_SMALL_COUNTS_WORD], both));
}

// The `walks` entries of small raster triangle `index` in the per-triangle rasterizer's list,
// from `slot` on (TS_SMALL_WALK_BIT). Past capacity the writes are skipped; the host sees
// small_counts, grows the buffers, redoes the frame.
void store_small_entries(uint index, uint slot, uint walks) {
  for (uint k = 0u; k < walks && slot + k < frame.raster_capacity; ++k) {
    small_list[slot + k] = k == 0u ? index : (TS_SMALL_WALK_BIT | k);
  }
}

void store_raster_tri(uint index, RasterTri t) {
  raster_tris[index].xy01 = uvec4(ivec4(t.v0, t.v1));
  raster_tris[index].xy2_box = uvec4(uvec2(t.v2), uint(t.box_min.x) | (uint(t.box_min.y) << 16),
                                     uint(t.box_max.x) | (uint(t.box_max.y) << 16));
  raster_tris[index].depth_id = uvec4(floatBitsToUint(t.depth), t.id);
}

// Workgroups an indirect dispatch needs for `total` list entries, `per_group` a workgroup. The
// total is clamped to the lists' capacity (past it the host redoes the frame, and the passes
// read no further), which also keeps the count within maxComputeWorkGroupCount.
uint dispatch_groups(uint total, uint per_group) {
  return (min(total, frame.raster_capacity) + per_group - 1u) / per_group;
}

// Appends raise an indirect dispatch only when they reach into a new grain of entries, and then
// to the end of that grain: an atomicMax per appending subgroup, next to the atomicAdd of the
// append on the same counters, made setup 13 % slower on scatter at 10^6 objects (H200).
// The last grain is reached by some append, so the dispatch covers the total; the overshoot,
// under a grain of entries, launches workgroups that return at once.
const uint DISPATCH_GRAIN = 1024u;
bool reaches_new_grain(uint base, uint count) {
  return (base + DISPATCH_GRAIN - 1u) / DISPATCH_GRAIN <
         (base + count + DISPATCH_GRAIN - 1u) / DISPATCH_GRAIN;
}
uint grain_dispatch_groups(uint end, uint per_group) {
  return dispatch_groups((end + DISPATCH_GRAIN - 1u) / DISPATCH_GRAIN * DISPATCH_GRAIN, per_group);
}
// After an append took entries [base, base + count) of a list, raises the indirect dispatch
// whose x is `groups_x` (per_group entries a workgroup) if the append reached a new grain.
#define RAISE_DISPATCH(groups_x, base, count, per_group)                        \
  if (reaches_new_grain(base, count))                                          \
    atomicMax(groups_x, grain_dispatch_groups((base) + (count), per_group))

// Direct tile lists (no scan pass): the per-tile rasterizer runs over every tile once a bin
// entry is appended (the scan pass's dispatch for counted lists). Written by the append that
// took the batch's first entry (base 0), one store instead of one per appending subgroup.
#define WRITE_TILES_DISPATCH(b) counters[b].tiles_dispatch = uvec4(frame.tiles.x, frame.tiles.y, 1u, 0u)

// Bin entries of a binned triangle: its tile range split into blocks of at most
// TS_BIN_CHUNK x TS_BIN_CHUNK tiles, each packed as x | y << 10 | (w - 1) << 20 | (h - 1) << 24
// (tiles_x and tiles_y are at most TS_MAX_TILES_PER_SIDE = 1024, which the renderer checks).
uint bin_entry_count(RasterTri t) {
  ivec2 first, last;
  tile_range(t, first, last);
  uvec2 blocks = (uvec2(last - first) + TS_BIN_CHUNK) / TS_BIN_CHUNK;
  return blocks.x * blocks.y;
}

uint bin_entry(RasterTri t, uint k) {
  ivec2 first, last;
  tile_range(t, first, last);
  uint blocks_x = (uint(last.x - first.x) + TS_BIN_CHUNK) / TS_BIN_CHUNK;
  ivec2 origin = first + ivec2(k % blocks_x, k / blocks_x) * TS_BIN_CHUNK;
  uvec2 size = uvec2(min(last - origin + 1, ivec2(TS_BIN_CHUNK)));
  return uint(origin.x) | (uint(origin.y) << 10) | ((size.x - 1u) << 20) | ((size.y - 1u) << 24);
}

// Writes the bin entries of raster triangle `index` at slots [first, first + count) of the big
// list, skipping those past its capacity (the host sees the count and redoes the frame).
void store_bin_entries(uint index, RasterTri t, uint first, uint count) {
  for (uint k = 0u; k < count && first + k < frame.raster_capacity; ++k) {
    big_list[first + k] = uvec2(index, bin_entry(t, k));
  }
}
