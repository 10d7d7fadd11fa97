// Coverage, depth and visibility keys shared by both rasterizers (per triangle and per tile).
// Both paths must produce bit-identical keys, so every value here is either exact integer
// arithmetic or float arithmetic marked `precise` and evaluated in one fixed order.

#include "samples.glsl"

layout(constant_id = TS_SPEC_DEBUG_COVERAGE) const bool DEBUG_COVERAGE = false;
// Tile side in pixels (RendererOptions::tile_size). A specialization constant rather than a
// #define so that one SPIR-V module serves every size: the driver folds it like a literal.
layout(constant_id = TS_SPEC_TILE_SIZE) const int TILE_SIZE = TS_TILE_SIZE;
// Shading by tiles (RendererOptions::shade_tiles): TS_SHADE_TILES_OFF, or the rasterizers mark
// each tile they may write a sample of in tile_drawn, so that list_tiles can send the others
// to the background's dispatch.
layout(constant_id = TS_SPEC_SHADE_TILES) const uint SHADE_TILES = TS_SHADE_TILES_OFF;

struct RasterTri {
  ivec2 v0, v1, v2;     // fixed point, oriented so that the doubled area is positive
  ivec2 box_min, box_max;
  vec3 depth;           // near / w at each vertex (reverse depth: larger is nearer)
  uint id;              // triangle-instance id
};

RasterTri load_raster_tri(uint index) {
  GpuRasterTri t = raster_tris[index];
  RasterTri r;
  r.v0 = ivec2(t.xy01.xy);
  r.v1 = ivec2(t.xy01.zw);
  r.v2 = ivec2(t.xy2_box.xy);
  r.box_min = ivec2(t.xy2_box.z & 0xFFFFu, t.xy2_box.z >> 16);
  r.box_max = ivec2(t.xy2_box.w & 0xFFFFu, t.xy2_box.w >> 16);
  r.depth = uintBitsToFloat(t.depth_id.xyz);
  r.id = t.depth_id.w;
  return r;
}

// Fixed-point position of the centre of pixel (x, y).
ivec2 pixel_centre(ivec2 pixel) {
  return pixel * TS_SUBPIXEL_ONE + TS_SUBPIXEL_ONE / 2;
}

// Fixed-point position of sample s of pixel (x, y) (the centre with one sample).
ivec2 sample_position(ivec2 pixel, uint s) {
  return pixel * TS_SUBPIXEL_ONE + sample_offset(s);
}

// Edge function of the directed edge a->b at p: twice the signed area of (a, b, p).
// Inputs are < 2^24 in magnitude, so the products need 48 bits: int64 is exact.
int64_t edge_function(ivec2 a, ivec2 b, ivec2 p) {
  return int64_t(b.x - a.x) * int64_t(p.y - a.y) - int64_t(b.y - a.y) * int64_t(p.x - a.x);
}

// Top-left fill rule for positively oriented triangles in y-down pixel coordinates: a sample
// exactly on an edge belongs to the triangle only if the edge is a top edge (horizontal,
// running in +x) or a left edge (running in -y). Two triangles sharing an edge traverse it in
// opposite directions, so exactly one of them owns samples on it.
// Returns the smallest edge value that counts as covered: 0 for top-left edges, 1 otherwise.
int64_t edge_threshold(ivec2 a, ivec2 b) {
  bool top = a.y == b.y && b.x > a.x;
  bool left = b.y < a.y;
  return (top || left) ? 0l : 1l;
}

// Edge values at a pixel centre: x for edge v1->v2 (weight of v0), y for v2->v0, z for v0->v1.
struct Edges {
  int64_t e0, e1, e2;
};

Edges edges_at(RasterTri t, ivec2 p) {
  Edges e;
  e.e0 = edge_function(t.v1, t.v2, p);
  e.e1 = edge_function(t.v2, t.v0, p);
  e.e2 = edge_function(t.v0, t.v1, p);
  return e;
}

struct Thresholds {
  int64_t t0, t1, t2;
};

