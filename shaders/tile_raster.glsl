// Rasterization of a screen tile by one workgroup, one thread per pixel: each thread keeps the
// minimum key of each of its samples over the tile's triangles. Shared by the per-tile
// rasterizer (raster_tiles.comp), which takes the tile's list (rasterize_tile), and the pass
// that rasterizes and shades small frames in one (raster_shade.comp), which takes every raster
// triangle whose box meets the tile (scan_tile). Needs bindings.glsl and raster_common.glsl;
// the includer declares the workgroup size (TILE_SIZE x TILE_SIZE).
//
// Hierarchical depth rejection (REJECTION, raster_common.glsl) in rasterize_tile: the list is taken in
// chunks of up to one entry per thread. Before each chunk the workgroup reduces the farthest high
// word of its samples' keys so far, an upper bound on their final keys since keys only fall;
// each thread then tests one entry of the chunk against it, and only the entries that may
// still win a sample are rasterized, from shared memory. The image is the same as without
// rejection: a rejected entry's key is above the final key at every sample. The candidates'
// order changes only how much is rejected.

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

// Whether raster triangle `index`'s pixel box meets `tile`.
bool box_meets_tile(uint index, ivec2 tile) {
  uvec2 packed_box = raster_tris[index].xy2_box.zw;
  ivec2 box_min = ivec2(packed_box.x & 0xFFFFu, packed_box.x >> 16);
  ivec2 box_max = ivec2(packed_box.y & 0xFFFFu, packed_box.y >> 16);
  return all(greaterThanEqual(tile, box_min / TILE_SIZE)) && all(lessThanEqual(tile, box_max / TILE_SIZE));
}

// Rasterizes this thread's pixel (`p` its fixed-point centre) against every raster triangle of
// [first, end) whose box meets the tile (raster_shade.comp), from best[] as the caller set it:
// SCAN_ROUND triangles at a time (each thread tests SCAN_ROUND / workgroup size of them), those
// that meet the tile listed in shared memory and rasterized. No depth rejection: the frames that
// take this are small (RendererOptions::raster_shade, at most 512 triangles: one round).
// Every thread of the workgroup must call it (barriers). Double-buffered by round parity, so
// that one barrier a round suffices: round r lists into scan_list[r & 1] while no thread reads
// it (they read it in round r - 2, before barrier r - 1).
const uint SCAN_ROUND = 512u;
shared uint scan_list[2][SCAN_ROUND];
shared uint scan_count[3];
void scan_tile(ivec2 tile, uint first, uint end, ivec2 pixel, ivec2 p) {
  uint group = TILE_SIZE * TILE_SIZE;
  uint local = gl_LocalInvocationIndex;
  if (local == 0u) scan_count[0] = 0u;
  barrier();
  uint round = 0u;
  for (uint base = first; base < end; base += SCAN_ROUND, ++round) {
    uint now = round & 1u;
    // The count round r + 1 lists into, which no thread reads during round r (round r - 1's
    // count is read before barrier r; the three slots turn by round modulo 3).
    if (local == 0u) scan_count[(round + 1u) % 3u] = 0u;
    for (uint k = base + local; k < min(base + SCAN_ROUND, end); k += group) {
      if (box_meets_tile(k, tile)) scan_list[now][atomicAdd(scan_count[round % 3u], 1u)] = k;
    }
    barrier();
    uint kept = scan_count[round % 3u];
    for (uint j = 0u; j < kept; ++j) rasterize(scan_list[now][j], pixel, p);
  }
}

// Rasterizes this thread's pixel (`p` its fixed-point centre) against the entries [first, end)
// of the tile's list, from best[] as the caller set it. Every thread of the workgroup must call
// it (barriers). `bound`: the tile's far bound to start from (tile_far), and on return, with
// REJECTION, the bound the last round reduced. Returns the entries rejected (the same in every
// thread).
uint rasterize_tile(uint first, uint end, ivec2 pixel, ivec2 p, bool in_image, inout uint bound) {
  if (!REJECTION) {
    for (uint k = first; k < end; ++k) rasterize(tile_entries[k], pixel, p);
    return 0u;
  }
  pixel_far = pixel_far_high(in_image);
  uint group = TILE_SIZE * TILE_SIZE;
  uint local = gl_LocalInvocationIndex;
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
  bound = far_high_max[round & 1u];
  return rejected;
}
