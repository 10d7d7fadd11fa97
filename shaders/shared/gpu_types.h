// GPU-visible data layouts, shared by the GLSL compute shaders and the C++ host.
//
// This is the one definition of every struct that crosses the host/GPU boundary. Members are
// only vec4, uvec4, mat4 and groups of four 32-bit scalars, so std430 (buffers) and std140
// (the frame uniform block) give the same offsets as C++ with glm; the static_asserts at the
// end check size and offsets on the C++ side.
#ifndef TESSERA_GPU_TYPES_H
#define TESSERA_GPU_TYPES_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace tessera::gpu {
using uint = std::uint32_t;
using glm::mat4;
using glm::uvec4;
using glm::vec4;
#endif

// Fixed-point screen coordinates: 8 sub-pixel bits, as in common hardware rasterizers.
#define TS_SUBPIXEL_BITS 8
#define TS_SUBPIXEL_ONE 256
// Screen tiles used by binning and the per-tile rasterizer, in pixels per side.
#define TS_TILE_SIZE 16
// Snapped coordinates stay inside +-TS_GUARD_BAND_PX so that edge products fit easily in int64
// and the coordinates themselves in int32 (2^15 px * 2^8 = 2^23).
#define TS_GUARD_BAND_PX 32768.0
// Largest image side the renderer accepts: box corners are packed as two 16-bit halves.
#define TS_MAX_IMAGE_SIDE 16384
// Visibility buffer value of a pixel no triangle covers (all bits set: larger than any key).
#define TS_VIS_EMPTY 0xFFFFFFFFFFFFFFFFul
// Threads per workgroup of the one-thread-per-item passes.
#define TS_GROUP_SIZE 64
// Workgroup size of the setup pass: its cull counters are summed per workgroup, so larger
// groups mean fewer atomics on the same few addresses.
#define TS_SETUP_GROUP_SIZE 256
// Workgroup size of the prefix-sum pass.
#define TS_SCAN_GROUP_SIZE 256
// Workgroups of the clipping pass; its threads loop over the (usually short) clip list.
#define TS_CLIP_GROUPS 16
// Workgroups of the tile-counting pass; its threads loop over the bin entries.
#define TS_COUNT_GROUPS 512
// A binned triangle is split into bin entries of at most this many tiles per side, so that no
// thread loops over more than TS_BIN_CHUNK^2 tiles when counting or filling.
#define TS_BIN_CHUNK 8

// Light kinds (GpuLight.kind.x) and falloff models (GpuLight.kind.y).
#define TS_LIGHT_POINT 0u
#define TS_LIGHT_DIRECTIONAL 1u
#define TS_LIGHT_SPOT 2u
#define TS_FALLOFF_INVERSE_SQUARE 0u
#define TS_FALLOFF_CLASSIC 1u

// BRDF variants (specialization constant TS_SPEC_BRDF of the shading stages).
#define TS_BRDF_CLASSIC 0u
#define TS_BRDF_FILAMENT 1u
#define TS_BRDF_BLINN_PHONG 2u

// Tone-mapping operators (GpuFrame.scene_counts.w).
#define TS_TONEMAP_ACES 0u
#define TS_TONEMAP_REINHARD 1u
#define TS_TONEMAP_CLAMP 2u

// What the shading pass writes (GpuFrame.limits.w): shaded colour, or a debug view.
#define TS_VIEW_SHADED 0u
#define TS_VIEW_NORMAL 1u    // world normal * 0.5 + 0.5
#define TS_VIEW_UV 2u        // (u, v, 0)
#define TS_VIEW_TRIANGLE 3u  // a colour hashed from the triangle-instance id
#define TS_VIEW_OBJECT 4u    // a colour hashed from the object slot

// Facing culled by setup (GpuFrame.flags.x).
#define TS_CULL_BACK 0u
#define TS_CULL_FRONT 1u
#define TS_CULL_NONE 2u

