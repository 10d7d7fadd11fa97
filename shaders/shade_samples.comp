#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// Shading at several samples per pixel (SAMPLES > 1; one sample: shade.comp, which says why the
// two are modules of their own). Each distinct triangle among a pixel's samples, and the
// background if a sample is empty, is shaded once (resolve_samples) with the one-sample path's
// functions (shade_pixel.glsl), and the pixel takes their weighted sum.
#include "bindings.glsl"
#include "material.glsl"
#include "lighting.glsl"
#include "raster_common.glsl"
#include "coverage.glsl"
#include "display.glsl"
#include "pixel_colour.glsl"
#include "shade_tiles.glsl"
#include "shade_pixel.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// How anti-aliasing weighs a pixel's triangles (TS_AA_COVERAGE_*): a specialization constant,
// so that the count's pipelines carry none of the analytic code.
layout(constant_id = TS_SPEC_AA_COVERAGE) const uint AA_COVERAGE = TS_AA_COVERAGE_COUNT;
// SHADE_TILES (raster_common.glsl): TS_SHADE_TILES_OFF dispatches a workgroup per 8x8 pixels of
// the image; TS_SHADE_TILES_DRAWN one per 8x8 pixels of each tile list_tiles found drawn into
// (shade_background.comp takes the others).

// Anti-aliased pixels (SAMPLES > 1): each distinct triangle among a pixel's samples, and the
// background if a sample is empty, is shaded once, at the pixel centre if it holds every
// sample and else at the mean of its samples (inside the triangle, which is convex). Its weight
// is the fraction of samples it holds, except under analytic coverage (TS_AA_COVERAGE_ANALYTIC)
// in a pixel whose samples see one triangle and the background, where the triangle takes its
// outline coverage (outline_coverage) if it has an outline edge, the background the rest.
// Under silhouette coverage (TS_AA_COVERAGE_SILHOUETTE) a pixel whose samples see one surface
// and the background is written with the counts and listed for the outline pass
// (outline.comp), which writes it again with the surface's exact area where it finds one: the
// walk across the mesh that measures it runs there, over a compact list, rather than here,
// where its registers cost every pixel and a SIMD group waits for its one walking thread.
// The pixels of the workgroup first list these shading requests in shared memory, then all
// threads shade the list together, a request per thread in turn, so that a pixel with four
// triangles does not keep the others of its SIMD group waiting for four shading evaluations
// while most have one; each pixel then sums its own requests' colours in increasing id, the
// empty id (all ones) last, so the sum is the same whatever order the samples were written or
// the requests listed in.
const uint GROUP_PIXELS = 64u;  // local_size_x * local_size_y
const uint MAX_REQUESTS = GROUP_PIXELS * SAMPLES;
// A request: (id, point.x, point.y) as written by its pixel, then its stored colour (as bits)
// written over it by the thread that shades it. Three arrays of words rather than one of uvec3,
// which an implementation may pad to 16 bytes: 12 KiB at 16 samples.
shared uint request_words[3][MAX_REQUESTS];
// Per request: NEEDS_COVERAGE | the pixel's empty samples (a bit each) where its pixel takes
// the outline coverage of the request's triangle (analytic coverage), else 0; the thread that
// shades it writes the coverage (float bits) over it.
shared uint request_coverage[MAX_REQUESTS];
const uint NEEDS_COVERAGE = 0x80000000u;  // above the sample bits (SAMPLES <= 16)

void put_request(uint slot, uvec3 words) {
  for (uint k = 0u; k < 3u; ++k) request_words[k][slot] = words[k];
}
uvec3 get_request(uint slot) {
  return uvec3(request_words[0][slot], request_words[1][slot], request_words[2][slot]);
}
shared uint request_count;

// A new slot in the request list. The threads that take one together share one atomic on
// request_count: each their own would all hit one shared-memory address, one after another.
// The slots' order differs from run to run, which nothing reads (see above).
uint request_slot() {
  uvec4 takers = subgroupBallot(true);
  uint base = 0u;
  if (subgroupElect()) base = atomicAdd(request_count, subgroupBallotBitCount(takers));
  return subgroupBroadcastFirst(base) + subgroupBallotExclusiveBitCount(takers);
}

// Lists `pixel` for the outline pass (silhouette coverage) with its surface's stored colour.
// The threads that list together share one atomic; the list's order differs from run to run,
// and nothing reads it (each entry is one pixel's, written by the outline pass alone).
void list_outline_pixel(ivec2 pixel, vec3 surface) {
  uvec4 takers = subgroupBallot(true);
  uint count = subgroupBallotBitCount(takers);
  uint base = 0u;
  if (subgroupElect()) {
    base = atomicAdd(counters[0].outline_pixels, count);
    // The outline pass's workgroups, raised a grain of 8 at a time as these entries reach into
    // a new grain's worth: 8 times fewer atomics on a second contended address than one per
    // workgroup, for at most 7 workgroups that find no pixel.
    const uint grain = 8u * TS_OUTLINE_PIXELS_PER_GROUP;
    uint grains = (base + count + grain - 1u) / grain - (base + grain - 1u) / grain;
    if (grains != 0u) atomicAdd(counters[0].outline_dispatch.x, 8u * grains);
  }
  uint slot = subgroupBroadcastFirst(base) + subgroupBallotExclusiveBitCount(takers);
  outline[slot] = GpuOutlinePixel(surface, uint(pixel.x) | (uint(pixel.y) << 16));
}

