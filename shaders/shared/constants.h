// Constants of the rendering model shared by the GLSL shaders, the C++ host and the
// double-precision reference renderer (core/), which includes this header and nothing else of
// shaders/. Plain #defines with no type, so each language reads them in its own precision
// (float in GLSL, double in C++): a constant is defined here once and restated nowhere.
#ifndef TESSERA_CONSTANTS_H
#define TESSERA_CONSTANTS_H

// Visibility buffer value of a pixel no triangle covers (all bits set: larger than any key;
// core/pick.h reads keys on the CPU).
#define TS_VIS_EMPTY 0xFFFFFFFFFFFFFFFFul

// Fixed-point screen coordinates: 8 sub-pixel bits, as in common hardware rasterizers.
#define TS_SUBPIXEL_BITS 8
#define TS_SUBPIXEL_ONE 256
// Anti-aliasing (FrameSettings::samples): 1, 4, 8 or 16 samples per pixel at fixed positions,
// the standard multisample patterns of Vulkan (the "standard sample locations" of
// VkPhysicalDeviceLimits::standardSampleLocations) and Direct3D, given here on a grid of 1/32
// pixel (their 1/16 positions doubled), (0, 0) the pixel's top-left corner, y down. One sample
// is the pixel centre (16, 16). The 16-sample pattern is the standard one moved by 1/32 px right
// and down (2p + 1): the standard 16 positions use each row and column of the 1/16 grid once,
// so they average (7.5, 7.5) / 16, 1/32 px up and left of the centre, which shifted every edge
// and shading point by that much and made 16 samples less accurate than 8 (docs/tradeoffs.md,
// "Anti-aliasing"); moved, they average the centre, as the 4 and 8 patterns do.
// Multiplied by TS_SUBPIXEL_ONE / TS_SAMPLE_GRID they are exact fixed-point offsets. Each list
// is a macro taking the constructor of a 2-vector, so GLSL (ivec2) and C++ (glm::ivec2) expand
// the one definition: e.g. ivec2[4](TS_SAMPLES_4(ivec2)).
#define TS_SAMPLE_GRID 32
#define TS_MAX_SAMPLES 16
#define TS_SAMPLES_1(P) P(16, 16)
#define TS_SAMPLES_4(P) P(12, 4), P(28, 12), P(4, 20), P(20, 28)
#define TS_SAMPLES_8(P) \
  P(18, 10), P(14, 22), P(26, 18), P(10, 6), P(6, 26), P(2, 14), P(22, 30), P(30, 2)
#define TS_SAMPLES_16(P)                                                                           \
  P(19, 19), P(15, 11), P(11, 21), P(25, 15), P(7, 13), P(21, 27), P(27, 23), P(23, 7), P(13, 29), \
      P(17, 3), P(9, 5), P(5, 25), P(1, 17), P(31, 9), P(29, 31), P(3, 1)
// Snapped coordinates stay inside +-TS_GUARD_BAND_PX so that edge products fit easily in int64
// and the coordinates themselves in int32 (2^15 px * 2^8 = 2^23).
#define TS_GUARD_BAND_PX 32768.0
// Largest image side the renderer accepts: box corners are packed as two 16-bit halves.
#define TS_MAX_IMAGE_SIDE 16384
// Largest finite fp16 value: the HDR image is RGBA16F and anything above would become Inf.
#define TS_MAX_HALF 65504.0

// Guards of the shading model. They are part of the model, not of one implementation, so the
// compute path, the hardware baseline and the reference apply the same ones.
// Smallest perceptual roughness used: below it alpha^2 underflows the GGX denominator in fp32
// and a point light's highlight collapses to a single sample (Filament uses 0.045 for fp32).
#define TS_MIN_PERCEPTUAL_ROUGHNESS 0.045
// Smallest N.V used: at a silhouette N.V reaches 0 and the specular term divides by it.
#define TS_MIN_N_DOT_V 1e-4
// Smallest squared light distance, in m^2 (1 cm): a light on the surface would divide by zero.
#define TS_MIN_LIGHT_DISTANCE_SQUARED 1e-4
// Smallest classic attenuation denominator Kc + Kl d + Kq d^2: it is 0 at d = 0 when Kc = 0.
#define TS_MIN_ATTENUATION_DENOMINATOR 1e-4
// Smallest cos(inner) - cos(outer) of a spot cone: equal angles would divide by zero, and this
// makes the cone's edge a hard step instead.
#define TS_MIN_SPOT_COSINE_GAP 1e-4
// Smallest N.V a normal map may leave. A mapped normal can face away from the viewer (a steep
// bump near a silhouette); shading it would light the surface from below its horizon and make
// the clamped N.V of the specular term blow up. Such a normal is bent back towards V until
// N.V = 0.01 (about 0.6 degrees above the horizon), which keeps the image continuous.
#define TS_MIN_MAPPED_N_DOT_V 0.01
// Specular reflectance at normal incidence of every dielectric (an index of refraction of 1.5).
#define TS_DIELECTRIC_F0 0.04