// Descriptor bindings of the one descriptor set every pass uses.
#define TS_BINDING_FRAME 0
#define TS_BINDING_VERTICES 1
#define TS_BINDING_INDICES 2
#define TS_BINDING_OBJECTS 3
#define TS_BINDING_MATERIALS 4
#define TS_BINDING_LIGHTS 5
#define TS_BINDING_RASTER_TRIS 6
#define TS_BINDING_SMALL_LIST 7
#define TS_BINDING_BIG_LIST 8
#define TS_BINDING_TILE_COUNTS 9
#define TS_BINDING_TILE_OFFSETS 10
#define TS_BINDING_TILE_CURSORS 11
#define TS_BINDING_TILE_ENTRIES 12
#define TS_BINDING_COUNTERS 13
#define TS_BINDING_VISIBILITY 14
#define TS_BINDING_COVERAGE 15
#define TS_BINDING_HDR_IMAGE 16
#define TS_BINDING_LDR_IMAGE 17
#define TS_BINDING_CLIP_LIST 18
#define TS_BINDING_DFG 19
#define TS_BINDING_TEXELS 20           // every texture's mip chain, fp16 RGBA
#define TS_BINDING_TEXTURES 21         // GpuTexture per Scene::textures entry
#define TS_BINDING_ENV_MAP 22          // equirectangular radiance with mips (sampler2D)
#define TS_BINDING_ENV_SPECULAR 23     // prefiltered specular cube, one roughness per level
#define TS_BINDING_ENV_LEVELS 24       // the same cube's levels as written by the prefilter
#define TS_BINDING_ENV_IRRADIANCE 25   // 9 spherical-harmonic coefficients of irradiance / pi
#define TS_BINDING_COUNT 26

// Specialization constant ids.
#define TS_SPEC_DEBUG_COVERAGE 0
#define TS_SPEC_BRDF 1
#define TS_SPEC_ENERGY_COMPENSATION 2
#define TS_SPEC_LIGHTS_SPECIALIZED 3  // the light counts below are the scene's (lights sorted by kind)
#define TS_SPEC_POINT_LIGHTS 4
#define TS_SPEC_SPOT_LIGHTS 5
#define TS_SPEC_DIRECTIONAL_LIGHTS 6
#define TS_SPEC_TEXTURE_MAPS 7  // maps the shader can sample (TS_MAP_* bits; all if generic)
#define TS_SPEC_IBL 8           // image-based lighting: TS_IBL_OFF, _ON, or _RUNTIME (generic)

#define TS_IBL_OFF 0u
#define TS_IBL_ON 1u
#define TS_IBL_RUNTIME 2u  // decided per frame by GpuFrame.flags.y

// Texture maps of a material (bits of TS_SPEC_TEXTURE_MAPS; slots of GpuMaterial.maps).
#define TS_MAP_BASE_COLOR 1u
#define TS_MAP_METALLIC_ROUGHNESS 2u
#define TS_MAP_NORMAL 4u
#define TS_MAP_OCCLUSION 8u
#define TS_MAP_ALL 15u
#define TS_NO_TEXTURE 0xFFFFFFFFu
// Mip levels a GpuTexture can describe: sides up to 2^15 (the largest accepted is 16384).
#define TS_MAX_TEXTURE_LEVELS 16
// Levels of the prefiltered specular cube: faces of up to 2^(TS_ENV_MAX_LEVELS - 1) texels.
#define TS_ENV_MAX_LEVELS 10

// Side of the DFG table: N.V and perceptual roughness from 0 to 1 inclusive (grid points
// i / (TS_DFG_SIZE - 1)), one table per visibility term.
#define TS_DFG_SIZE 64

// One mesh vertex: position and normal in object space, uv split over the two w components,
// and the tangent (xyz, object space) with its handedness (w, +-1) for normal maps.
struct GpuVertex {
  vec4 position_u;
  vec4 normal_v;
  vec4 tangent;
};

