// Triangle setup shared by the setup and clip passes: clip planes, snapping, culling of what
// covers no pixel, and appending a raster triangle (small list, or counted into its tiles).

// Clip-space position of vertex k of triangle instance `id`.
void triangle_clip_coords(uint id, out vec4 c[3]) {
  GpuObject o = objects[find_object(id)];
  uvec3 vi = triangle_vertices(o, id);
  mat4 to_clip = frame.view_proj * o.model;
  for (int k = 0; k < 3; ++k) c[k] = to_clip * vec4(vertices[vi[k]].position_u.xyz, 1.0);
}

// Signed distance to clip plane `plane` (inside >= 0): the near plane, then the guard band.
float plane_distance(vec4 c, int plane) {
  float gx = frame.raster_params.x;
  float gy = frame.raster_params.y;
  switch (plane) {
    case 0: return c.w - frame.camera_position.w;
    case 1: return gx * c.w - c.x;
    case 2: return gx * c.w + c.x;
    case 3: return gy * c.w - c.y;
    default: return gy * c.w + c.y;
  }
}

void emit(vec4 c0, vec4 c1, vec4 c2, uint id) {
  vec2 size = vec2(frame.image_size.xy);
  float near_plane = frame.camera_position.w;
  vec4 c[3] = vec4[3](c0, c1, c2);
  ivec2 v[3];
  float d[3];
  for (int k = 0; k < 3; ++k) {
    vec2 screen = (c[k].xy / c[k].w * 0.5 + 0.5) * size;
    v[k] = ivec2(floor(screen * float(TS_SUBPIXEL_ONE) + 0.5));
    d[k] = near_plane / c[k].w;
  }
  int64_t area = edge_function(v[0], v[1], v[2]);
  if (area == 0) {
    atomicAdd(counters[batch.index].culled_empty, 1u);
    return;
  }
  // Front faces wind counter-clockwise in world space; the y-down screen mirrors them, so
  // their doubled area comes out negative here.
  bool front = area < 0;
  if ((front && frame.flags.x == TS_CULL_FRONT) || (!front && frame.flags.x == TS_CULL_BACK)) {
    atomicAdd(counters[batch.index].culled_backface, 1u);
    return;
  }
  // Order the vertices so the area is positive: every edge function is then >= 0 inside.
  int second = front ? 2 : 1;
  int third = front ? 1 : 2;
  RasterTri t;
  t.v0 = v[0];
  t.v1 = v[second];
  t.v2 = v[third];
  t.depth = vec3(d[0], d[second], d[third]);
  t.id = id;

  ivec2 lo = min(min(t.v0, t.v1), t.v2);
  ivec2 hi = max(max(t.v0, t.v1), t.v2);
  // Pixel x has its centre at x*256 + 128: the first centre >= lo and the last <= hi.
  ivec2 box_min = max((lo - TS_SUBPIXEL_ONE / 2 + (TS_SUBPIXEL_ONE - 1)) >> TS_SUBPIXEL_BITS, ivec2(0));
  ivec2 box_max = min((hi - TS_SUBPIXEL_ONE / 2) >> TS_SUBPIXEL_BITS, ivec2(frame.image_size.xy) - 1);
  if (any(greaterThan(box_min, box_max))) {
    atomicAdd(counters[batch.index].culled_empty, 1u);
    return;
  }
  t.box_min = box_min;
  t.box_max = box_max;
  // Slivers and sub-pixel triangles often cover no pixel centre: for boxes of up to 2x2
  // pixels, test the centres here rather than pay for a raster triangle that writes nothing.
  if (all(lessThanEqual(box_max - box_min, ivec2(1)))) {
    Thresholds h = thresholds_of(t);
    bool any_covered = false;
    for (int y = box_min.y; y <= box_max.y; ++y) {
      for (int x = box_min.x; x <= box_max.x; ++x) {
        any_covered = any_covered || is_covered(edges_at(t, pixel_centre(ivec2(x, y))), h);
      }
    }
    if (!any_covered) {
      atomicAdd(counters[batch.index].culled_empty, 1u);
      return;
    }
  }

  uint index = atomicAdd(counters[batch.index].raster_tris, 1u);
  if (index >= frame.limits.x) return;  // overflow: the host sees the count, grows, redoes
  raster_tris[index].xy01 = uvec4(ivec4(t.v0, t.v1));
  raster_tris[index].xy2_box =
      uvec4(uvec2(t.v2), uint(box_min.x) | (uint(box_min.y) << 16), uint(box_max.x) | (uint(box_max.y) << 16));
  raster_tris[index].depth_id = uvec4(floatBitsToUint(t.depth), id);

  uvec2 extent = uvec2(box_max - box_min) + 1u;
  if (extent.x * extent.y <= frame.limits.z) {
    small_list[atomicAdd(counters[batch.index].small_tris, 1u)] = index;
    return;
  }
  big_list[atomicAdd(counters[batch.index].big_tris, 1u)] = index;
  ivec2 first, last;
  tile_range(t, first, last);
  for (int ty = first.y; ty <= last.y; ++ty) {
    for (int tx = first.x; tx <= last.x; ++tx) {
      if (tile_may_overlap(t, ivec2(tx, ty))) {
        atomicAdd(tile_counts[uint(ty) * frame.image_size.z + uint(tx)], 1u);
      }
    }
  }
}