void resolve_samples(ivec2 pixel, bool inside) {
  uint thread = gl_LocalInvocationIndex;
  if (thread == 0u) request_count = 0u;
  if (AA_COVERAGE == TS_AA_COVERAGE_SILHOUETTE && all(equal(pixel, ivec2(0)))) {
    // The outline pass's dispatch: y and z one (the counters start the frame at zero). Under
    // shading by tiles the background's dispatch may have pixel (0, 0): list_tiles sets them.
    counters[0].outline_dispatch.y = 1u;
    counters[0].outline_dispatch.z = 1u;
  }
  barrier();

  uint slots[SAMPLES];
  float weights[SAMPLES];
  uint groups = 0u;
  uint empty_mask = 0u;
  if (inside) {
    uint base = sample_index(pixel_index(pixel), 0u);
    uint ids[SAMPLES];
    for (uint s = 0u; s < SAMPLES; ++s) ids[s] = uint(visibility[base + s] & 0xFFFFFFFFul);
    // An empty key is all ones, so its id is too, and no drawn key's id is (the last id is
    // never used): the drawn samples are emptied for the next frame. No pass of this frame
    // reads a key after this one (the outline pass does: then the host does not ask).
    if (frame.reset_visibility != 0u) {
      for (uint s = 0u; s < SAMPLES; ++s) {
        if (ids[s] != 0xFFFFFFFFu) visibility[base + s] = TS_VIS_EMPTY;
      }
    }
    uint next = 0u;  // every id below this has been listed
    uint listed = 0u;  // samples in the groups listed
    for (uint group = 0u; group < SAMPLES; ++group) {
      uint id = 0xFFFFFFFFu;
      for (uint s = 0u; s < SAMPLES; ++s) {
        if (ids[s] >= next) id = min(id, ids[s]);
      }
      uint count = 0u;
      ivec2 offsets = ivec2(0);
      for (uint s = 0u; s < SAMPLES; ++s) {
        if (ids[s] == id) {
          count++;
          offsets += sample_offset(s);
          if (id == 0xFFFFFFFFu) empty_mask |= 1u << s;
        }
      }
      if (count == 0u) break;
      vec2 point = count == SAMPLES ? vec2(pixel) + 0.5
                                    : vec2(pixel) + vec2(offsets) / float(TS_SUBPIXEL_ONE * count);
      uint slot = request_slot();
      put_request(slot, uvec3(id, floatBitsToUint(point)));
      slots[groups] = slot;
      weights[groups] = float(count) / float(SAMPLES);
      groups++;
      listed += count;
      // Every sample is in a group: a search for the next id would find none (the empty id,
      // all ones, is always the last group).
      if (listed == SAMPLES) break;
      next = id + 1u;
    }
    // One triangle and the background (listed last): the triangle's outline coverage is wanted.
    bool analytic = AA_COVERAGE == TS_AA_COVERAGE_ANALYTIC && empty_mask != 0u && groups == 2u;
    for (uint g = 0u; g < groups && AA_COVERAGE == TS_AA_COVERAGE_ANALYTIC; ++g) {
      request_coverage[slots[g]] = analytic && g == 0u ? NEEDS_COVERAGE | empty_mask : 0u;
    }
  }
  barrier();

  uint total = request_count;
  for (uint r = thread; r < total; r += GROUP_PIXELS) {
    uvec3 q = get_request(r);
    vec2 point = uintBitsToFloat(q.yz);
    bool empty = q.x == 0xFFFFFFFFu;
    vec3 color = empty ? background(point) : shade_triangle(q.x, point);
    put_request(r, floatBitsToUint(stored(color)));
    // The request's point lies inside its pixel (the mean of some of its samples). Tested on
    // the constant first, so that the other pipelines fold the clipping code away.
    uint wanted = AA_COVERAGE == TS_AA_COVERAGE_ANALYTIC ? request_coverage[r] : 0u;
    if (AA_COVERAGE == TS_AA_COVERAGE_ANALYTIC && wanted != 0u && !empty) {
      float covered = outline_coverage(q.x, ivec2(floor(point)), wanted & ~NEEDS_COVERAGE);
      request_coverage[r] = floatBitsToUint(covered);
    }
  }
  barrier();

  if (!inside) return;
  if (AA_COVERAGE == TS_AA_COVERAGE_ANALYTIC && empty_mask != 0u && groups == 2u) {
    // Without an outline edge (-1) or area (0), the counts stay.
    float covered = uintBitsToFloat(request_coverage[slots[0]]);
    if (covered > 0.0) {
      weights[0] = covered;
      weights[groups - 1u] = 1.0 - covered;  // the background's (index 1, written so that the
                                             // 1-sample compile sees no constant index past 0)
    }
  }
  vec3 sum = vec3(0.0);
  for (uint g = 0u; g < groups; ++g) sum += uintBitsToFloat(get_request(slots[g])) * weights[g];
  write_pixel(pixel, sum);
  if (AA_COVERAGE == TS_AA_COVERAGE_SILHOUETTE && empty_mask != 0u && groups >= 2u) {
    // Samples of one surface, or of several, and the background (listed last): the outline
    // pass decides, with the surface's colour (its groups weighted as their samples are).
    float seen = float(SAMPLES - uint(bitCount(empty_mask)));
    vec3 surface = vec3(0.0);
    for (uint g = 0u; g + 1u < groups; ++g) {
      surface += uintBitsToFloat(get_request(slots[g])) * (weights[g] * float(SAMPLES) / seen);
    }
    list_outline_pixel(pixel, surface);
  }
}

void main() {
  ivec2 origin;
  // The same for the whole workgroup, so that its barriers (resolve_samples) see every thread.
  if (!block_origin(origin)) return;
  reset_tile_bound(origin);
  ivec2 pixel = origin + ivec2(gl_LocalInvocationID.xy);
  // Every thread of the workgroup takes part, inside the image or not: the requests are shaded
  // together.
  resolve_samples(pixel, all(lessThan(pixel, ivec2(frame.image_size))));
}
