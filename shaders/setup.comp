#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Triangle setup: one thread per triangle instance of the batch. Transforms to clip space,
// culls (non-finite, frustum, facing, empty), snaps to fixed point and appends raster
// triangles; small ones go to the per-triangle list, larger ones to the bin entries that the
// count and fill passes spread over the tiles. Triangles that cross the near plane or the guard band are listed for
// the clip pass instead: clipping code here, even never taken, slows every thread on lavapipe.
// Counters and appends are made once per subgroup: one atomic per thread on a single address
// would serialize a million-triangle batch.
#include "bindings.glsl"
#include "raster_common.glsl"

layout(local_size_x = TS_SETUP_GROUP_SIZE) in;

// Under level of detail the batch's triangle count is the lod_scan pass's, on the GPU.
layout(constant_id = TS_SPEC_LOD) const bool LOD = false;
// Raster triangles only (frames that rasterize and shade in one pass read no walks or bin
// entries): the walks' and bin entries' atomics, each a round trip a subgroup waits for, are
// left out.
layout(constant_id = TS_SPEC_RASTER_ONLY) const bool RASTER_ONLY = false;

// Cull counts of the workgroup, a word per subgroup (at most one per thread): a byte per kind,
// the subgroup's count of it (a subgroup has at most 128 lanes). A million-object frame culls
// ~10^9 triangles, and even one atomic per subgroup on the same four addresses limited
// setup's throughput.
shared uint subgroup_culled[TS_SETUP_GROUP_SIZE];

#include "setup_common.glsl"

bool is_finite(vec4 c) {
  return !any(isnan(c)) && !any(isinf(c));
}

uint classify(uint slot, uint id, out RasterTri t) {
  vec4 c[3];
  triangle_clip_coords(slot, id, c);
  if (!is_finite(c[0]) || !is_finite(c[1]) || !is_finite(c[2])) return OUTCOME_NONFINITE;
  // Trivial reject: all three vertices outside one viewport plane or behind the near plane.
  bool outside = false;
  bool needs_clip = false;
  for (int axis = 0; axis < 2; ++axis) {
    outside = outside || (c[0][axis] > c[0].w && c[1][axis] > c[1].w && c[2][axis] > c[2].w);
    outside = outside || (c[0][axis] < -c[0].w && c[1][axis] < -c[1].w && c[2][axis] < -c[2].w);
  }
  for (int plane = 0; plane < 5; ++plane) {
    float d0 = plane_distance(c[0], plane), d1 = plane_distance(c[1], plane), d2 = plane_distance(c[2], plane);
    if (plane == 0) outside = outside || (d0 < 0.0 && d1 < 0.0 && d2 < 0.0);
    needs_clip = needs_clip || d0 < 0.0 || d1 < 0.0 || d2 < 0.0;
  }
  if (outside) return OUTCOME_OUTSIDE;
  if (needs_clip) return OUTCOME_CLIP;
  return prepare_triangle(c[0], c[1], c[2], id, objects[slot].mirrored != 0u,
                          objects[slot].double_sided != 0u, t);
}

// Slot of this thread in an append list whose length is `counter`, one atomic per subgroup.
#define APPEND_SLOT(counter, mine, slot)                               \
  {                                                                    \
    uvec4 ballot = subgroupBallot(mine);                               \
    uint n = subgroupBallotBitCount(ballot);                           \
    uint base = 0u;                                                    \
    if (n > 0u && subgroupElect()) base = atomicAdd(counter, n);       \
    slot = subgroupBroadcastFirst(base) + subgroupBallotExclusiveBitCount(ballot); \
  }

// find_object(tri) for a `tri` the same in every lane, given that the answer lies in [lo, hi),
// searched by all of them at once: each
// step every lane loads one object and the ballot of their answers keeps one of
// (gl_SubgroupSize + 1) parts of the range, where a binary search keeps one of 2. With 32 lanes a
// million objects take 4 steps of dependent loads instead of 20: setup ran at a quarter of its
// ALU rate on the H200 whichever lane searched (docs/performance.md, "What limits each pass"), so
// the chain's latency, not its loads, was the cost. The answer, the last object whose first
// triangle-instance id is <= tri (objects are sorted by it), is unique, so it is find_object's.
// Every lane of the subgroup must be active (main calls it before any branch, under a condition
// the same in every lane, and a workgroup is a whole number of subgroups): an inactive lane
// would vote "no" in the middle of the "yes" lanes.
// gl_SubgroupSize rather than a count of the active lanes lets the compiler turn the division
// into a shift (the subgroup size is a power of two, and a constant of the device).
uint find_object_in_subgroup(uint tri, uint lo, uint hi) {
  uint lanes = gl_SubgroupSize;
  uint lane = gl_SubgroupInvocationID;
  // Invariant: the answer is in [lo, hi), and lo is it unless a later object starts <= tri.
  while (hi - lo > 1u) {
    // Lane k probes lo + 1 + k * stride (clamped to the last candidate, hi - 1): non-decreasing
    // in k, so the lanes whose object starts <= tri are the first `below` ones.
    uint stride = (hi - lo - 1u + lanes - 1u) / lanes;
    uint probe = min(lo + 1u + lane * stride, hi - 1u);
    uint below = subgroupBallotBitCount(subgroupBallot(objects[probe].first_triangle <= tri));
    // The answer lies from the last "yes" probe (lo if none) to before the first "no" one (equal
    // probes answer alike, so the two differ).
    uint first_no = below < lanes ? min(lo + 1u + below * stride, hi - 1u) : hi;
    if (below > 0u) lo = min(lo + 1u + (below - 1u) * stride, hi - 1u);
    hi = first_no;
  }
  return lo;
}

