// The shading of one triangle seen through a point of a pixel, and of a pixel of one sample:
// shared by the shading pass (shade.comp) and the pass that rasterizes and shades small frames
// in one (raster_shade.comp), so that both give the same bits. Needs bindings.glsl,
// material.glsl, lighting.glsl, raster_common.glsl, display.glsl and pixel_colour.glsl.

// Unclamped barycentrics of the ray's hit on the triangle's plane, for texture footprints;
// false if the ray is parallel to the plane.
bool plane_barycentrics(vec3 origin, vec3 dir, vec3 p0, vec3 p1, vec3 p2, out vec3 b) {
  vec3 e1 = p1 - p0;
  vec3 e2 = p2 - p0;
  vec3 pv = cross(dir, e2);
  float inv_det = 1.0 / dot(e1, pv);
  b = vec3(0.0);
  if (isinf(inv_det) || isnan(inv_det)) return false;
  vec3 tv = origin - p0;
  float u = dot(tv, pv) * inv_det;
  float v = dot(dir, cross(tv, e1)) * inv_det;
  b = vec3(1.0 - u - v, u, v);
  return true;
}

// Barycentrics of the ray's hit on the triangle's plane (Moeller & Trumbore 1997).
vec3 ray_barycentrics(vec3 origin, vec3 dir, vec3 p0, vec3 p1, vec3 p2) {
  vec3 e1 = p1 - p0;
  vec3 e2 = p2 - p0;
  vec3 pv = cross(dir, e2);
  float inv_det = 1.0 / dot(e1, pv);
  // The determinant vanishes only for a triangle seen exactly edge-on, which covered the
  // sample through snapping alone: its centroid is as good an answer as any.
  if (isinf(inv_det) || isnan(inv_det)) return vec3(1.0 / 3.0);
  vec3 tv = origin - p0;
  float u = dot(tv, pv) * inv_det;
  float v = dot(dir, cross(tv, e1)) * inv_det;
  // Snapping moves edges by up to 1/512 px, so a covered sample can land just outside the
  // exact triangle: clamp instead of extrapolating.
  vec3 b = max(vec3(1.0 - u - v, u, v), vec3(0.0));
  return b / (b.x + b.y + b.z);
}

// A well-spread colour for an integer (PCG hash, O'Neill 2014), for the id debug views.
vec3 id_colour(uint id) {
  uint h = id * 747796405u + 2891336453u;
  h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
  h = (h >> 22u) ^ h;
  return vec3(h & 0xFFu, (h >> 8) & 0xFFu, (h >> 16) & 0xFFu) / 255.0;
}

// Shaded colour of triangle-instance `id` seen along the ray through `point` (in pixels: the
// pixel centre, or the mean of the triangle's samples in a partly covered pixel).
vec3 shade_triangle(uint id, vec2 point) {
  uint slot = find_object(id);
  GpuObject o = objects[slot];
  uvec3 vi = triangle_vertices(o, id);
  vec3 p[3];
  vec3 n[3];
  vec2 t[3];
  vec3 tan[3];
  for (int k = 0; k < 3; ++k) {
    GpuVertex vert = vertices[vi[k]];
    p[k] = (o.model * vec4(vert.position_u.xyz, 1.0)).xyz;
    n[k] = mat3(o.normal_matrix) * vert.normal_v.xyz;
    t[k] = vec2(vert.position_u.w, vert.normal_v.w);
    tan[k] = mat3(o.model) * vert.tangent.xyz;
  }
  vec3 origin = frame.camera_position;
  vec3 dir = camera_ray_at(point);
  vec3 b = ray_barycentrics(origin, dir, p[0], p[1], p[2]);
  vec3 P = b.x * p[0] + b.y * p[1] + b.z * p[2];
  vec3 N = b.x * n[0] + b.y * n[1] + b.z * n[2];
  float n2 = dot(N, N);
  // Opposite vertex normals can cancel; the face normal is then the only sensible choice.
  N = n2 > 1e-20 ? N * inversesqrt(n2) : normalize(cross(p[1] - p[0], p[2] - p[0]));
  SurfaceGeometry g;
  g.P = P;
  g.N = N;
  g.uv = b.x * t[0] + b.y * t[1] + b.z * t[2];
  // Texture footprint by ray differentials (Igehy 1999): where the rays of the next pixel to the
  // right and below meet the triangle's plane. Compute shaders have no implicit derivatives.
  vec3 bx, by;
  const float INF = uintBitsToFloat(0x7F800000u);
  bool has_dx = plane_barycentrics(origin, camera_ray_at(point + vec2(1.0, 0.0)), p[0], p[1], p[2], bx);
  bool has_dy = plane_barycentrics(origin, camera_ray_at(point + vec2(0.0, 1.0)), p[0], p[1], p[2], by);
  g.duv_dx = has_dx ? bx.x * t[0] + bx.y * t[1] + bx.z * t[2] - g.uv : vec2(INF);
  g.duv_dy = has_dy ? by.x * t[0] + by.y * t[1] + by.z * t[2] - g.uv : vec2(INF);
  // Uv set 1 the same way, only where the material reads it (else uv1s may hold nothing).
  g.uv1 = g.uv;
  g.duv1_dx = g.duv_dx;
  g.duv1_dy = g.duv_dy;
  if (UV1_MAPS != 0u && materials[o.material].uv1_maps != 0u) {
    vec2 s[3] = vec2[3](uv1s[vi[0]], uv1s[vi[1]], uv1s[vi[2]]);
    g.uv1 = b.x * s[0] + b.y * s[1] + b.z * s[2];
    g.duv1_dx = has_dx ? bx.x * s[0] + bx.y * s[1] + bx.z * s[2] - g.uv1 : vec2(INF);
    g.duv1_dy = has_dy ? by.x * s[0] + by.y * s[1] + by.z * s[2] - g.uv1 : vec2(INF);
  }
  // A mirroring transform flips the handedness of the tangent frame.
  float handedness = vertices[vi[0]].tangent.w * (o.mirrored != 0u ? -1.0 : 1.0);
  g.T = vec4(b.x * tan[0] + b.y * tan[1] + b.z * tan[2], handedness);
  // Front faces wind counter-clockwise seen from the camera, clockwise if mirrored (as setup
  // decides facing).
  bool back = (dot(cross(p[1] - p[0], p[2] - p[0]), dir) > 0.0) != (o.mirrored != 0u);
  g = face_viewer(o.material, g, back);
  MaterialSample ms = evaluate_material(o.material, g, -dir);

  uint view = frame.view;
  if (view == TS_VIEW_NORMAL) return ms.N * 0.5 + 0.5;
  if (view == TS_VIEW_UV) return vec3(g.uv, 0.0);
  if (view == TS_VIEW_TRIANGLE) return id_colour(id);
  if (view == TS_VIEW_OBJECT) return id_colour(slot);

  return shade_surface(P, -dir, ms);
}

// Shades and writes `pixel` of a one-sample image whose visibility key is `key`: the background
// where it is empty, else the key's triangle seen through the pixel centre.
void shade_one_sample_pixel(ivec2 pixel, uint64_t key) {
  if (key == TS_VIS_EMPTY && background_is_uniform()) {
    write_background_pixel(pixel);
    return;
  }
  vec2 centre = vec2(pixel) + 0.5;
  vec3 color = key == TS_VIS_EMPTY ? background(centre) : shade_triangle(uint(key & 0xFFFFFFFFul), centre);
  write_pixel(pixel, stored(color));
}
