#version 460
#extension GL_GOOGLE_include_directive : require
// Silhouette coverage's second half (FrameSettings::aa_coverage silhouette, several samples per
// pixel), over the outline pixels the shading pass listed (TS_BINDING_OUTLINE): those whose
// samples see triangles of one surface and the background. For each it measures the area of
// the pixel that the surface's front faces cover, up to its silhouette, and where it finds one
// writes the pixel again: the surface's colour weighted by that area, the background by the
// rest. Each pixel is written by its own threads alone, so the list's order, which differs from
// run to run, changes no bit.
//
// The measure (the reference renderer's silhouette_coverage, core/pixel_coverage.h, is the same
// in double): from the first triangle the samples see, a breadth-first walk across the mesh's
// edges (TS_BINDING_ADJACENCY) takes in each neighbour that winds as the first does on screen
// (past a silhouette edge a neighbour faces away, or the mesh ends there) and reaches into the
// pixel, adding its area in the pixel (front_face_area): the thin slivers at the outline that
// no sample hits included. Only those taken in are walked from; a neighbour left out may be
// tested again from another. On a closed mesh the front faces do not overlap on screen, so the
// sum is the area of the surface's outline in the pixel. With a limit of S steps
// (FrameSettings::silhouette_steps, 0 for none) the walk does not go on from the triangles of
// its step S - 1 (the first triangle is step 0, its neighbours taken in step 1, ...), and the
// area found so far stands. The counts stay where a triangle the samples see is not taken in
// (two pieces of surface, or two objects, in one pixel) or where more than
// TS_SILHOUETTE_TRIANGLES would be.
//
// How it runs: TS_OUTLINE_LANES threads walk a pixel together, each round testing that many
// neighbours of the walk's current step at once; the first round tests the first triangle and
// its three neighbours. Each thread works out which of the round's neighbours an earlier
// thread of the round also reached, and appends the triangles it takes in after those of
// earlier threads: the triangles, their order and the sum are those of the one-thread walk,
// step by step and in edge order. The pass waits for its longest walks. On the H200 (default
// scene, 1920 x 1080, 4 samples, about 10,000 outline pixels, no step limit) one thread per
// pixel took 0.128 ms, 8 threads 0.081 ms (4: 0.088, 16: 0.092, 32: 0.127), and with the first
// round merged 0.075 ms; fetching each tested triangle's neighbours ahead, so that a round
// waits for one load, was slower (0.146 ms). A limit of 3 steps: 0.020 ms.
#include "bindings.glsl"
#include "material.glsl"
#include "lighting.glsl"
#include "raster_common.glsl"
#include "coverage.glsl"
#include "display.glsl"
#include "pixel_colour.glsl"

const uint LANES = TS_OUTLINE_LANES;
const uint PIXELS = TS_OUTLINE_PIXELS_PER_GROUP;
const uint CAP = TS_SILHOUETTE_TRIANGLES;
const uint NONE = 0xFFFFFFFFu;
// The first round tests the first triangle and its three neighbours (step 1) at once: at least
// 4 threads a pixel, and 2 steps (Renderer::render refuses fewer).
#if TS_OUTLINE_LANES < 4
#error "the outline pass needs at least 4 threads per pixel"
#endif
layout(constant_id = TS_SPEC_SILHOUETTE_STEPS) const uint SILHOUETTE_STEPS = 0u;

layout(local_size_x = TS_OUTLINE_PIXELS_PER_GROUP * TS_OUTLINE_LANES) in;

const uint WALKING = 0u;
const uint MEASURED = 1u;  // the walk ended: taken_area sums to the coverage
const uint COUNTS = 2u;    // the counts stay (no pixel, or a walk the measure does not cover)

