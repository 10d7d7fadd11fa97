// The pixel-box walk of raster_small.comp, included once per width of its edge values:
// EDGE_VEC (ivec3 or i64vec3) holds the three edge values, RASTER_BOX names the function.
// Every value is taken in int64 first (exact: edge_function's bound) and converted; the walk
// then only adds, and converts a covered sample's edge values to float for its depth (exact in
// ivec3, edges_fit_int32). SPIR-V defines OpIAdd as the low bits of the exact sum and OpSConvert to a
// narrower type as truncation, so in ivec3 every value is exact modulo 2^32, and a value that
// the caller has shown to lie in int32's range (edges_fit_int32) is the exact one. Only values
// at sample points (less a threshold) are compared or converted back; the stepped values past
// the box's last column or row, which may wrap, are never used.
// Thresholds are folded in: a sample is covered when each edge value less its threshold
// (edge_threshold: 0 or 1) is >= 0, that is when the OR of the three has its sign bit clear.

void RASTER_BOX(RasterTri t, uint near_high) {
  Thresholds h = thresholds_of(t);
  i64vec3 threshold = i64vec3(h.t0, h.t1, h.t2);
  Edges first = edges_at(t, pixel_centre(t.box_min));
  // The three edge functions sum to the doubled area at every point (barycentric weights sum
  // to one), so float(e0 + e1 + e2), which depth_at divides by, is the same for every sample.
  float area = float(first.e0 + first.e1 + first.e2);
  // One pixel right changes E_ab by -(b.y - a.y) * 256, one pixel down by (b.x - a.x) * 256.
  ivec3 dx = ivec3(t.v2.x - t.v1.x, t.v0.x - t.v2.x, t.v1.x - t.v0.x);
  ivec3 dy = ivec3(t.v2.y - t.v1.y, t.v0.y - t.v2.y, t.v1.y - t.v0.y);
  EDGE_VEC step_x = EDGE_VEC(-i64vec3(dy) * TS_SUBPIXEL_ONE);
  EDGE_VEC step_y = EDGE_VEC(i64vec3(dx) * TS_SUBPIXEL_ONE);

  // Each sample's edge values less the thresholds differ from its pixel centre's by the same
  // amounts in every pixel; `reach` is their largest on each edge, so that one test per pixel
  // tells whether any of its samples can be covered (the largest value on each edge is that
  // of some sample: a sample point's value less its threshold, in range like the others).
  EDGE_VEC to_sample[SAMPLES];
  i64vec3 reach;
  for (uint s = 0u; s < SAMPLES; ++s) {
    Edges d = edges_moved(t, Edges(0l, 0l, 0l), sample_offset(s) - TS_SUBPIXEL_ONE / 2);
    i64vec3 moved = i64vec3(d.e0, d.e1, d.e2) - threshold;
    to_sample[s] = EDGE_VEC(moved);
    reach = s == 0u ? moved : max(reach, moved);
  }
  EDGE_VEC pixel_reach = EDGE_VEC(reach);

  EDGE_VEC row = EDGE_VEC(i64vec3(first.e0, first.e1, first.e2));
  for (int y = t.box_min.y; y <= t.box_max.y; ++y) {
    EDGE_VEC e = row;
    bool entered = false;
    for (int x = t.box_min.x; x <= t.box_max.x; ++x, e += step_x) {
      EDGE_VEC m = e + pixel_reach;
      // Each of m's components is affine in x, so the pixels of a row that pass are one run:
      // after it, the rest of the row cannot pass either.
      if ((m.x | m.y | m.z) < 0) {
        if (entered) break;
        continue;
      }
      entered = true;
      uint covered = SAMPLES == 1u ? 1u : 0u;  // with one sample, m is the sample's value
      for (uint s = 0u; s < SAMPLES && SAMPLES > 1u; ++s) {
        EDGE_VEC es = e + to_sample[s];
        if ((es.x | es.y | es.z) >= 0) covered |= 1u << s;
      }
      if (covered == 0u) continue;
      uint p = pixel_index(ivec2(x, y));
      uint64_t keys[SAMPLES];
      load_pixel_keys(p, keys);
      for (uint s = 0u; s < SAMPLES; ++s) {
        if ((covered & (1u << s)) == 0u) continue;
        if (DEBUG_COVERAGE) atomicAdd(coverage[p], 1u);
        // A plain read first skips most atomics; a stale value is never below the true one.
        if (REJECTION && uint(keys[s] >> 32) < near_high) continue;  // the key would be above
        EDGE_VEC exact = (SAMPLES == 1u ? m : e + to_sample[s]) + EDGE_VEC(threshold);
        uint64_t key = visibility_key(depth_at(t, vec3(exact), area), t.id);
        if (keys[s] > key) atomicMin(visibility[sample_index(p, s)], key);
      }
    }
    row += step_y;
  }
}