// Light kinds (GpuLight.kind, the values of tessera::LightKind). Lights are uploaded sorted by
// kind in this order, and the shading pipeline is specialized to the number of each kind
// (specialization constant TS_SPEC_LIGHT_COUNT_BASE + kind). A new kind takes the next value
// and raises TS_LIGHT_KIND_COUNT.
#define TS_LIGHT_POINT 0u
#define TS_LIGHT_SPOT 1u
#define TS_LIGHT_DIRECTIONAL 2u
#define TS_LIGHT_KIND_COUNT 3
// How a point or spot light fades with distance (GpuLight.falloff, tessera::Falloff).
#define TS_FALLOFF_INVERSE_SQUARE 0u
#define TS_FALLOFF_CLASSIC 1u

// BRDF variants (tessera::Brdf; specialization constant TS_SPEC_BRDF of the shading stages).
#define TS_BRDF_CLASSIC 0u
#define TS_BRDF_FILAMENT 1u
#define TS_BRDF_BLINN_PHONG 2u

// How anti-aliasing (more than one sample per pixel) weighs the triangles of a pixel whose
// samples disagree (tessera::AaCoverage, specialization constant TS_SPEC_AA_COVERAGE): by the
// fraction of samples each holds; or, where they see one triangle and the background, by its
// outline coverage; or, where they see one surface and the background, by the area of the
// pixel its front faces cover (silhouette coverage) (shaders/coverage.glsl).
#define TS_AA_COVERAGE_COUNT 0u
#define TS_AA_COVERAGE_ANALYTIC 1u
#define TS_AA_COVERAGE_SILHOUETTE 2u
// Triangles a silhouette coverage walk takes in at most, the first included (the compute
// path's and the reference's): a pixel that needs more keeps the counts. On the default scene
// at 128 x 128 and 4 samples (spheres 14 px across, whose poles gather 64 slivers in a pixel)
// 24 gave an edge error 3.61x below 1 sample's, 32 4.39x, 48 5.17x (docs/tradeoffs.md).
#define TS_SILHOUETTE_TRIANGLES 32

// Tone-mapping operators (GpuFrame.tonemap).
#define TS_TONEMAP_ACES 0u
#define TS_TONEMAP_REINHARD 1u
#define TS_TONEMAP_CLAMP 2u

// What the shading pass writes (GpuFrame.view): shaded colour, or a debug view.
#define TS_VIEW_SHADED 0u
#define TS_VIEW_NORMAL 1u    // world normal * 0.5 + 0.5
#define TS_VIEW_UV 2u        // (u, v, 0)
#define TS_VIEW_TRIANGLE 3u  // a colour hashed from the triangle-instance id
#define TS_VIEW_OBJECT 4u    // a colour hashed from the object slot

// Texture maps of a material (bits of Material::uv1_maps, TS_SPEC_TEXTURE_MAPS,
// TS_SPEC_UV1_MAPS and GpuMaterial.uv1_maps; GpuMaterial.*_map).
#define TS_MAP_BASE_COLOR 1u
#define TS_MAP_METALLIC_ROUGHNESS 2u
#define TS_MAP_NORMAL 4u
#define TS_MAP_OCCLUSION 8u
#define TS_MAP_EMISSIVE 16u
// Not a map: some texture wraps other than by repeating (GpuTexture.wrap is read only then).
#define TS_MAP_WRAP_MODES 32u
#define TS_MAP_ALL 63u

#endif  // TESSERA_CONSTANTS_H