Thresholds thresholds_of(RasterTri t) {
  Thresholds h;
  h.t0 = edge_threshold(t.v1, t.v2);
  h.t1 = edge_threshold(t.v2, t.v0);
  h.t2 = edge_threshold(t.v0, t.v1);
  return h;
}

bool is_covered(Edges e, Thresholds h) {
  return e.e0 >= h.t0 && e.e1 >= h.t1 && e.e2 >= h.t2;
}

// Edge values `d` fixed-point units away from where `e` was taken: E is affine, so this is
// exact and equals edges_at at the moved point (d = 0 with one sample: folded away).
Edges edges_moved(RasterTri t, Edges e, ivec2 d) {
  Edges m;
  m.e0 = e.e0 + int64_t(t.v2.x - t.v1.x) * d.y - int64_t(t.v2.y - t.v1.y) * d.x;
  m.e1 = e.e1 + int64_t(t.v0.x - t.v2.x) * d.y - int64_t(t.v0.y - t.v2.y) * d.x;
  m.e2 = e.e2 + int64_t(t.v1.x - t.v0.x) * d.y - int64_t(t.v1.y - t.v0.y) * d.x;
  return m;
}

// Reverse depth near/w at a covered sample: an affine function of screen position, so the
// screen-space barycentrics (edge values over the doubled area) interpolate it exactly.
// The weights are >= 0 and the vertex depths > 0, so the result is > 0 and finite.
// `weights` are the edge values converted to float, `area` their sum converted: the edge
// functions sum to the doubled area everywhere, so a caller with many samples of one triangle
// converts it once (raster_small, which also converts 32-bit values where that is exact).
float depth_at(RasterTri t, vec3 weights, float area) {
  precise float d = weights.x * t.depth.x + weights.y * t.depth.y + weights.z * t.depth.z;
  return d / area;
}
float depth_at(RasterTri t, Edges e) {
  return depth_at(t, vec3(float(e.e0), float(e.e1), float(e.e2)), float(e.e0 + e.e1 + e.e2));
}

// 64-bit visibility key: inverted depth bits above, triangle-instance id below. Positive
// floats order like their bit patterns, so under atomicMin the nearest sample wins and equal
// depths go to the lower id, whatever order threads run in.
uint64_t visibility_key(float depth, uint id) {
  return (uint64_t(~floatBitsToUint(depth)) << 32) | uint64_t(id);
}

// Whether every edge function, taken at its maximum over the rectangle holding the tile's
// samples (`at_minimum` false) or at its minimum (true), reaches the edge's threshold. E is
// affine, so its extremes over the rectangle lie at corners.
bool tile_edges_reach(RasterTri t, ivec2 tile, bool at_minimum) {
  ivec2 lo = tile * TILE_SIZE * TS_SUBPIXEL_ONE + sample_offset_min();
  ivec2 hi = (tile * TILE_SIZE + (TILE_SIZE - 1)) * TS_SUBPIXEL_ONE + sample_offset_max();
  Thresholds h = thresholds_of(t);
  ivec2 a[3] = ivec2[3](t.v1, t.v2, t.v0);
  ivec2 b[3] = ivec2[3](t.v2, t.v0, t.v1);
  int64_t th[3] = int64_t[3](h.t0, h.t1, h.t2);
  for (int i = 0; i < 3; ++i) {
    // E(p) = dx * (p.y - a.y) - dy * (p.x - a.x): grows with p.y when dx > 0, with p.x when dy < 0.
    int dx = b[i].x - a[i].x;
    int dy = b[i].y - a[i].y;
    ivec2 p = ivec2((dy < 0) != at_minimum ? hi.x : lo.x, (dx > 0) != at_minimum ? hi.y : lo.y);
    if (edge_function(a[i], b[i], p) < th[i]) return false;
  }
  return true;
}

// Conservative test: can any sample of `tile` be covered by the triangle? Below an edge's
// threshold at the edge function's maximum over the tile, no sample of the tile is inside.
// Used identically by counting and filling.
bool tile_may_overlap(RasterTri t, ivec2 tile) {
  return tile_edges_reach(t, tile, false);
}

