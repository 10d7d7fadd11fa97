// Samples per pixel (anti-aliasing, FrameSettings::samples) and where they lie: the patterns of
// shared/constants.h, fixed per pipeline by a specialization constant, so that the 1-sample
// pipelines compute exactly what they did before there were others. Visibility keys are stored
// pixel after pixel, each pixel's SAMPLES keys together.

layout(constant_id = TS_SPEC_SAMPLES) const uint SAMPLES = 1u;

const ivec2 SAMPLES_4[4] = ivec2[4](TS_SAMPLES_4(ivec2));
const ivec2 SAMPLES_8[8] = ivec2[8](TS_SAMPLES_8(ivec2));
const ivec2 SAMPLES_16[16] = ivec2[16](TS_SAMPLES_16(ivec2));

// Fixed-point offset of sample s from its pixel's top-left corner, in 1/TS_SUBPIXEL_ONE px.
ivec2 sample_offset(uint s) {
  const int scale = TS_SUBPIXEL_ONE / TS_SAMPLE_GRID;
  if (SAMPLES == 4u) return SAMPLES_4[s] * scale;
  if (SAMPLES == 8u) return SAMPLES_8[s] * scale;
  if (SAMPLES == 16u) return SAMPLES_16[s] * scale;
  return ivec2(TS_SUBPIXEL_ONE / 2);  // one sample: the pixel centre
}

// Smallest and largest sample offsets on each axis: the reach of a pixel's samples, for boxes
// and conservative tile tests.
ivec2 sample_offset_min() {
  ivec2 m = sample_offset(0u);
  for (uint s = 1u; s < SAMPLES; ++s) m = min(m, sample_offset(s));
  return m;
}
ivec2 sample_offset_max() {
  ivec2 m = sample_offset(0u);
  for (uint s = 1u; s < SAMPLES; ++s) m = max(m, sample_offset(s));
  return m;
}

// Index of sample s of a pixel (pixel_index, bindings.glsl) in the visibility buffer.
uint sample_index(uint pixel, uint s) {
  return pixel * SAMPLES + s;
}