// Per pixel of the workgroup: the triangles taken in, in the order taken, with their areas; the
// walk's step (taken[step_begin, step_end)) and the next of its 3 (step_end - step_begin)
// neighbours to test.
shared uint taken_id[PIXELS][CAP];
shared float taken_area[PIXELS][CAP];
shared uint taken_count[PIXELS];
shared uint step_index[PIXELS];
shared uint step_begin[PIXELS];
shared uint step_end[PIXELS];
shared uint next_neighbour[PIXELS];
shared uint walk_state[PIXELS];
shared int facing_sign[PIXELS];
// This round's triangle per thread: the neighbour it tested if it took it in, else NONE.
shared uint round_taken[PIXELS][LANES];

bool is_taken(uint p, uint id) {
  // Counted rather than short-circuited: a branch per entry made such scans a quarter of the
  // walk's time on the H200 (docs/tradeoffs.md).
  uint hits = 0u;
  for (uint j = 0u; j < taken_count[p]; ++j) hits += uint(taken_id[p][j] == id);
  return hits != 0u;
}

// The triangle of object `o` across edge `e` of its triangle instance `id` (TS_BINDING_ADJACENCY),
// or NONE at an open edge.
uint neighbour_of(GpuObject o, uint id, uint e) {
  uint across = adjacency[o.first_index + 3u * (id - o.first_triangle) + e];
  return across == TS_NO_NEIGHBOUR ? NONE : o.first_triangle + across;
}

// Pixel p's neighbour `k` of the walk's current step (k < 3 * the step's size): the triangle of
// object `o` across edge k % 3 of the step's triangle k / 3, or NONE at an open edge.
uint step_neighbour(GpuObject o, uint p, uint k) {
  return neighbour_of(o, taken_id[p][step_begin[p] + k / 3u], k % 3u);
}

// The first thread of pixel p moves its walk on after a round that took `all` triangles in
// (`count` before it): to the next step once every neighbour of this one is tested, and to
// its end once a step takes nothing in; or ends it with the counts.
void advance_walk(uint p, uint count, uint all) {
  if (count + all > CAP) {
    walk_state[p] = COUNTS;
    return;
  }
  taken_count[p] = count + all;
  next_neighbour[p] += LANES;
  if (next_neighbour[p] < 3u * (step_end[p] - step_begin[p])) return;
  step_index[p]++;
  step_begin[p] = step_end[p];
  step_end[p] = count + all;
  next_neighbour[p] = 0u;
  // The walk ends where a step takes nothing in, or at its last step, whose triangles it does
  // not walk from.
  bool last_step = SILHOUETTE_STEPS != 0u && step_index[p] + 1u >= SILHOUETTE_STEPS;
  if (step_begin[p] == step_end[p] || last_step) walk_state[p] = MEASURED;
}

// After a round (round_taken written, `count` triangles taken before it), thread `lane` of
// pixel p appends the triangle it took in (area `area`) after those of earlier threads, and the
// first thread moves the walk on (no other thread reads what it writes before the next
// barrier).
void append_round(uint p, uint lane, uint count, float area) {
  uint earlier = 0u, all = 0u;
  for (uint j = 0u; j < LANES; ++j) {
    uint took = uint(round_taken[p][j] != NONE);
    earlier += j < lane ? took : 0u;
    all += took;
  }
  if (round_taken[p][lane] != NONE && count + earlier < CAP) {
    taken_id[p][count + earlier] = round_taken[p][lane];
    taken_area[p][count + earlier] = area;
  }
  if (lane == 0u) advance_walk(p, count, all);
}

