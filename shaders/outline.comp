#version 460
#extension GL_GOOGLE_include_directive : require
// Silhouette coverage's second half (FrameSettings::aa_coverage silhouette, several samples per
// pixel), over the outline pixels the shading pass listed (TS_BINDING_OUTLINE): those whose
// samples see triangles of one surface and the background. For each it measures the area of
// the pixel that the surface's front faces cover and, where it finds one, writes the pixel
// again: the surface's colour weighted by that area, the background by the rest. Where it finds
// none (two surfaces in the pixel, or a walk over TS_SILHOUETTE_TRIANGLES), the shading pass's
// counts stay. Each pixel is written by its own threads alone, so the list's order, which
// differs from run to run, changes no bit.
//
// The measure is silhouette_coverage's (coverage.glsl; its comment has the method): a
// breadth-first walk across the mesh's edges from the first triangle the samples see, taking
// in each neighbour that winds as it does and reaches into the pixel, summing their areas.
// Here TS_OUTLINE_LANES threads walk a pixel together: each round they test that many
// neighbours of the walk's current step at once, and the first thread appends those taken in,
// in the order the one-thread walk would, so the triangles, their order and the sum are the
// one-thread walk's. A walk is a chain of dependent loads (a triangle's neighbour, its
// indices, its corners) per neighbour tested, and the pass waits for its longest: one thread
// per pixel took 0.128 ms on the H200 for the default scene's 10,000 outline pixels.
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
shared uint step_begin[PIXELS];
shared uint step_end[PIXELS];
shared uint next_neighbour[PIXELS];
shared uint walk_state[PIXELS];
shared int facing_sign[PIXELS];
// This round's neighbour per thread (NONE if it has none to test), then the same if the thread
// took it in (else NONE), with its area.
shared uint round_id[PIXELS][LANES];
shared uint round_taken[PIXELS][LANES];
shared float round_area[PIXELS][LANES];

bool is_taken(uint p, uint id) {
  uint hits = 0u;  // counted rather than short-circuited, as in silhouette_coverage
  for (uint j = 0u; j < taken_count[p]; ++j) hits += uint(taken_id[p][j] == id);
  return hits != 0u;
}

// The first thread of pixel p appends this round's triangles taken in, in thread order, and
// moves the walk on: to its next step once every neighbour of this one is tested, and to its end
// once a step takes nothing in.
void append_round(uint p) {
  for (uint lane = 0u; lane < LANES; ++lane) {
    uint id = round_taken[p][lane];
    if (id == NONE) continue;
    if (taken_count[p] == CAP) {
      walk_state[p] = COUNTS;
      return;
    }
    taken_id[p][taken_count[p]] = id;
    taken_area[p][taken_count[p]] = round_area[p][lane];
    taken_count[p]++;
  }
  next_neighbour[p] += LANES;
  if (next_neighbour[p] < 3u * (step_end[p] - step_begin[p])) return;
  step_begin[p] = step_end[p];
  step_end[p] = taken_count[p];
  next_neighbour[p] = 0u;
  if (step_begin[p] == step_end[p]) walk_state[p] = MEASURED;
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

  if (lane == 0u) {
    walk_state[p] = COUNTS;
    if (listed) {
      int64_t facing = 0l;
      float area = front_face_area(slot, first, pixel, facing);
      facing_sign[p] = int(facing);
      if (area > 0.0) {
        taken_id[p][0] = first;
        taken_area[p][0] = area;
        taken_count[p] = 1u;
        step_begin[p] = 0u;
        step_end[p] = 1u;
        next_neighbour[p] = 0u;
        walk_state[p] = WALKING;
      }
    }
  }
  barrier();

  while (true) {
    // The same decision in every thread (all read the states after the barrier), so that the
    // barriers below are reached by the whole workgroup.
    bool any_walking = false;
    for (uint q = 0u; q < PIXELS; ++q) any_walking = any_walking || walk_state[q] == WALKING;
    if (!any_walking) break;

    bool walking = walk_state[p] == WALKING;
    uint id = NONE;
    if (walking) {
      uint k = next_neighbour[p] + lane;
      if (k < 3u * (step_end[p] - step_begin[p])) {
        uint from = taken_id[p][step_begin[p] + k / 3u];
        uint across = adjacency[o.first_index + 3u * (from - o.first_triangle) + k % 3u];
        if (across != TS_NO_NEIGHBOUR) id = o.first_triangle + across;
        if (id != NONE && is_taken(p, id)) id = NONE;
      }
      round_id[p][lane] = id;
    }
    barrier();

    if (walking && id != NONE) {
      // A neighbour an earlier thread of this round also reached is that thread's to test: the
      // one-thread walk would test it there first, and find it taken or find the same area.
      for (uint j = 0u; j < lane; ++j) {
        if (round_id[p][j] == id) id = NONE;
      }
    }
    float area = 0.0;
    if (walking && id != NONE) {
      int64_t facing = int64_t(facing_sign[p]);
      area = front_face_area(slot, id, pixel, facing);
    }
    if (walking) {
      round_taken[p][lane] = area > 0.0 ? id : NONE;
      round_area[p][lane] = area;
    }
    barrier();

    if (walking && lane == 0u) append_round(p);
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
