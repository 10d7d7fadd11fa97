// The display colour of an HDR value: tone mapping and sRGB encoding, shared by the resolve pass
// (resolve.comp, which reads the HDR image) and the shading pass when it resolves its own pixels
// (GpuFrame.resolve_in_shading). Both must give the same bytes for the same stored value.

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": a fit of the ACES reference rendering
// transform's luminance response.
vec3 tonemap_aces(vec3 x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// Reinhard et al. 2002, "Photographic Tone Reproduction for Digital Images", per channel.
vec3 tonemap_reinhard(vec3 x) {
  return x / (1.0 + x);
}

// IEC 61966-2-1 sRGB transfer function.
vec3 srgb_encode(vec3 c) {
  vec3 lo = 12.92 * c;
  vec3 hi = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
  return mix(hi, lo, lessThanEqual(c, vec3(0.0031308)));
}

// Tone-mapped, sRGB-encoded colour of `stored`, a value as the HDR image holds it (the shading
// pass already applied the exposure: pre-exposure, bindings.glsl).
vec3 display_colour(vec3 stored) {
  vec3 hdr = max(stored, vec3(0.0));
  // Debug views hold values in [0, 1] meant to be seen as they are: no curve.
  bool shaded = frame.view == TS_VIEW_SHADED;
  uint op = shaded ? frame.tonemap : TS_TONEMAP_CLAMP;
  vec3 mapped = op == TS_TONEMAP_ACES       ? tonemap_aces(hdr)
                : op == TS_TONEMAP_REINHARD ? tonemap_reinhard(hdr)
                                            : clamp(hdr, 0.0, 1.0);
  return srgb_encode(mapped);
}

// `x` rounded to an IEEE 754 binary16 value, to nearest even or toward zero: what an RGBA16F
// image stores for it (Vulkan allows either; GpuFrame.hdr_rounding says which this device does),
// so that the shading pass resolves the value the resolve pass would read back. Integer
// arithmetic, so that no float mode (flush, fast math) changes it. Precondition: |x| is at most
// TS_MAX_HALF, or Inf or NaN (returned as they are), as GpuFrame.hdr_max makes it.
float round_to_half(float x, bool nearest_even) {
  uint a = floatBitsToUint(x) & 0x7FFFFFFFu;
  if (a >= 0x7F800000u) return x;
  int e = int(a >> 23) - 127;  // |x| = sig * 2^(e - 23)
  // Below half the smallest subnormal half (2^-25; exactly that ties to the even 0), and below
  // the smallest toward zero: zero. This also takes 32-bit subnormals.
  if (e < -25) return x < 0.0 ? -0.0 : 0.0;
  uint sig = (a & 0x7FFFFFu) | 0x800000u;
  // Bits of `sig` below the half's last: 13 for a normal half, more below 2^-14 (subnormal).
  uint drop = uint(13 + max(-14 - e, 0));  // 13 to 24
  uint unit = 1u << drop;
  uint rest = sig & (unit - 1u);
  uint kept = sig - rest;
  if (nearest_even && (rest > unit / 2u || (rest == unit / 2u && (kept & unit) != 0u))) kept += unit;
  // kept has at most 12 significant bits: float() and ldexp are exact.
  float r = ldexp(float(kept), e - 23);
  return x < 0.0 ? -r : r;
}

// `c` as the HDR image holds it (GpuFrame.hdr_rounding).
vec3 as_stored(vec3 c) {
  if (frame.hdr_rounding == TS_HDR_ROUNDING_AS_IS) return c;
  bool nearest = frame.hdr_rounding == TS_HDR_ROUNDING_HALF_NEAREST_EVEN;
  return vec3(round_to_half(c.r, nearest), round_to_half(c.g, nearest), round_to_half(c.b, nearest));
}
