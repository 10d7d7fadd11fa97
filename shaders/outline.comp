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
// sum is the area of the surface's outline in the pixel. The counts stay where a triangle the
// samples see is not taken in (two pieces of surface, or two objects, in one pixel) or where
// more than TS_SILHOUETTE_TRIANGLES would be.
//
// How it runs: the pass waits for its longest walk, and a walk is a chain of rounds, each of
// dependent loads (a triangle's neighbour across an edge, the neighbour's indices, its
// corners) and then the area. So TS_OUTLINE_LANES threads walk a pixel together, each round
// testing that many neighbours of the walk's current step at once; and the thread that tests
// a triangle also fetches its neighbours and their vertex indices, which the next step needs,
// alongside its corners, so that a round waits for one load (the corners), not three. Each
// thread works out which of the round's neighbours an earlier thread of the round also
// reached, and appends the triangles it takes in after those earlier threads': the triangles,
// their order and the sum are those of the one-thread walk, step by step and in edge order.
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

// A triangle as the walk needs it: its id, its area in the pixel, and per edge the neighbour
// across it (NONE at an open edge) with that neighbour's vertices.
struct WalkTriangle {
  uint id;
  float area;
  uint neighbour[3];
  uvec3 neighbour_vertices[3];
};

// Per pixel of the workgroup: the triangles taken in, in the order taken; the walk's step
// (taken[step_begin, step_end)) and the first of its 3 (step_end - step_begin) neighbours
// the next round tests.
shared WalkTriangle taken[PIXELS][CAP];
shared uint taken_count[PIXELS];
shared uint step_begin[PIXELS];
shared uint step_end[PIXELS];
shared uint next_neighbour[PIXELS];
shared uint walk_state[PIXELS];
shared int facing_sign[PIXELS];
// Each thread's triangle of this round (id NONE unless it took one in).
shared WalkTriangle round_result[PIXELS][LANES];

// Whether `id` is among the `count` triangles pixel p has taken in. Over the whole capacity so
// that the loads do not wait on one another.
bool is_taken(uint p, uint count, uint id) {
  uint hits = 0u;
  for (uint j = 0u; j < CAP; ++j) hits += uint(j < count && taken[p][j].id == id);
  return hits != 0u;
}

// Triangle `id` of object `o` (slot `slot`) with vertices `vi`, measured in `pixel`; its
// neighbours and their vertices are fetched alongside its corners.
WalkTriangle measure(GpuObject o, uint slot, uint id, uvec3 vi, ivec2 pixel, inout int64_t facing) {
  WalkTriangle t;
  t.id = id;
  uint edges = o.first_index + 3u * (id - o.first_triangle);
  for (uint e = 0u; e < 3u; ++e) {
    uint across = adjacency[edges + e];
    t.neighbour[e] = across == TS_NO_NEIGHBOUR ? NONE : o.first_triangle + across;
    uint corners = o.first_index + 3u * (across == TS_NO_NEIGHBOUR ? 0u : across);
    t.neighbour_vertices[e] = uvec3(indices[corners], indices[corners + 1u], indices[corners + 2u]) + o.base_vertex;
  }
  t.area = front_face_area(slot, id, vi, pixel, facing);
  return t;
}

// Pixel p's neighbour `k` of the current step (k < 3 * step size): its id (NONE at an open
// edge) and vertices.
uint step_neighbour(uint p, uint k, out uvec3 vi) {
  uint from = step_begin[p] + k / 3u;
  vi = taken[p][from].neighbour_vertices[k % 3u];
  return taken[p][from].neighbour[k % 3u];
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
      WalkTriangle t = measure(o, slot, first, triangle_vertices(o, first), pixel, facing);
      facing_sign[p] = int(facing);
      if (t.area > 0.0) {
        taken[p][0] = t;
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
    // The same decision in every thread (all read the states after a barrier), so that the
    // barriers below are reached by the whole workgroup.
    bool any_walking = false;
    for (uint q = 0u; q < PIXELS; ++q) any_walking = any_walking || walk_state[q] == WALKING;
    if (!any_walking) break;

    // Test this thread's neighbour, unless it is taken already or an earlier thread of the
    // round reached it too (that thread tests it first, as the one-thread walk would).
    bool walking = walk_state[p] == WALKING;
    uint count = walking ? taken_count[p] : 0u;
    WalkTriangle result;
    result.id = NONE;
    uint k = walking ? next_neighbour[p] + lane : NONE;
    uint step_neighbours = walking ? 3u * (step_end[p] - step_begin[p]) : 0u;
    if (k < step_neighbours) {
      uvec3 vi;
      uint id = step_neighbour(p, k, vi);
      bool test = id != NONE && !is_taken(p, count, id);
      for (uint j = 0u; j < lane; ++j) {
        uvec3 unused;
        if (step_neighbour(p, k - lane + j, unused) == id) test = false;
      }
      if (test) {
        int64_t facing = int64_t(facing_sign[p]);
        WalkTriangle t = measure(o, slot, id, vi, pixel, facing);
        if (t.area > 0.0) result = t;
      }
    }
    if (walking) round_result[p][lane] = result;
    barrier();

    // Append in thread order, after the triangles earlier threads took in; the first thread
    // moves the walk on (no other reads these before the next barrier).
    if (walking) {
      uint earlier = 0u, all = 0u;
      for (uint j = 0u; j < LANES; ++j) {
        uint took = uint(round_result[p][j].id != NONE);
        earlier += j < lane ? took : 0u;
        all += took;
      }
      if (result.id != NONE && count + earlier < CAP) taken[p][count + earlier] = result;
      if (lane == 0u) {
        if (count + all > CAP) {
          walk_state[p] = COUNTS;
        } else {
          taken_count[p] = count + all;
          next_neighbour[p] += LANES;
          if (next_neighbour[p] >= step_neighbours) {
            step_begin[p] = step_end[p];
            step_end[p] = count + all;
            next_neighbour[p] = 0u;
            if (step_begin[p] == step_end[p]) walk_state[p] = MEASURED;
          }
        }
      }
    }
    barrier();
  }

  if (lane != 0u || walk_state[p] != MEASURED) return;
  uint count = taken_count[p];
  // Every sample sees the background or a triangle taken in (else two pieces of surface).
  for (uint s = 0u; s < SAMPLES; ++s) {
    if (seen[s] != NONE && !is_taken(p, count, seen[s])) return;
  }
  float total = 0.0;
  for (uint j = 0u; j < count; ++j) total += taken[p][j].area;
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