// One placed instance of a mesh. Objects are uploaded in a canonical order (see
// compute/scene_upload.cpp) and their triangles numbered consecutively: triangle-instance id
// `first_triangle + t` is triangle t of this object.
struct GpuObject {
  mat4 model;          // object -> world
  mat4 normal_matrix;  // inverse transpose of model's upper 3x3 (in a mat4 for alignment)
  uint first_index;    // first entry of the mesh in the index buffer
  uint base_vertex;    // added to every index of the mesh
  uint triangle_count;
  uint material;
  uint first_triangle;
  uint mirrored;  // 1 if model's upper 3x3 has a negative determinant (is_mirroring, scene.h)
  uint pad1;
  uint pad2;
};

// Metallic-roughness material; roughness is perceptual (alpha = roughness^2).
struct GpuMaterial {
  vec4 base_color;          // linear RGB, a unused
  vec4 emissive_occlusion;  // rgb: emitted radiance; a: occlusion (scales ambient and IBL)
  float metallic;
  float roughness;
  float normal_scale;
  float pad1;
  uvec4 maps;  // textures: base colour, metallic-roughness, normal, occlusion (TS_NO_TEXTURE)
};

// One texture: its mip chain in the texel buffer, level l being max(1, size >> l) texels per
// side, rows top to bottom, starting at texel level_offset[l / 4][l % 4].
struct GpuTexture {
  uvec4 size;  // width, height, levels, unused
  uvec4 level_offset[TS_MAX_TEXTURE_LEVELS / 4];
};

struct GpuLight {
  vec4 position;   // world, point and spot lights
  vec4 direction;  // world, unit, the direction light travels (directional and spot lights)
  vec4 radiance;   // rgb: colour * intensity (W/sr for point and spot lights, W/m^2 directional)
  vec4 falloff;    // x: 1 / range^4 (0: no fade), y, z, w: Kc, Kl, Kq (classic falloff)
  vec4 cone;       // spot: x = 1 / max(cos inner - cos outer, 1e-4), y = -cos outer * x
  uvec4 kind;      // x: TS_LIGHT_*, y: TS_FALLOFF_*
};

// Per-frame constants (uniform block, std140).
struct GpuFrame {
  mat4 view_proj;        // world -> clip; clip.w is the view-space distance along the view axis
  mat4 inv_view_proj;    // clip -> world, for the shading pass's camera rays
  vec4 camera_position;  // xyz world, w: near-plane distance
  vec4 background;       // linear HDR colour of pixels no triangle covers
  vec4 ambient;          // rgb: constant ambient radiance, multiplied by the diffuse albedo
  vec4 raster_params;    // x, y: guard band in NDC units; z: exposure scale 2^EV; w: unused
  uvec4 image_size;      // width, height, tiles_x, tiles_y
  uvec4 scene_counts;    // objects, lights, triangle instances, tone-mapping operator
  uvec4 limits;          // raster-triangle capacity, tile-entry capacity, small-path max box
                         // area, view (TS_VIEW_*)
  uvec4 flags;           // x: culling (TS_CULL_*); y: 1 if an environment lights the scene;
                         // z: levels of the prefiltered cube; w: texture anisotropy (>= 1)
};

// Push constants of the environment passes (env_irradiance.comp, env_prefilter.comp), in the
// same 16 bytes as GpuBatch.
struct GpuEnvPass {
  uint level;    // prefilter: cube level written; irradiance: env_map level read
  uint size;     // texels per side of that level
  uint samples;  // importance samples per texel (prefilter)
  uint levels;   // levels of the cube
};

// Push constants: the range of triangle instances one batch of the rasterizer handles.
struct GpuBatch {
  uint first_triangle;
  uint triangle_count;
  uint index;  // which GpuCounters slot this batch uses
  uint pad;
};

