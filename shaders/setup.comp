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

// Cull counts of the workgroup: a million-object frame culls ~10^9 triangles, and even one
// atomic per subgroup on the same four addresses limited setup's throughput.
shared uint group_culled[4];

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

// Adds the number of this subgroup's threads for which `mine` holds to `counter`, once.
#define COUNT_ONCE(counter, mine)                                      \
  {                                                                    \
    uint n = subgroupBallotBitCount(subgroupBallot(mine));             \
    if (n > 0u && subgroupElect()) atomicAdd(counter, n);              \
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

void main() {
  uint local = gl_GlobalInvocationID.x;
  uint id = batch.first_triangle + local;
  // The subgroup's triangles are consecutive ids, so one binary search finds the object of the
  // first and each lane walks forward from it (at most a step for meshes of many triangles):
  // a search per thread, 20 dependent loads deep for a million objects, was setup's bottleneck.
  uint slot = 0u;
  if (subgroupElect()) slot = find_object(subgroupBroadcastFirst(id));
  slot = subgroupBroadcastFirst(slot);
  while (slot + 1u < frame.object_count && objects[slot + 1u].first_triangle <= id) ++slot;
  RasterTri t;
  uint count = LOD ? counters[batch.index].lod_triangles : batch.triangle_count;
  uint outcome = local < count ? classify(slot, id, t) : OUTCOME_NONE;

  if (gl_LocalInvocationIndex < 4u) group_culled[gl_LocalInvocationIndex] = 0u;
  barrier();
  COUNT_ONCE(group_culled[0], outcome == OUTCOME_NONFINITE);
  COUNT_ONCE(group_culled[1], outcome == OUTCOME_OUTSIDE);
  COUNT_ONCE(group_culled[2], outcome == OUTCOME_FACING);
  COUNT_ONCE(group_culled[3], outcome == OUTCOME_EMPTY);
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    if (group_culled[0] > 0u) atomicAdd(counters[batch.index].culled_nonfinite, group_culled[0]);
    if (group_culled[1] > 0u) atomicAdd(counters[batch.index].culled_frustum, group_culled[1]);
    if (group_culled[2] > 0u) atomicAdd(counters[batch.index].culled_backface, group_culled[2]);
    if (group_culled[3] > 0u) atomicAdd(counters[batch.index].culled_empty, group_culled[3]);
  }

  // The passes after setup are dispatched indirectly, sized by what setup and clip append, so
  // that an idle one (nothing to clip, nothing binned) launches no workgroup.
  if (gl_GlobalInvocationID.x == 0u) {
    counters[batch.index].clip_dispatch.yz = uvec2(1u);
    counters[batch.index].big_dispatch.yz = uvec2(1u);
  }
  uint clip_slot;
  {
    uvec4 ballot = subgroupBallot(outcome == OUTCOME_CLIP);
    uint n = subgroupBallotBitCount(ballot);
    uint base = 0u;
    if (n > 0u && subgroupElect()) {
      base = atomicAdd(counters[batch.index].clip_list, n);
      if (reaches_new_grain(base, n))
        atomicMax(counters[batch.index].clip_dispatch.x, grain_dispatch_groups(base + n, TS_GROUP_SIZE));
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
  uint small_slot;
  APPEND_SLOT(counters[batch.index].small_tris, stored && outcome == OUTCOME_SMALL, small_slot);
  if (stored && outcome == OUTCOME_SMALL) small_list[small_slot] = index;
  // Bin entries: a variable number per thread, so the subgroup takes them with a prefix sum.
  uint entries = stored && outcome == OUTCOME_BIG ? bin_entry_count(t) : 0u;
  uint total = subgroupAdd(entries);
  uint base = 0u;
  if (total > 0u && subgroupElect()) {
    base = atomicAdd(counters[batch.index].big_tris, total);
    if (reaches_new_grain(base, total))
      atomicMax(counters[batch.index].big_dispatch.x,
                grain_dispatch_groups(base + total, TS_BIN_ENTRIES_PER_GROUP));
  }
  uint first_entry = subgroupBroadcastFirst(base) + subgroupExclusiveAdd(entries);
  if (entries > 0u) store_bin_entries(index, t, first_entry, entries);
}
