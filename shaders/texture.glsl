// Texture filtering by hand from the texel buffer: the same lookups as core/texture.cpp (the
// reference), so the two agree to float rounding. Needs bindings.glsl.

// The texels of the level starting at texel `offset`: its address computed in 64 bits (the
// buffer may exceed 4 GiB, and an index past 2^31 into one runtime array may be taken as
// signed), the texels within it indexed from there (fewer than 2^28: validate_scene allows
// sides up to kMaxTextureSide, 16384).
TexelLevel texel_level(uint offset) {
  return TexelLevel(packUint2x32(frame.texels_address) + uint64_t(offset) * 8ul);
}

// Texel (x, y) of `level`, `width` texels wide, as linear RGBA.
vec4 texel_at(TexelLevel level, uint width, uint x, uint y) {
  uvec2 raw = unpackUint2x32(level.texels[y * width + x]);
  return vec4(unpackHalf2x16(raw.x), unpackHalf2x16(raw.y));
}

// Wraps a texel index that is at most one period outside [0, n).
uint wrap_once(int i, int n) {
  return uint(i < 0 ? i + n : (i >= n ? i - n : i));
}

// Folds a coordinate into [0, 1] by its TS_WRAP_* mode: repeat by its fraction, mirrored
// repeat with period 2, clamp to edge by clamping (beyond [0, 1] every lookup reads the edge
// texel alike, and a huge coordinate would overflow the integer texel index).
float fold_coordinate(float u, uint mode) {
  if (mode == TS_WRAP_MIRRORED_REPEAT) {
    float t = u - 2.0 * floor(0.5 * u);
    return t > 1.0 ? 2.0 - t : t;
  }
  return mode == TS_WRAP_REPEAT ? u - floor(u) : clamp(u, 0.0, 1.0);
}

// Texel index within one texel of [0, n) after fold_coordinate: repeat wraps, mirroring and
// clamping both read the edge texel.
uint texel_index(int i, int n, uint mode) {
  return mode == TS_WRAP_REPEAT ? wrap_once(i, n) : uint(clamp(i, 0, n - 1));
}

// Bilinear lookup of one level of texture `tex`, wrapping by its modes (repeat unless the
// scene has other modes: TS_MAP_WRAP_MODES). Reads the descriptor's fields from the buffer
// where needed: copying the whole GpuTexture into a local costs a lot on CPU implementations
// (its offset array becomes an indexed local array).
vec4 bilinear(uint tex, uint level, vec2 uv) {
  uint wrap = (TEXTURE_MAPS & TS_MAP_WRAP_MODES) != 0u ? textures[tex].wrap : 0u;
  uint wrap_u = wrap & 3u, wrap_v = wrap >> 2u;
  uv = vec2(fold_coordinate(uv.x, wrap_u), fold_coordinate(uv.y, wrap_v));
  ivec2 size = ivec2(max(textures[tex].size >> level, uvec2(1u)));
  TexelLevel texels = texel_level(textures[tex].level_offset[level >> 2u][level & 3u]);
  vec2 xy = uv * vec2(size) - 0.5;
  vec2 corner = floor(xy);
  vec2 f = xy - corner;
  ivec2 i0 = ivec2(corner);
  uint x0 = texel_index(i0.x, size.x, wrap_u), x1 = texel_index(i0.x + 1, size.x, wrap_u);
  uint y0 = texel_index(i0.y, size.y, wrap_v), y1 = texel_index(i0.y + 1, size.y, wrap_v);
  uint w = uint(size.x);
  return mix(mix(texel_at(texels, w, x0, y0), texel_at(texels, w, x1, y0), f.x),
             mix(texel_at(texels, w, x0, y1), texel_at(texels, w, x1, y1), f.x), f.y);
}

vec4 trilinear(uint tex, uint levels, vec2 uv, float lod) {
  float top = float(levels - 1u);
  lod = clamp(lod, 0.0, top);  // also maps the -inf of a zero footprint to level 0
  float l0 = floor(lod);
  uint i0 = uint(l0);
  float f = lod - l0;
  vec4 a = bilinear(tex, i0, uv);
  // The finer level alone when the blend weight is 0 (level 0 up close, the coarsest far).
  return f > 0.0 ? mix(a, bilinear(tex, min(i0 + 1u, levels - 1u), uv), f) : a;
}

// Filtered lookup of texture `index` at uv with the screen-space derivatives of one pixel step
// (see sample_texture in core/texture.h): trilinear at log2 of the footprint's longer axis in
// texels, or, with anisotropy > 1 (GpuFrame.anisotropy), up to that many trilinear probes along
// the longer axis at a finer level.
// Its three calls of trilinear (coarsest level, one probe, several) and trilinear's two calls of
// bilinear are inlined whole at each of the five sample_map calls (material.glsl) before
// specialization removes the maps a pipeline leaves out. One call of each, in loops, built a
// shading pipeline faster on lavapipe (a 16x16 render took 0.50 against 0.67 s), but made
// the H200's shading pass 3 % and its hardware baseline 5.6 % slower on the textured scene:
// kept as it is (docs/development.md, "Measured CI time").
vec4 sample_texture(uint index, vec2 uv, vec2 duv_dx, vec2 duv_dy) {
  uvec3 info = uvec3(textures[index].size, textures[index].levels);
  vec2 size = vec2(info.xy);
  uint levels = info.z;
  float lx = length(duv_dx * size);
  float ly = length(duv_dy * size);
  float major = max(lx, ly);
  float minor = min(lx, ly);
  // An infinite or NaN footprint (a triangle seen edge-on): the coarsest level.
  if (!(major <= 3.0e38)) return trilinear(index, levels, uv, float(levels - 1u));
  float probes = 1.0;
  uint anisotropy = frame.anisotropy;
  if (anisotropy > 1u && major > minor) probes = min(ceil(major / max(minor, 1e-20)), float(anisotropy));
  float lod = log2(major / probes);
  if (probes == 1.0) return trilinear(index, levels, uv, lod);
  vec2 axis = lx >= ly ? duv_dx : duv_dy;
  vec4 sum = vec4(0.0);
  for (int i = 0; i < int(probes); ++i) {
    sum += trilinear(index, levels, uv + axis * ((float(i) + 0.5) / probes - 0.5), lod);
  }
  return sum / probes;
}