void main() {
  uint local = gl_GlobalInvocationID.x;
  uint id = batch.first_triangle + local;
  // The subgroup's triangles are consecutive ids, so one search finds the object of the first
  // and each lane walks forward from it (at most a step for meshes of many triangles).
  uint first = subgroupBroadcastFirst(id);
  // Every lane's object lies in [lo, hi).
  uint lo = 0u;
  uint hi = frame.object_count;
  if (!LOD && first < frame.triangle_count) {
    // The objects that hold the first ids of the lanes' groups and of the group after bound it
    // (group_object, adjacent words the whole subgroup loads): for meshes of TS_TRIANGLE_GROUP
    // triangles or more, one or two objects, where a search over 10^6 objects took 4 steps of
    // 32 scattered loads. The lanes' ids reach into the next group if the first lies within a
    // subgroup of its group's end. Level of detail numbers the triangles anew each frame, on
    // the GPU, so its frames search them all.
    uint group = first >> TS_TRIANGLE_GROUP_BITS;
    uint offset = first & (TS_TRIANGLE_GROUP - 1u);
    uint last_group = group + (offset + gl_SubgroupSize - 1u >= TS_TRIANGLE_GROUP ? 1u : 0u);
    lo = group_object(group);
    if (last_group + 1u <= (frame.triangle_count - 1u) >> TS_TRIANGLE_GROUP_BITS) {
      hi = group_object(last_group + 1u) + 1u;
    }
  }
  // Over one or two objects the lanes walk at once, a load at most, where the search would
  // take a step of loads and a ballot before the walk's load.
  uint slot = hi - lo > 2u ? find_object_in_subgroup(first, lo, hi) : lo;
  while (slot + 1u < hi && objects[slot + 1u].first_triangle <= id) ++slot;
  RasterTri t;
  uint count = LOD ? counters[batch.index].lod_triangles : batch.triangle_count;
  uint outcome = local < count ? classify(slot, id, t) : OUTCOME_NONE;

  // Each subgroup sums its counts in one reduction and stores them in its own word, so that
  // one barrier, and no shared atomics, suffice; a thread per kind then adds the words up and
  // makes the workgroup's one atomic for it. Counting with a ballot and a shared atomic per
  // kind and subgroup, between two barriers, took 1.9 ms of setup's 21.3 at 10^6 grid objects
  // on the H200.
  uint culled = outcome >= OUTCOME_NONFINITE && outcome <= OUTCOME_EMPTY
                    ? 1u << (8u * (outcome - OUTCOME_NONFINITE))
                    : 0u;
  uint subgroup_counts = subgroupAdd(culled);
  if (subgroupElect()) subgroup_culled[gl_SubgroupID] = subgroup_counts;
  barrier();
  if (gl_LocalInvocationIndex < 4u) {
    uint kind = gl_LocalInvocationIndex;
    uint n = 0u;
    for (uint sg = 0u; sg < gl_NumSubgroups; ++sg) n += (subgroup_culled[sg] >> (8u * kind)) & 0xFFu;
    if (n > 0u) {
      if (kind == 0u) atomicAdd(counters[batch.index].culled_nonfinite, n);
      if (kind == 1u) atomicAdd(counters[batch.index].culled_frustum, n);
      if (kind == 2u) atomicAdd(counters[batch.index].culled_backface, n);
      if (kind == 3u) atomicAdd(counters[batch.index].culled_empty, n);
    }
  }

  // The passes after setup are dispatched indirectly, sized by what setup and clip append, so
  // that an idle one (nothing to clip, nothing binned) launches no workgroup.
  if (gl_GlobalInvocationID.x == 0u) {
    counters[batch.index].clip_dispatch.yz = uvec2(1u);
    counters[batch.index].big_dispatch.yz = uvec2(1u);
    counters[batch.index].small_dispatch.yz = uvec2(1u);
  }
  // At 10^6 grid objects nearly every subgroup culls all its triangles: such a subgroup skips
  // the appends' ballots, prefix sums and broadcasts (the condition is the same in all its lanes).
  // A ballot rather than subgroupAny: the device is asked for the ballot operations, not votes.
  if (subgroupBallot(outcome >= OUTCOME_CLIP) == uvec4(0u)) return;
  uint clip_slot;
  {
    uvec4 ballot = subgroupBallot(outcome == OUTCOME_CLIP);
    uint n = subgroupBallotBitCount(ballot);
    uint base = 0u;
    if (n > 0u && subgroupElect()) {
      base = atomicAdd(counters[batch.index].clip_list, n);
      RAISE_DISPATCH(counters[batch.index].clip_dispatch.x, base, n, TS_GROUP_SIZE);
    }
    clip_slot = subgroupBroadcastFirst(base) + subgroupBallotExclusiveBitCount(ballot);
  }
  if (outcome == OUTCOME_CLIP && clip_slot < frame.raster_capacity) clip_list[clip_slot] = id;

  // Past capacity the write is skipped; the host sees the count, grows the buffers, redoes.
  bool emits = outcome == OUTCOME_SMALL || outcome == OUTCOME_BIG;
  uint index;
  APPEND_SLOT(counters[batch.index].raster_tris, emits, index);
  bool stored = emits && index < frame.raster_capacity;
  if (stored) store_raster_tri(index, t);
  // The (tile, triangle) pairs of the large triangles' pixel boxes (those binned, or in frames
  // that rasterize and shade in one pass, tested by every pixel of every tile they meet), for
  // the next frame's choice of that pass: counted alike in both kinds of frame.
  uint box_tiles = 0u;
  if (stored && outcome == OUTCOME_BIG) {
    ivec2 first_tile, last_tile;
    tile_range(t, first_tile, last_tile);
    ivec2 tiles = last_tile - first_tile + 1;
    box_tiles = uint(tiles.x * tiles.y);
  }
  uint box_tiles_total = subgroupAdd(box_tiles);
  if (box_tiles_total > 0u && subgroupElect()) {
    atomicAdd(counters[batch.index].large_box_tiles, box_tiles_total);
  }
  if (RASTER_ONLY) return;
  // Small triangles: a variable number of walks per thread, taken with a prefix sum.
  uint walks = stored && outcome == OUTCOME_SMALL ? small_walks(t) : 0u;
  uint small_slot;
  {
    uvec4 ballot = subgroupBallot(walks != 0u);
    uint n = subgroupBallotBitCount(ballot);
    // Most subgroups hold no triangle of several walks: the ballot then gives the slots without
    // the prefix sums (the condition is the same in all lanes).
    bool single = subgroupBallot(walks > 1u) == uvec4(0u);
    uint total = n;
    uint before = subgroupBallotExclusiveBitCount(ballot);
    if (!single) {
      total = subgroupAdd(walks);
      before = subgroupExclusiveAdd(walks);
    }
    uint base = 0u;
    if (n > 0u && subgroupElect()) {
      // One atomic for both counts: a second on the same few addresses made setup 1.6 times
      // slower at 10^3 grid objects on the H200.
      base = append_small(n, total);
      // Direct tile lists run no scan pass, which sizes raster_small's dispatch otherwise.
      if (frame.tile_list_stride != 0u) {
        RAISE_DISPATCH(counters[batch.index].small_dispatch.x, base, total, TS_GROUP_SIZE);
      }
    }
    small_slot = subgroupBroadcastFirst(base) + before;
  }
  if (walks != 0u) store_small_entries(index, small_slot, walks);
  // Bin entries: a variable number per thread, so the subgroup takes them with a prefix sum.
  uint entries = stored && outcome == OUTCOME_BIG ? bin_entry_count(t) : 0u;
  uint total = subgroupAdd(entries);
  uint base = 0u;
  if (total > 0u && subgroupElect()) {
    base = atomicAdd(counters[batch.index].big_tris, total);
    RAISE_DISPATCH(counters[batch.index].big_dispatch.x, base, total, TS_BIN_ENTRIES_PER_GROUP);
    if (frame.tile_list_stride != 0u && base == 0u) WRITE_TILES_DISPATCH(batch.index);
  }
  uint first_entry = subgroupBroadcastFirst(base) + subgroupExclusiveAdd(entries);
  if (entries > 0u) store_bin_entries(index, t, first_entry, entries);
}