// A triangle after setup, clipped and snapped, ready to rasterize. 48 bytes.
struct GpuRasterTri {
  uvec4 xy01;     // x0, y0, x1, y1: int32 fixed point (TS_SUBPIXEL_BITS), stored as bits
  uvec4 xy2_box;  // x2, y2, box min (x | y << 16), box max (x | y << 16), inclusive pixels
  uvec4 depth_id; // x, y, z: float bits of near/w at each vertex; w: triangle-instance id
};

// Counters of one batch, written by the GPU and read back by the host after the frame.
struct GpuCounters {
  uvec4 small_dispatch;  // VkDispatchIndirectCommand for the per-triangle rasterizer (xyz)
  uvec4 big_dispatch;    // VkDispatchIndirectCommand for the tile-fill pass (xyz)
  uvec4 tiles_dispatch;  // VkDispatchIndirectCommand for the per-tile rasterizer (none if empty)
  uint raster_tris;      // triangles set up (may exceed capacity: then the frame is redone)
  uint small_tris;
  uint big_tris;         // bin entries (a binned triangle makes one per 8x8 block of tiles)
  uint tile_entries;     // entries the tile lists need (may exceed capacity, likewise)
  uint culled_backface;
  uint culled_frustum;   // entirely outside the view or behind the near plane
  uint culled_empty;     // zero area or no pixel centre covered
  uint culled_nonfinite; // a vertex with NaN or Inf clip coordinates
  uint clipped;          // triangles that crossed the near plane or the guard band
  uint clip_list;        // entries in the clip list (== clipped unless it overflowed)
  uint pad1;
  uint pad2;
};

#ifdef __cplusplus
static_assert(sizeof(GpuVertex) == 48);
static_assert(offsetof(GpuVertex, normal_v) == 16);
static_assert(offsetof(GpuVertex, tangent) == 32);
static_assert(sizeof(GpuObject) == 160);
static_assert(offsetof(GpuObject, normal_matrix) == 64);
static_assert(offsetof(GpuObject, first_index) == 128);
static_assert(offsetof(GpuObject, first_triangle) == 144);
static_assert(offsetof(GpuObject, mirrored) == 148);
static_assert(sizeof(GpuMaterial) == 64);
static_assert(offsetof(GpuMaterial, emissive_occlusion) == 16);
static_assert(offsetof(GpuMaterial, metallic) == 32);
static_assert(offsetof(GpuMaterial, normal_scale) == 40);
static_assert(offsetof(GpuMaterial, maps) == 48);
static_assert(sizeof(GpuTexture) == 80);
static_assert(offsetof(GpuTexture, level_offset) == 16);
static_assert(sizeof(GpuLight) == 96);
static_assert(offsetof(GpuLight, falloff) == 48);
static_assert(offsetof(GpuLight, kind) == 80);
static_assert(sizeof(GpuFrame) == 256);
static_assert(offsetof(GpuFrame, inv_view_proj) == 64);
static_assert(offsetof(GpuFrame, camera_position) == 128);
static_assert(offsetof(GpuFrame, image_size) == 192);
static_assert(offsetof(GpuFrame, limits) == 224);
static_assert(offsetof(GpuFrame, flags) == 240);
static_assert(sizeof(GpuBatch) == 16);
static_assert(sizeof(GpuEnvPass) == sizeof(GpuBatch));
static_assert(sizeof(GpuRasterTri) == 48);
static_assert(sizeof(GpuCounters) == 96);
static_assert(offsetof(GpuCounters, big_dispatch) == 16);
static_assert(offsetof(GpuCounters, tiles_dispatch) == 32);
static_assert(offsetof(GpuCounters, raster_tris) == 48);
static_assert(offsetof(GpuCounters, clipped) == 80);
static_assert(offsetof(GpuCounters, clip_list) == 84);
}  // namespace tessera::gpu
#endif

#endif  // TESSERA_GPU_TYPES_H