// Does the triangle cover every sample of `tile` (the triangle is convex, so covering the
// rectangle's corners covers every sample between them)?
bool tile_inside(RasterTri t, ivec2 tile) {
  return tile_edges_reach(t, tile, true);
}

// Hierarchical depth rejection (RendererOptions::depth_rejection) compares the high words of
// visibility keys, ~floatBitsToUint(depth): larger is farther. A triangle whose every key has a
// high word strictly above a bound on the final keys of a tile's samples cannot win any of
// them, whatever the ids (equal high words are never rejected: there the id decides).
layout(constant_id = TS_SPEC_DEPTH_REJECTION) const bool DEPTH_REJECTION = true;
// Debug coverage counts every covered sample, hidden or not, so it rasterizes everything.
const bool REJECTION = DEPTH_REJECTION && !DEBUG_COVERAGE;

// depth_at is a convex combination of the vertex depths computed in float: 3 conversions,
// 3 products, 2 sums, a conversion of the area and a division (2.5 ulp in Vulkan) put it
// within about 10 ulps of the exact value, so it lies within that of [min, max] of the vertex
// depths. The bounds below widen that range by 256 ulps (~3e-5 relative), far more than
// needed, which costs nothing measurable in what is rejected.
const uint DEPTH_BOUND_ULPS = 256u;

// A lower bound on the high word of every key the triangle can produce: that of its nearest
// vertex depth, moved nearer by the margin (saturating below infinity's bits: depth_at is
// finite).
uint nearest_key_high(vec3 depth) {
  uint bits = floatBitsToUint(max(depth.x, max(depth.y, depth.z)));
  return ~min(bits + DEPTH_BOUND_ULPS, 0x7F800000u);
}

// An upper bound on the high word of every key the triangle produces: that of its farthest
// vertex depth, moved farther by the margin (saturating at zero depth).
uint farthest_key_high(vec3 depth) {
  uint bits = floatBitsToUint(min(depth.x, min(depth.y, depth.z)));
  return ~(bits > DEPTH_BOUND_ULPS ? bits - DEPTH_BOUND_ULPS : 0u);
}

// The block of tiles of a bin entry (setup_common.glsl's bin_entry): its first tile and its size
// in tiles, each side 1 to TS_BIN_CHUNK.
void bin_entry_block(uint packed, out ivec2 first, out ivec2 size) {
  first = ivec2(packed & 0x3FFu, (packed >> 10) & 0x3FFu);
  size = ivec2((packed >> 20) & 0xFu, (packed >> 24) & 0xFu) + 1;
}

// Tile `k` of a bin entry's block of `size` tiles from `first`, row by row. The count and fill
// passes deal a block's tiles out among the entry's TS_BIN_CHUNK threads, thread j taking tiles
// j, j + TS_BIN_CHUNK, ...: each tile's atomic is a round trip to memory that the next waits
// for, and a block of w x h tiles then costs ceil(w h / 8) of them instead of w (a thread per
// row). One grid sphere at 1920x1080 binned blocks of a few tiles each.
ivec2 bin_block_tile(ivec2 first, ivec2 size, uint k) {
  return first + ivec2(int(k) % size.x, int(k) / size.x);
}

// Walks of a small triangle (entries of the per-triangle rasterizer's list): the rows of its box
// are dealt out among them, row r to walk r mod walks, so that each walk covers about
// frame.small_triangle_walk_area pixels or fewer, and one thread does not walk a box of
// hundreds of pixels alone while the rest of its SIMD group waits. A box one row high takes
// one walk whatever its width.
uint small_walks(RasterTri t) {
  uvec2 extent = uvec2(t.box_max - t.box_min) + 1u;
  // (area - 1) / walk_area + 1 rounds up without overflow (area >= 1, walk_area >= 1).
  uint walks = (extent.x * extent.y - 1u) / frame.small_triangle_walk_area + 1u;
  return min(walks, min(extent.y, TS_MAX_SMALL_WALKS));
}

// Tile range (inclusive) overlapped by the triangle's pixel box.
void tile_range(RasterTri t, out ivec2 first, out ivec2 last) {
  first = t.box_min / TILE_SIZE;
  last = t.box_max / TILE_SIZE;
}