void main() {
  uint p = gl_LocalInvocationIndex / LANES;
  uint lane = gl_LocalInvocationIndex % LANES;
  uint index = gl_WorkGroupID.x * PIXELS + p;
  bool listed = index < counters[0].outline_pixels;
  GpuOutlinePixel entry = outline[listed ? index : 0u];
  ivec2 pixel = ivec2(entry.pixel & 0xFFFFu, entry.pixel >> 16);
  uint seen[SAMPLES];
  uint first = NONE;
  if (listed) {
    uint base = sample_index(pixel_index(pixel), 0u);
    for (uint s = 0u; s < SAMPLES; ++s) {
      seen[s] = uint(visibility[base + s] & 0xFFFFFFFFul);
      first = min(first, seen[s]);
    }
  }
  uint slot = listed ? find_object(first) : 0u;
  GpuObject o = objects[slot];

  // Step 0 and the tests of step 1 at once: the first thread measures the first triangle,
  // threads 1 to 3 its neighbours across edges 0 to 2, each in its own winding (facing 0),
  // kept below if it is the first's.
  uint id = NONE;
  if (listed) id = lane == 0u ? first : lane <= 3u ? neighbour_of(o, first, lane - 1u) : NONE;
  float area = 0.0;
  int64_t own_facing = 0l;
  if (id != NONE) area = front_face_area(slot, id, pixel, own_facing);
  if (lane == 0u) {
    walk_state[p] = COUNTS;
    if (listed) {
      facing_sign[p] = int(own_facing);
      if (area > 0.0) {
        taken_id[p][0] = first;
        taken_area[p][0] = area;
        taken_count[p] = 1u;
        step_index[p] = 0u;
        step_begin[p] = 0u;
        step_end[p] = 1u;
        next_neighbour[p] = 0u;
        walk_state[p] = WALKING;
      }
    }
  }
  barrier();
  bool walking = walk_state[p] == WALKING;
  if (walking) {
    bool took = lane != 0u && area > 0.0 && int(own_facing) == facing_sign[p] && id != first;
    // A neighbour reached across two edges is the earlier edge's.
    for (uint j = 1u; j < lane; ++j) took = took && neighbour_of(o, first, j - 1u) != id;
    round_taken[p][lane] = took ? id : NONE;
  }
  barrier();
  if (walking) append_round(p, lane, 1u, area);
  barrier();

  while (true) {
    // The same decision in every thread (all read the states after a barrier), so that the
    // barriers below are reached by the whole workgroup.
    bool any_walking = false;
    for (uint q = 0u; q < PIXELS; ++q) any_walking = any_walking || walk_state[q] == WALKING;
    if (!any_walking) break;

    walking = walk_state[p] == WALKING;
    uint count = walking ? taken_count[p] : 0u;
    uint k = walking ? next_neighbour[p] + lane : NONE;
    id = NONE;
    if (k < 3u * (step_end[p] - step_begin[p])) {
      id = step_neighbour(o, p, k);
      if (id != NONE && is_taken(p, id)) id = NONE;
      // A neighbour an earlier thread of this round also reached is that thread's to test: the
      // one-thread walk would test it there first, and find it taken or find the same area.
      for (uint j = 0u; j < lane; ++j) {
        if (step_neighbour(o, p, k - lane + j) == id) id = NONE;
      }
    }
    area = 0.0;
    if (id != NONE) {
      int64_t facing = int64_t(facing_sign[p]);
      area = front_face_area(slot, id, pixel, facing);
    }
    if (walking) round_taken[p][lane] = area > 0.0 ? id : NONE;
    barrier();
    if (walking) append_round(p, lane, count, area);
    barrier();
  }

  if (lane != 0u || walk_state[p] != MEASURED) return;
  // Every sample sees the background or a triangle taken in (else two pieces of surface).
  for (uint s = 0u; s < SAMPLES; ++s) {
    if (seen[s] != NONE && !is_taken(p, seen[s])) return;
  }
  float total = 0.0;
  for (uint j = 0u; j < taken_count[p]; ++j) total += taken_area[p][j];
  // Front faces may overlap where snapping folds the outline: the area is a fraction.
  float covered = clamp(total, 0.0, 1.0);
  uint empty = 0u;
  ivec2 offsets = ivec2(0);
  for (uint s = 0u; s < SAMPLES; ++s) {
    if (seen[s] == NONE) {
      empty++;
      offsets += sample_offset(s);
    }
  }
  // The background as the shading pass shaded it: seen through the mean of the empty samples.
  vec2 point = vec2(pixel) + vec2(offsets) / float(TS_SUBPIXEL_ONE * empty);
  write_pixel(pixel, entry.surface * covered + stored(background(point)) * (1.0 - covered));
}
