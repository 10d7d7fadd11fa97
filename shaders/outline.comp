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

// Per pixel of the workgroup: the triangles taken in, in the order taken (their ids, areas,
// and per edge the neighbour across it, NONE at an open edge, with that neighbour's vertex
// indices); the walk's step (taken[step_begin, step_end)) and the first of its
// 3 (step_end - step_begin) neighbours the next round tests. Arrays of words, not of structs:
// a struct with arrays in it is copied through local memory.
shared uint taken_id[PIXELS][CAP];
shared float taken_area[PIXELS][CAP];
shared uint taken_neighbour[PIXELS][3 * CAP];
shared uint taken_neighbour_vertex[PIXELS][9 * CAP];
shared uint taken_count[PIXELS];
shared uint step_begin[PIXELS];
shared uint step_end[PIXELS];
shared uint next_neighbour[PIXELS];
shared uint walk_state[PIXELS];
shared int facing_sign[PIXELS];
// Each thread's triangle of this round: its id (NONE unless it took one in).
shared uint round_id[PIXELS][LANES];

// Whether `id` is among the `count` triangles pixel p has taken in. Over the whole capacity so
// that the loads do not wait on one another.
bool is_taken(uint p, uint count, uint id) {
  uint hits = 0u;
  for (uint j = 0u; j < CAP; ++j) hits += uint(j < count && taken_id[p][j] == id);
  return hits != 0u;
}

// A triangle being measured: its neighbours across its edges (NONE at an open edge) and their
// vertices, fetched alongside its corners.
struct Neighbours {
  uvec3 id;
  uvec3 vertices0, vertices1, vertices2;
};

Neighbours fetch_neighbours(GpuObject o, uint id) {
  Neighbours n;
  uvec3 across = uvec3(0u);
  uint edges = o.first_index + 3u * (id - o.first_triangle);
  for (uint e = 0u; e < 3u; ++e) across[e] = adjacency[edges + e];
  n.id = mix(o.first_triangle + across, uvec3(NONE), equal(across, uvec3(TS_NO_NEIGHBOUR)));
  uvec3 corners = o.first_index + 3u * mix(across, uvec3(0u), equal(across, uvec3(TS_NO_NEIGHBOUR)));
  n.vertices0 = uvec3(indices[corners.x], indices[corners.x + 1u], indices[corners.x + 2u]) + o.base_vertex;
  n.vertices1 = uvec3(indices[corners.y], indices[corners.y + 1u], indices[corners.y + 2u]) + o.base_vertex;
  n.vertices2 = uvec3(indices[corners.z], indices[corners.z + 1u], indices[corners.z + 2u]) + o.base_vertex;
  return n;
}

// Stores triangle `id` (area `area`, neighbours `n`) as pixel p's taken triangle `slot`.
void store_taken(uint p, uint slot, uint id, float area, Neighbours n) {
  taken_id[p][slot] = id;
  taken_area[p][slot] = area;
  for (uint e = 0u; e < 3u; ++e) taken_neighbour[p][3u * slot + e] = n.id[e];
  uint base = 9u * slot;
  for (uint c = 0u; c < 3u; ++c) {
    taken_neighbour_vertex[p][base + c] = n.vertices0[c];
    taken_neighbour_vertex[p][base + 3u + c] = n.vertices1[c];
    taken_neighbour_vertex[p][base + 6u + c] = n.vertices2[c];
  }
}

// Pixel p's neighbour `k` of the current step (k < 3 * step size): its id (NONE at an open
// edge); `vi` its vertices.
uint step_neighbour(uint p, uint k) {
  return taken_neighbour[p][3u * step_begin[p] + k];
}
uvec3 step_neighbour_vertices(uint p, uint k) {
  uint base = 3u * (3u * step_begin[p] + k);
  return uvec3(taken_neighbour_vertex[p][base], taken_neighbour_vertex[p][base + 1u],
               taken_neighbour_vertex[p][base + 2u]);
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
      Neighbours n = fetch_neighbours(o, first);
      float area = front_face_area(slot, first, triangle_vertices(o, first), pixel, facing);
      facing_sign[p] = int(facing);
      if (area > 0.0) {
        store_taken(p, 0u, first, area, n);
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
    uint k = walking ? next_neighbour[p] + lane : NONE;
    uint step_neighbours = walking ? 3u * (step_end[p] - step_begin[p]) : 0u;
    uint took = NONE;
    float area = 0.0;
    Neighbours n;
    if (k < step_neighbours) {
      uint id = step_neighbour(p, k);
      bool test = id != NONE && !is_taken(p, count, id);
      for (uint j = 0u; j < lane; ++j) test = test && step_neighbour(p, k - lane + j) != id;
      if (test) {
        int64_t facing = int64_t(facing_sign[p]);
        n = fetch_neighbours(o, id);
        area = front_face_area(slot, id, step_neighbour_vertices(p, k), pixel, facing);
        if (area > 0.0) took = id;
      }
    }
    if (walking) round_id[p][lane] = took;
    barrier();

    // Append in thread order, after the triangles earlier threads took in; the first thread
    // moves the walk on (no other reads these before the next barrier).
    if (walking) {
      uint earlier = 0u, all = 0u;
      for (uint j = 0u; j < LANES; ++j) {
        uint one = uint(round_id[p][j] != NONE);
        earlier += j < lane ? one : 0u;
        all += one;
      }
      if (took != NONE && count + earlier < CAP) store_taken(p, count + earlier, took, area, n);
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
  for (uint j = 0u; j < count; ++j) total += taken_area[p][j];
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
