// Whether image-based lighting applies this frame: shared by the shading model (lighting.glsl)
// and the background (pixel_colour.glsl), so that the background's own dispatch
// (shade_background.comp) needs no lighting code. Needs bindings.glsl.
#ifndef TS_IBL_MODE_GLSL
#define TS_IBL_MODE_GLSL

// Image-based lighting: off, on, or decided per frame (the generic pipeline).
layout(constant_id = TS_SPEC_IBL) const uint IBL_MODE = TS_IBL_RUNTIME;

bool ibl_enabled() {
  return IBL_MODE == TS_IBL_ON || (IBL_MODE == TS_IBL_RUNTIME && frame.environment != 0u);
}

#endif
