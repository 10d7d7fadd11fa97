#version 460
#extension GL_GOOGLE_include_directive : require
// Shading: one thread per pixel. Reads the visibility buffer, rebuilds the visible triangle
// in world space, intersects the pixel's camera ray with it for perspective-correct
// barycentrics, and evaluates the Cook-Torrance BRDF for every light into linear HDR.
#include "bindings.glsl"
#include "lighting.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// Largest finite fp16 value: the HDR image is RGBA16F and anything above would become Inf.
const float MAX_HALF = 65504.0;

vec3 camera_ray(ivec2 pixel) {
  vec2 ndc = (vec2(pixel) + 0.5) / vec2(frame.image_size.xy) * 2.0 - 1.0;
  vec4 far_point = frame.inv_view_proj * vec4(ndc, 1.0, 1.0);
  return normalize(far_point.xyz / far_point.w - frame.camera_position.xyz);
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

vec3 shade_sample(uint id, ivec2 pixel) {
  uint slot = find_object(id);
  GpuObject o = objects[slot];
  uvec3 vi = triangle_vertices(o, id);
  vec3 p[3];
  vec3 n[3];
  vec2 t[3];
  for (int k = 0; k < 3; ++k) {
    GpuVertex vert = vertices[vi[k]];
    p[k] = (o.model * vec4(vert.position_u.xyz, 1.0)).xyz;
    n[k] = mat3(o.normal_matrix) * vert.normal_v.xyz;
    t[k] = vec2(vert.position_u.w, vert.normal_v.w);
  }
  vec3 origin = frame.camera_position.xyz;
  vec3 dir = camera_ray(pixel);
  vec3 b = ray_barycentrics(origin, dir, p[0], p[1], p[2]);
  vec3 P = b.x * p[0] + b.y * p[1] + b.z * p[2];
  vec3 N = b.x * n[0] + b.y * n[1] + b.z * n[2];
  float n2 = dot(N, N);
  // Opposite vertex normals can cancel; the face normal is then the only sensible choice.
  N = n2 > 1e-20 ? N * inversesqrt(n2) : normalize(cross(p[1] - p[0], p[2] - p[0]));
  vec2 uv = b.x * t[0] + b.y * t[1] + b.z * t[2];

  uint view = frame.limits.w;
  if (view == TS_VIEW_NORMAL) return N * 0.5 + 0.5;
  if (view == TS_VIEW_UV) return vec3(uv, 0.0);
  if (view == TS_VIEW_TRIANGLE) return id_colour(id);
  if (view == TS_VIEW_OBJECT) return id_colour(slot);

  return shade_surface(P, N, -dir, o.material);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.image_size.xy)))) return;
  uint64_t key = visibility[pixel_index(pixel)];
  vec3 color = key == TS_VIS_EMPTY ? frame.background.rgb : shade_sample(uint(key & 0xFFFFFFFFul), pixel);
  imageStore(hdr_image, pixel, vec4(min(color, vec3(MAX_HALF)), 1.0));
}
