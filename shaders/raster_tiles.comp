#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Rasterizer for large triangles: one workgroup per screen tile, one thread per pixel. Each
// thread keeps the minimum key of each of its samples over the tile's list and writes it with
// a single atomicMin per sample.
//
// Hierarchical depth rejection (REJECTION, raster_common.glsl): the list is taken in
// chunks of up to one entry per thread. Before each chunk the workgroup reduces the farthest high
// word of its samples' keys so far, an upper bound on their final keys since keys only fall;
// each thread then tests one entry of the chunk against it, and only the entries that may
// still win a sample are rasterized, from shared memory. The bound starts from tile_far (the
// farthest depth of triangles covering the whole tile, written by fill, and earlier batches'
// bounds) and the samples start from the visibility buffer (earlier batches). The image is the
// same as without rejection: a rejected entry's key is above the final key at every sample.
// The list's order (fill's atomics) changes only how much is rejected.
#include "bindings.glsl"
#include "raster_common.glsl"

// One thread per pixel of a TILE_SIZE x TILE_SIZE tile (the same specialization constant).
layout(local_size_x_id = TS_SPEC_TILE_SIZE, local_size_y_id = TS_SPEC_TILE_SIZE) in;

// Sized for the largest tile (16 x 16, validate_tile_size); smaller tiles use the front.
shared uint chunk[TS_TILE_SIZE * TS_TILE_SIZE];  // the current chunk's entries not rejected
// Double-buffered by round parity, so that one barrier after the appends and one after the
// rasterization suffice per chunk (barriers are what the chunks cost): round r appends to
// chunk_count[r & 1] and reduces into far_high_max[(r + 1) & 1], which round r + 1 reads, and
// clears the other slots, which no thread touches during round r.
shared uint chunk_count[2];
shared uint far_high_max[2];
// Entries of the first chunk; each next one doubles up to one per thread. The first chunks
// run before the bound knows much, so small ones bring the first reductions earlier.
const uint FIRST_CHUNK = 32u;

uint64_t best[SAMPLES];  // this thread's pixel: the minimum key of each sample so far
uint changed = 0u;       // bit s: best[s] was lowered here, so it is written back
uint pixel_far = ~0u;    // the largest high word of best[] (0 past the image): a bound per pixel

// The largest high word of this thread's keys; 0 (no constraint) for a pixel past the image.
uint pixel_far_high(bool in_image) {
  uint far_high = 0u;
  for (uint s = 0u; s < SAMPLES; ++s) far_high = max(far_high, uint(best[s] >> 32));
  return in_image ? far_high : 0u;
}

// Tests every sample of `pixel` (fixed-point centre `p`) against raster triangle `index`.
void rasterize(uint index, ivec2 pixel, ivec2 p) {
  RasterTri t = load_raster_tri(index);
  // The box is clamped to the image, so this also keeps pixels past the image's edge out.
  if (any(lessThan(pixel, t.box_min)) || any(greaterThan(pixel, t.box_max))) return;
  // The same rejection per pixel: a subgroup whose pixels all hide the triangle skips the edge
  // functions (the SIMD width is the block size of this finest level).
  if (REJECTION && nearest_key_high(t.depth) > pixel_far) return;
  Edges centre = edges_at(t, p);
  Thresholds h = thresholds_of(t);
  bool lowered = false;
  for (uint s = 0u; s < SAMPLES; ++s) {
    Edges e = edges_moved(t, centre, sample_offset(s) - TS_SUBPIXEL_ONE / 2);
    if (!is_covered(e, h)) continue;
    if (DEBUG_COVERAGE) atomicAdd(coverage[pixel_index(pixel)], 1u);
    uint64_t key = visibility_key(depth_at(t, e), t.id);
    if (key < best[s]) {
      best[s] = key;
      changed |= 1u << s;
      lowered = true;
    }
  }
  if (REJECTION && lowered) pixel_far = pixel_far_high(true);
}

// Adds this subgroup's largest pixel_far to far_high_max[slot], once per subgroup.
void reduce_far_high(uint slot) {
  uint subgroup_far = subgroupMax(pixel_far);
  if (subgroupElect()) atomicMax(far_high_max[slot], subgroup_far);
}

void main() {
  ivec2 tile = ivec2(gl_WorkGroupID.xy);
  uint tile_index = uint(tile.y) * frame.tiles.x + uint(tile.x);
  uint count = tile_counts[tile_index];
  // The next batch's (or frame's) count pass adds to zeroed counts: every tile's count is read
  // here (a binned batch dispatches every tile) and nowhere after, so zeroing it here replaces
  // a fill of the buffer and two barriers before each batch.
  barrier();
  if (gl_LocalInvocationIndex == 0u && count != 0u) {
    tile_counts[tile_index] = 0u;
    if (SHADE_TILES != TS_SHADE_TILES_OFF) tile_drawn[tile_index] = 1u;
  }
  if (count == 0u) return;
  // Past a list's room the frame is redone anyway (direct lists: fill.comp).
  uint stride = frame.tile_list_stride;
  uint first = stride != 0u ? tile_index * stride : tile_offsets[tile_index];
  uint end = stride != 0u ? first + min(count, stride) : min(first + count, frame.tile_entry_capacity);

  ivec2 pixel = tile * TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
  ivec2 p = pixel_centre(pixel);
  bool in_image = all(lessThan(uvec2(pixel), frame.image_size));
  uint index = pixel_index(pixel);
  for (uint s = 0u; s < SAMPLES; ++s) {
    best[s] = REJECTION && in_image ? visibility[sample_index(index, s)] : TS_VIS_EMPTY;
  }

  if (!REJECTION) {
    for (uint k = first; k < end; ++k) rasterize(tile_entries[k], pixel, p);
  } else {
    pixel_far = pixel_far_high(in_image);
    uint group = TILE_SIZE * TILE_SIZE;
    uint local = gl_LocalInvocationIndex;
    uint bound = tile_far[tile_index];
    uint rejected = 0u;
    if (local == 0u) {
      chunk_count[0] = 0u;
      far_high_max[0] = 0u;
    }
    barrier();
    reduce_far_high(0u);
    barrier();
    uint size = min(group, FIRST_CHUNK);
    uint round = 0u;
    for (uint base = first; base < end; base += size, size = min(group, 2u * size), ++round) {
      uint now = round & 1u, next = now ^ 1u;
      bound = min(bound, far_high_max[now]);
      if (local == 0u) {
        chunk_count[next] = 0u;
        far_high_max[next] = 0u;
      }
      uint k = base + local;
      if (local < size && k < end) {
        uint entry = tile_entries[k];
        vec3 depth = uintBitsToFloat(raster_tris[entry].depth_id.xyz);
        if (nearest_key_high(depth) <= bound) chunk[atomicAdd(chunk_count[now], 1u)] = entry;
      }
      barrier();
      uint kept = chunk_count[now];
      rejected += min(end - base, size) - kept;
      for (uint j = 0u; j < kept; ++j) rasterize(chunk[j], pixel, p);
      reduce_far_high(next);
      barrier();
    }
    // The tile's bound for raster_small and later batches (the last round's reduction).
    if (local == 0u) {
      atomicMin(tile_far[tile_index], far_high_max[round & 1u]);
      if (rejected > 0u) atomicAdd(counters[batch.index].rejected_entries, rejected);
    }
  }
  for (uint s = 0u; s < SAMPLES; ++s) {
    if ((changed & (1u << s)) != 0u) atomicMin(visibility[sample_index(index, s)], best[s]);
  }
}
