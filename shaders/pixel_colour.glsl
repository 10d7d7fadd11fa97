// What a pixel shows, shared by the shading pass and the outline pass: the camera ray through
// a point of the image, the background along it, and how a pixel's colour is stored. Needs
// bindings.glsl and display.glsl.
#include "ibl_mode.glsl"

// Unit ray through the point `pixel_point` of the image, in pixels.
vec3 camera_ray_at(vec2 pixel_point) {
  vec2 ndc = pixel_point / vec2(frame.image_size) * 2.0 - 1.0;
  // The far plane's point relative to the eye (GpuFrame::camera_rays). Built as a point in
  // world space minus the camera's position, it kept about 24 bits of the two: 3e6 m from the
  // origin with a 0.1 m near plane the rays moved in 0.25 m steps on a 100 m far plane, and
  // shading showed every facet.
  return normalize((frame.camera_rays * vec4(ndc, 1.0, 0.0)).xyz);
}

// What samples no triangle covers show, seen through `point` (in pixels).
// Whether that is one colour, frame.background, everywhere (no environment behind the scene).
bool background_is_uniform() {
  return !(ibl_enabled() && frame.view == TS_VIEW_SHADED);
}

vec3 background(vec2 point) {
  if (!background_is_uniform()) {
    return textureLod(env_map, equirect_uv(camera_ray_at(point)), 0.0).rgb;
  }
  return frame.background;
}

// The colour a group of samples stores: pre-exposed and clamped to what the HDR image's format
// holds (65504 for fp16), so that overflow saturates instead of becoming Inf.
vec3 stored(vec3 color) {
  return min(color * pre_exposure(), vec3(frame.hdr_max));
}

// Writes a pixel's stored colour into the HDR image and, when the shading pass resolves
// (GpuFrame.resolve_in_shading), its display colour into the display image: from the value as
// the HDR image holds it, so the bytes are those the resolve pass would compute from that image,
// without its dispatch, its barrier and its reading of the image.
void write_pixel(ivec2 pixel, vec3 value) {
  imageStore(hdr_image, pixel, vec4(value, 1.0));
  if (frame.resolve_in_shading != 0u) imageStore(ldr_image, pixel, vec4(display_colour(as_stored(value)), 1.0));
}

// write_pixel(pixel, stored(background(...))) for a pixel of one sample no triangle covers, under
// background_is_uniform(): the values the background pass computed (GpuBackground).
void write_background_pixel(ivec2 pixel) {
  imageStore(hdr_image, pixel, background_colours.stored);
  if (frame.resolve_in_shading != 0u) imageStore(ldr_image, pixel, background_colours.display);
}
