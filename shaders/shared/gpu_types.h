// GPU-visible data layouts, shared by the GLSL compute shaders and the C++ host.
//
// This is the one definition of every struct that crosses the host/GPU boundary. Members come
// in 16-byte groups: a mat4; a vec4 or uvec4; a vec3 and one 32-bit scalar; a vec2 or uvec2
// and another, or two 32-bit scalars; or four 32-bit scalars. So std430 (buffers) and std140
// (the frame uniform block) give the same offsets as C++ with glm (whose vec3 is 12 bytes,
// 4-aligned); the static_asserts at the end check size and offsets on the C++ side. Every
// field has a name: no component of a vector holds an unrelated value, except in
// GpuRasterTri, packed into three 16-byte stores for the rasterizer's bandwidth
// (raster_common.glsl unpacks it), and the VkDispatchIndirectCommand vectors of GpuCounters.
#ifndef TESSERA_GPU_TYPES_H
#define TESSERA_GPU_TYPES_H

#include "constants.h"

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace tessera::gpu {
using uint = std::uint32_t;
using glm::mat4;
using glm::uvec2;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
#endif

// Screen tiles used by binning and the per-tile rasterizer, in pixels per side: the default of
// RendererOptions::tile_size, which specializes the passes that bin and rasterize by tiles
// (TS_SPEC_TILE_SIZE; the renderer accepts 8 and 16).
#define TS_TILE_SIZE 16
// A bin entry packs tile coordinates in 10 bits (setup_common.glsl): at most 1024 tiles per
// side, so a tile size s holds images up to 1024 s pixels per side.
#define TS_MAX_TILES_PER_SIDE 1024
// Threads per workgroup of the one-thread-per-item passes.
#define TS_GROUP_SIZE 64
// Workgroup size of the setup pass: its cull counters are summed per workgroup, so larger
// groups mean fewer atomics on the same few addresses.
#define TS_SETUP_GROUP_SIZE 256
// Workgroup size of the tile-list allocation pass (scan.comp), one thread per tile.
#define TS_SCAN_GROUP_SIZE 256
// Objects per workgroup of the level-of-detail passes (lod.comp, lod_offsets.comp): each
// workgroup's triangle count is one entry of the TS_BINDING_LOD_SUMS buffer.
#define TS_LOD_GROUP_SIZE 256
// A binned triangle is split into bin entries of at most this many tiles per side, so that no
// thread loops over more than TS_BIN_CHUNK^2 tiles when counting or filling.
#define TS_BIN_CHUNK 8
// Counting and filling deal an entry's tiles out among TS_BIN_CHUNK threads (raster_common.glsl's
// bin_block_tile), so that a triangle's tiles are visited in parallel: entries per workgroup.
#define TS_BIN_ENTRIES_PER_GROUP (TS_GROUP_SIZE / TS_BIN_CHUNK)
// An entry of the per-triangle rasterizer's list (TS_BINDING_SMALL_LIST) is a raster-triangle
// index (below 2^31: the buffers hold fewer than 2^27 raster triangles), or, for the later walks
// of a triangle dealt out among several (shaders/raster_common.glsl, small_walks), this bit and
// the walk k: the triangle's index is then the entry k places earlier.
#define TS_SMALL_WALK_BIT 0x80000000u
// Walks a small triangle is dealt out among at most (GpuCounters::small_counts).
#define TS_MAX_SMALL_WALKS 8u
// GpuCounters in 64-bit words (setup_common.glsl's 64-bit view of the counters), and the word
// of GpuCounters::small_counts.
#define TS_COUNTERS_WORDS 28u
#define TS_SMALL_COUNTS_WORD 7u

// How a shader's store to the HDR image changes a value (GpuFrame.hdr_rounding): not at all
// (RGBA32F), or to fp16 rounded to nearest even or toward zero (RGBA16F: Vulkan allows either;
// Renderer probes which). lavapipe rounds toward zero.
#define TS_HDR_ROUNDING_AS_IS 0u
#define TS_HDR_ROUNDING_HALF_NEAREST_EVEN 1u
#define TS_HDR_ROUNDING_HALF_TOWARD_ZERO 2u

// Facing culled by setup (GpuFrame.cull).
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
#define TS_BINDING_TEXTURES 20        // GpuTexture per Scene::textures entry
#define TS_BINDING_ENV_MAP 21         // equirectangular radiance with mips (sampler2D)
#define TS_BINDING_ENV_SPECULAR 22    // prefiltered specular cube, one roughness per level
#define TS_BINDING_ENV_LEVELS 23      // the same cube's levels as written by the prefilter
#define TS_BINDING_ENV_IRRADIANCE 24  // 9 spherical-harmonic coefficients of irradiance / pi
#define TS_BINDING_UV1 25          // the second uv set (vec2 per vertex), when a material reads it
#define TS_BINDING_LOD_LEVELS 26   // GpuLodLevel of every mesh's level-of-detail chain
#define TS_BINDING_LOD_MESHES 27   // GpuLodMesh per Scene::meshes entry
#define TS_BINDING_LOD_SUMS 28     // triangles per TS_LOD_GROUP_SIZE objects, then their scan
#define TS_BINDING_LOD_DRAWS 29    // VkDrawIndexedIndirectCommand per object (hardware baseline)
#define TS_BINDING_HDR_TEXTURE 30  // the HDR image again, sampled: what the resolve pass reads
// Per screen tile: an upper bound on the high word of every visibility key of the tile's
// samples (hierarchical depth rejection, raster_common.glsl), all ones when nothing is known.
#define TS_BINDING_TILE_FAR 31
// Per object: its clip-space transform this frame, view_proj * model (object_clip.comp).
#define TS_BINDING_OBJECT_CLIP 32
// Per index of TS_BINDING_INDICES (3 per triangle): the mesh's triangle across that corner's
// edge to the next, or TS_NO_NEIGHBOUR (core/mesh_adjacency.h), for silhouette coverage.
#define TS_BINDING_ADJACENCY 33
// Silhouette coverage: the outline pixels the shading pass found (GpuOutlinePixel), which the
// outline pass measures; GpuCounters.outline_pixels of batch 0 says how many.
#define TS_BINDING_OUTLINE 34
// Shading by tiles (RendererOptions::shade_tiles, shaders/list_tiles.comp): per screen tile,
// nonzero once a rasterizer may have written a sample of it this frame; then the tiles the
// shading pass shades (from the front) and those its background dispatch fills (from the back).
// Before that, in a frame with counted tile lists and shading by tiles, each batch's scan pass
// lists there the tiles that hold entries for the per-tile rasterizer
// (GpuCounters::tiles_dispatch).
#define TS_BINDING_TILE_DRAWN 35
#define TS_BINDING_SHADE_TILES 36
#define TS_BINDING_COUNT 37
#define TS_NO_NEIGHBOUR 0xFFFFFFFFu
// The objects' buffer (TS_BINDING_OBJECTS) holds, after its GpuObject array, a word per
// TS_TRIANGLE_GROUP triangle-instance ids (group k: ids from k * TS_TRIANGLE_GROUP on): the
// object slot that holds the group's first id (group_objects, compute/scene_upload.h), where
// setup's object search starts. After the objects rather than a buffer of its own: lavapipe
// allows 32 storage buffers a stage, and the passes' one descriptor set had them all (31 since
// the texels are read at a device address, GpuFrame.texels_address).
#define TS_TRIANGLE_GROUP_BITS 8u
#define TS_TRIANGLE_GROUP (1u << TS_TRIANGLE_GROUP_BITS)
#define TS_OBJECT_WORDS 40u  // sizeof(GpuObject) / 4

// GpuBatch.flags
#define TS_BATCH_LOD_DRAWS 1u  // the lod pass also writes each object's indexed draw

// Specialization constant ids.
#define TS_SPEC_DEBUG_COVERAGE 0
#define TS_SPEC_BRDF 1
#define TS_SPEC_ENERGY_COMPENSATION 2
#define TS_SPEC_LIGHTS_SPECIALIZED \
  3                             // the light counts below are the scene's (lights sorted by kind)
#define TS_SPEC_TEXTURE_MAPS 4  // maps the shader can sample (TS_MAP_* bits; all if generic)
#define TS_SPEC_IBL 5           // image-based lighting: TS_IBL_OFF, _ON, or _RUNTIME (generic)
#define TS_SPEC_UV1_MAPS 6      // maps that may read uv set 1 (TS_MAP_* bits; all if generic)
#define TS_SPEC_SAMPLES 7       // samples per pixel: 1, 4, 8 or 16 (shaders/samples.glsl)
#define TS_SPEC_OUTPUT_BGRA 8   // the resolve pass stores B, G, R, A (a B8G8R8A8 swapchain's order)
#define TS_SPEC_LOD 9           // setup: the batch's triangle count is the level-of-detail pass's
#define TS_SPEC_TILE_SIZE 10  // tile side in px (RendererOptions::tile_size): binning, raster_tiles
#define TS_SPEC_DEPTH_REJECTION \
  11  // RendererOptions::depth_rejection: fill, raster_tiles, raster_small
#define TS_SPEC_AA_COVERAGE 12  // anti-aliased shading's weights: TS_AA_COVERAGE_* (FrameSettings)
// The outline pass's walk limit: FrameSettings::silhouette_steps (0: no limit).
#define TS_SPEC_SILHOUETTE_STEPS 13
// Shading by tiles (RendererOptions::shade_tiles): TS_SHADE_TILES_*. The rasterizers mark the
// tiles they draw into unless it is TS_SHADE_TILES_OFF; the shading pass takes it as below.
#define TS_SPEC_SHADE_TILES 14
// Setup forms each triangle's view_proj * model itself instead of reading the object_clip pass's
// (view_clip.glsl), in frames that record no object_clip pass (renderer.cpp's
// forms_object_clip_in_setup).
#define TS_SPEC_OBJECT_CLIP_INLINE 15
// Setup appends raster triangles only, no small-triangle walks or bin entries: in frames that
// rasterize and shade in one pass (RendererOptions::raster_shade), which read neither.
#define TS_SPEC_RASTER_ONLY 16
// The clipped polygons of view_clip.glsl and coverage.glsl are walked as queues indexed by
// constants only, rather than indexed by corner (Context::polygons_in_registers).
#define TS_SPEC_POLYGONS_IN_REGISTERS 17
// The number of lights of kind k (TS_LIGHT_*) has id TS_SPEC_LIGHT_COUNT_BASE + k, for k below
// TS_LIGHT_KIND_COUNT: the last ids, so a new light kind adds one without renumbering.
#define TS_SPEC_LIGHT_COUNT_BASE 18

// How the shading pass is dispatched (TS_SPEC_SHADE_TILES).
#define TS_SHADE_TILES_OFF 0u    // a workgroup per 8x8 pixels of the whole image
#define TS_SHADE_TILES_DRAWN 1u  // over the tiles list_tiles found drawn into
#define TS_SHADE_TILES_BACKGROUND \
  2u  // over the others, which hold only background: no
      // visibility read, no shading code

#define TS_IBL_OFF 0u
#define TS_IBL_ON 1u
#define TS_IBL_RUNTIME 2u  // decided per frame by GpuFrame.environment

// GpuTexture.wrap: the mode of u in bits 0-1, of v in bits 2-3 (glTF 2.0 sampler wrapS/wrapT,
// as OpenGL's REPEAT, CLAMP_TO_EDGE and MIRRORED_REPEAT).
#define TS_WRAP_REPEAT 0u
#define TS_WRAP_CLAMP_TO_EDGE 1u
#define TS_WRAP_MIRRORED_REPEAT 2u
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
// `first_triangle + t` is triangle t of this object. Under level of detail the lod passes
// rewrite first_index, base_vertex, triangle_count and first_triangle every frame with the
// chosen level's (from `mesh`'s chain, which they read and never write).
struct GpuObject {
  mat4 model;          // object -> world
  mat4 normal_matrix;  // inverse transpose of model's upper 3x3 (in a mat4 for alignment)
  uint first_index;    // first entry of the mesh in the index buffer
  uint base_vertex;    // added to every index of the mesh
  uint triangle_count;
  uint material;
  uint first_triangle;
  uint mirrored;      // 1 if model's upper 3x3 has a negative determinant (is_mirroring, scene.h)
  uint double_sided;  // 1 if its material is double-sided: never culled by facing
  uint mesh;          // index of its mesh in Scene::meshes (its GpuLodMesh)
};

// One level of a mesh's level-of-detail chain (core/lod.h): its triangles in the index and
// vertex buffers, and its object-space error.
struct GpuLodLevel {
  uint first_index;
  uint base_vertex;
  uint triangle_count;
  float error;  // object-space distance, in the mesh's units (LodLevel::error)
};

// The chain of one mesh: levels first_level .. first_level + level_count - 1 of
// TS_BINDING_LOD_LEVELS, finest first, and the object-space sphere around all of them.
struct GpuLodMesh {
  vec3 centre;
  float radius;
  uint first_level;
  uint level_count;
  uint pad0;
  uint pad1;
};

// Metallic-roughness material (core/scene.h's Material, whose comments give ranges and units);
// roughness is perceptual (alpha = roughness^2). The maps index GpuTexture (TS_NO_TEXTURE: none).
struct GpuMaterial {
  vec3 base_color;  // linear RGB
  float metallic;
  vec3 emissive;  // emitted radiance, linear RGB
  float roughness;
  float occlusion;  // scales ambient and environment light
  float normal_scale;
  uint double_sided;  // 1: back faces shaded with the frame flipped toward the viewer
  uint emissive_map;
  uint base_color_map;
  uint metallic_roughness_map;
  uint normal_map;
  uint occlusion_map;
  uint uv1_maps;  // TS_MAP_* bits of the maps that read uv set 1 (the TS_BINDING_UV1 buffer)
  uint pad0;
  uint pad1;
  uint pad2;
};

// One texture: its mip chain in the texel buffer, level l being max(1, size >> l) texels per
// side, rows top to bottom, starting at texel level_offset[l / 4][l % 4].
struct GpuTexture {
  uvec2 size;   // texels of level 0
  uint levels;  // in the mip chain
  uint wrap;    // TS_WRAP_* of u | (of v << 2)
  uvec4 level_offset[TS_MAX_TEXTURE_LEVELS / 4];
};

// One light (core/scene.h's Light, converted by flatten_scene).
struct GpuLight {
  vec3 position;      // world, lights with a position (all but directional)
  uint kind;          // TS_LIGHT_*
  vec3 direction;     // world, unit, the direction light travels (directional and spot lights)
  uint falloff;       // TS_FALLOFF_*
  vec3 radiance;      // colour * intensity (W/sr for point and spot lights, W/m^2 directional)
  float inv_range4;   // inverse-square falloff: 1 / range^4 (0: no fade)
  vec3 attenuation;   // classic falloff: Kc, Kl, Kq
  float cone_scale;   // spot: 1 / max(cos inner - cos outer, TS_MIN_SPOT_COSINE_GAP)
  float cone_offset;  // spot: -cos outer * cone_scale, so saturate(cos * scale + offset)
  float pad0;
  float pad1;
  float pad2;
};

// Per-frame constants (uniform block, std140).
struct GpuFrame {
  mat4 view_proj;  // world -> clip; clip.w is the view-space distance along the view axis
  // The camera rays: (NDC x, NDC y, 1, 0) -> a point of the far plane relative to the eye,
  // in world axes (columns: its slopes along x and y, its value at the centre, 0). No camera
  // position to subtract, which lost the direction to float rounding far from the origin.
  mat4 camera_rays;
  vec3 camera_position;  // world
  float near_plane;      // distance of the near plane
  vec3 background;       // linear HDR colour of pixels no triangle covers
  float exposure_scale;  // 2^EV, applied before tone mapping
  vec3 ambient;          // constant ambient radiance, multiplied by the diffuse albedo
  uint view;             // TS_VIEW_*
  vec2 guard_band;       // x, y extent of the guard band in NDC units
  uint tonemap;          // TS_TONEMAP_*
  uint cull;             // TS_CULL_*
  uvec2 image_size;      // pixels
  uvec2 tiles;           // tiles per row and column
  uint object_count;
  uint light_count;
  uint triangle_count;   // triangle instances
  uint raster_capacity;  // raster triangles the buffers hold
  uint tile_entry_capacity;
  uint small_triangle_max_area;  // largest pixel box of the per-triangle rasterizer
  // Pixels a thread of the per-triangle rasterizer walks at most, about: larger boxes are dealt
  // out among several walks (RendererOptions::small_triangle_walk_area, small_walks)
  uint small_triangle_walk_area;
  uint environment;  // 1 if an environment lights the scene
  uint env_levels;   // levels of the prefiltered specular cube
  uint anisotropy;   // texture anisotropy (>= 1)
  // Level of detail: a level is fine enough where error * (largest axis scale) * lod_scale
  // <= the view depth of the near side of the object's bounding sphere (core/lod.h).
  float lod_scale;       // lod_pixels_per_unit / lod_error_px
  uint batch_count;      // batches of this frame (the lod_scan pass sizes each one's setup)
  uint batch_triangles;  // triangle instances per batch (the last may hold fewer)
  // Largest value the HDR image stores (FrameSettings::hdr_format): the largest finite fp16
  // (TS_MAX_HALF) or fp32 value, so that overflow saturates instead of becoming Inf.
  float hdr_max;
  uint hdr_rounding;  // TS_HDR_ROUNDING_*: how a store to the HDR image changes a value
  // 1: the shading pass also writes the display image, from the HDR values as the HDR image
  // holds them (RendererOptions::resolve; shaders/display.glsl)
  uint resolve_in_shading;
  // Direct tile lists (RendererOptions::tile_lists): slots of each tile's list, which starts at
  // tile * tile_list_stride of the tile-entry array; 0: the lists are counted (count and scan
  // passes) and packed.
  uint tile_list_stride;
  // 1: the shading pass empties every key it reads (FrameSettings::keep_visibility off), so
  // that the next frame need not fill the visibility buffer.
  uint reset_visibility;
  // The device address of the scene's texels (every texture's mip chain, fp16 RGBA, two halves
  // per uint: GpuSceneArrays::texels) as (low, high) words. Read through a buffer reference
  // (texture.glsl) rather than a descriptor, whose range maxStorageBufferRange caps (128 MiB,
  // 16.7 M texels, on lavapipe); a buffer reached by address is capped only by the device's
  // allocation and buffer sizes.
  uvec2 texels_address;
};

// One input of the BRDF probe (brdf_probe.comp, tests only): directions and a material.
struct GpuBrdfSample {
  vec3 n;  // unit normal
  float metallic;
  vec3 v;           // unit direction towards the viewer
  float roughness;  // perceptual
  vec3 l;           // unit direction towards the light
  float pad0;
  vec3 base_color;
  float pad1;
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
  uint flags;  // TS_BATCH_* bits
};

// An outline pixel (silhouette coverage, several samples): one whose samples see triangles of
// one surface and the background. The shading pass writes the pixel with the counts' weights
// and lists it here with its surface's colour; the outline pass, once it has the surface's
// exact area in the pixel, writes it again. 16 bytes.
struct GpuOutlinePixel {
  // The surface's stored colour (pre-exposed, clamped): its triangles' colours weighted by the
  // share of the surface's samples each holds.
  vec3 surface;
  uint pixel;  // x | y << 16
};

// What a pixel no triangle covers stores when the background is one colour (no environment
// behind the scene): computed once by the background pass (background.comp) whenever what it
// depends on changes, and stored by the shading pass, which then need not tone-map and encode
// each background pixel. 32 bytes, after the DFG tables in their buffer (TS_BINDING_DFG,
// TS_BACKGROUND_OFFSET): a binding of its own would have been lavapipe's 33rd storage buffer
// of a stage, one more than it allows (maxPerStageDescriptorStorageBuffers), before the texels
// left the set.
#define TS_DFG_BYTES (2 * (TS_DFG_SIZE + 1) * TS_DFG_SIZE * 16)  // two tables and their means
#define TS_BACKGROUND_OFFSET TS_DFG_BYTES
struct GpuBackground {
  vec4 stored;   // pixel_colour.glsl's stored(frame.background), alpha 1: the HDR image's value
  vec4 display;  // display.glsl's display_colour of it as the HDR image holds it, alpha 1
};

// The outline pass walks each outline pixel's mesh with TS_OUTLINE_LANES threads, which test
// the neighbours of a step of the walk together, TS_OUTLINE_PIXELS_PER_GROUP pixels per
// workgroup (the multiple the shading pass raises its dispatch by).
#define TS_OUTLINE_LANES 8
#define TS_OUTLINE_PIXELS_PER_GROUP 8

// A triangle after setup, clipped and snapped, ready to rasterize. 48 bytes.
struct GpuRasterTri {
  uvec4 xy01;      // x0, y0, x1, y1: int32 fixed point (TS_SUBPIXEL_BITS), stored as bits
  uvec4 xy2_box;   // x2, y2, box min (x | y << 16), box max (x | y << 16), inclusive pixels
  uvec4 depth_id;  // x, y, z: float bits of near/w at each vertex; w: triangle-instance id
};

// Counters of one batch, written by the GPU and read back by the host after the frame.
struct GpuCounters {
  uvec4 small_dispatch;  // VkDispatchIndirectCommand for the per-triangle rasterizer (xyz)
  // VkDispatchIndirectCommand (xyz) for the tile-count and tile-fill passes, TS_BIN_CHUNK
  // threads per bin entry: x is raised by setup and clip as their appends reach into a new grain of
  // entries (setup_common.glsl), y and z set by setup's first thread.
  uvec4 big_dispatch;
  // VkDispatchIndirectCommand (xyz) for the per-tile rasterizer (none if empty). With counted
  // tile lists and shading by tiles, rows of x workgroups over the w tiles that hold entries,
  // which the scan pass lists in shade_tiles (TS_BINDING_SHADE_TILES) and counts in w.
  uvec4 tiles_dispatch;
  uint raster_tris;  // triangles set up (may exceed capacity: then the frame is redone)
  uint big_tris;     // bin entries (a binned triangle makes one per 8x8 block of tiles)
  // x: entries of the per-triangle rasterizer's list (a walk each, small_walks; may exceed
  // capacity, likewise); y: the small triangles that take them. Setup and clip append to both
  // with one 64-bit atomic on the pair (word TS_SMALL_COUNTS_WORD of the batch's counters, x
  // the low half). x cannot carry into y: a batch holds at most 2^26 triangles
  // (State::max_batch), clipping makes at most 6 of each, and a triangle takes at most
  // TS_MAX_SMALL_WALKS walks, so fewer than 3 * 2^30 entries.
  uvec2 small_counts;
  uint tile_entries;  // entries the tile lists need (may exceed capacity, likewise)
  uint culled_backface;
  uint culled_frustum;    // entirely outside the view or behind the near plane
  uint culled_empty;      // zero area or no pixel centre covered
  uint culled_nonfinite;  // a vertex with NaN or Inf clip coordinates
  uint clipped;           // triangles that crossed the near plane or the guard band
  uint clip_list;         // entries in the clip list (== clipped unless it overflowed)
  uint lod_triangles;     // level of detail: triangle instances of this batch
  uvec4 setup_dispatch;   // level of detail: VkDispatchIndirectCommand for setup (xyz)
  // Hierarchical depth rejection: tile-list entries raster_tiles skipped without testing a
  // pixel, and small triangles raster_small skipped without walking their box, each because
  // its nearest depth lies behind everything already drawn in its tile(s).
  uint rejected_entries;
  uint rejected_small;
  // Direct tile lists: the longest list the fill pass appended to (may exceed
  // GpuFrame::tile_list_stride: then the frame is redone with longer lists).
  uint tile_list_max;
  uint lod_total;       // level of detail, batch 0's slot: triangle instances of the frame
  uvec4 clip_dispatch;  // VkDispatchIndirectCommand for the clip pass, raised as big_dispatch
  // Silhouette coverage, batch 0's slot: VkDispatchIndirectCommand (xyz) for the outline pass,
  // x raised by the shading pass as its appends reach into a new workgroup's worth, and the
  // outline pixels it listed (TS_BINDING_OUTLINE).
  uvec4 outline_dispatch;
  uint outline_pixels;
  // The (tile, triangle) pairs of the pixel boxes of the large triangles (boxes over the
  // small-triangle area), counted by setup: what the pass that rasterizes and shades small
  // frames in one tests every pixel of a tile against, without depth rejection. The next frame
  // takes that pass only while they are few (renderer.cpp's rasterizes_and_shades_in_one_pass).
  uint large_box_tiles;
  uvec2 pad_outline1;  // std430 rounds the array stride to 16 bytes
  // Shading by tiles, batch 0's slot (list_tiles.comp): VkDispatchIndirectCommand (xyz) of the
  // shading pass over the drawn tiles and of its background dispatch over the others, x a row
  // of the tile grid's workgroups, y raised as the lists reach into a new row; and the lists'
  // lengths in tiles.
  uvec4 shade_dispatch;
  uvec4 background_dispatch;
  uint drawn_tiles;
  uint background_tiles;
  uvec2 pad_shade_tiles;  // std430 rounds the array stride to 16 bytes
};

#ifdef __cplusplus
static_assert(sizeof(GpuVertex) == 48);
static_assert(offsetof(GpuVertex, normal_v) == 16);
static_assert(offsetof(GpuVertex, tangent) == 32);
static_assert(sizeof(GpuObject) == 160);
static_assert(sizeof(GpuObject) == TS_OBJECT_WORDS * 4);
static_assert(offsetof(GpuObject, normal_matrix) == 64);
static_assert(offsetof(GpuObject, first_index) == 128);
static_assert(offsetof(GpuObject, first_triangle) == 144);
static_assert(offsetof(GpuObject, mirrored) == 148);
static_assert(offsetof(GpuObject, double_sided) == 152);
static_assert(offsetof(GpuObject, mesh) == 156);
static_assert(sizeof(GpuLodLevel) == 16);
static_assert(offsetof(GpuLodLevel, error) == 12);
static_assert(sizeof(GpuLodMesh) == 32);
static_assert(offsetof(GpuLodMesh, radius) == 12);
static_assert(offsetof(GpuLodMesh, first_level) == 16);
static_assert(sizeof(GpuMaterial) == 80);
static_assert(offsetof(GpuMaterial, metallic) == 12);
static_assert(offsetof(GpuMaterial, emissive) == 16);
static_assert(offsetof(GpuMaterial, roughness) == 28);
static_assert(offsetof(GpuMaterial, occlusion) == 32);
static_assert(offsetof(GpuMaterial, double_sided) == 40);
static_assert(offsetof(GpuMaterial, emissive_map) == 44);
static_assert(offsetof(GpuMaterial, base_color_map) == 48);
static_assert(offsetof(GpuMaterial, occlusion_map) == 60);
static_assert(offsetof(GpuMaterial, uv1_maps) == 64);
static_assert(sizeof(GpuTexture) == 80);
static_assert(offsetof(GpuTexture, levels) == 8);
static_assert(offsetof(GpuTexture, wrap) == 12);
static_assert(offsetof(GpuTexture, level_offset) == 16);
static_assert(sizeof(GpuLight) == 80);
static_assert(offsetof(GpuLight, kind) == 12);
static_assert(offsetof(GpuLight, direction) == 16);
static_assert(offsetof(GpuLight, falloff) == 28);
static_assert(offsetof(GpuLight, radiance) == 32);
static_assert(offsetof(GpuLight, inv_range4) == 44);
static_assert(offsetof(GpuLight, attenuation) == 48);
static_assert(offsetof(GpuLight, cone_scale) == 60);
static_assert(offsetof(GpuLight, cone_offset) == 64);
static_assert(sizeof(GpuFrame) == 288);
static_assert(offsetof(GpuFrame, camera_rays) == 64);
static_assert(offsetof(GpuFrame, camera_position) == 128);
static_assert(offsetof(GpuFrame, near_plane) == 140);
static_assert(offsetof(GpuFrame, background) == 144);
static_assert(offsetof(GpuFrame, exposure_scale) == 156);
static_assert(offsetof(GpuFrame, ambient) == 160);
static_assert(offsetof(GpuFrame, view) == 172);
static_assert(offsetof(GpuFrame, guard_band) == 176);
static_assert(offsetof(GpuFrame, tonemap) == 184);
static_assert(offsetof(GpuFrame, cull) == 188);
static_assert(offsetof(GpuFrame, image_size) == 192);
static_assert(offsetof(GpuFrame, tiles) == 200);
static_assert(offsetof(GpuFrame, object_count) == 208);
static_assert(offsetof(GpuFrame, raster_capacity) == 220);
static_assert(offsetof(GpuFrame, tile_entry_capacity) == 224);
static_assert(offsetof(GpuFrame, env_levels) == 240);
static_assert(offsetof(GpuFrame, anisotropy) == 244);
static_assert(offsetof(GpuFrame, lod_scale) == 248);
static_assert(offsetof(GpuFrame, batch_triangles) == 256);
static_assert(offsetof(GpuFrame, hdr_max) == 260);
static_assert(offsetof(GpuFrame, resolve_in_shading) == 268);
static_assert(offsetof(GpuFrame, tile_list_stride) == 272);
static_assert(offsetof(GpuFrame, reset_visibility) == 276);
static_assert(offsetof(GpuFrame, texels_address) == 280);
static_assert(sizeof(GpuBrdfSample) == 64);
static_assert(offsetof(GpuBrdfSample, roughness) == 28);
static_assert(offsetof(GpuBrdfSample, base_color) == 48);
static_assert(sizeof(GpuBatch) == 16);
static_assert(sizeof(GpuEnvPass) == sizeof(GpuBatch));
static_assert(sizeof(GpuRasterTri) == 48);
static_assert(sizeof(GpuOutlinePixel) == 16);
static_assert(sizeof(GpuBackground) == 32);
static_assert(TS_DFG_BYTES == 2 * (TS_DFG_SIZE + 1) * TS_DFG_SIZE * sizeof(vec4));
static_assert(offsetof(GpuBackground, display) == 16);
static_assert(offsetof(GpuOutlinePixel, pixel) == 12);
static_assert(sizeof(GpuCounters) == 224);
static_assert(sizeof(GpuCounters) == TS_COUNTERS_WORDS * 8);
static_assert(offsetof(GpuCounters, small_counts) == TS_SMALL_COUNTS_WORD * 8);
static_assert(offsetof(GpuCounters, shade_dispatch) == 176);
static_assert(offsetof(GpuCounters, background_dispatch) == 192);
static_assert(offsetof(GpuCounters, drawn_tiles) == 208);
static_assert(offsetof(GpuCounters, outline_dispatch) == 144);
static_assert(offsetof(GpuCounters, outline_pixels) == 160);
static_assert(offsetof(GpuCounters, clip_dispatch) == 128);
static_assert(offsetof(GpuCounters, rejected_entries) == 112);
static_assert(offsetof(GpuCounters, tile_list_max) == 120);
static_assert(offsetof(GpuCounters, lod_triangles) == 92);
static_assert(offsetof(GpuCounters, lod_total) == 124);
static_assert(offsetof(GpuCounters, setup_dispatch) == 96);
static_assert(offsetof(GpuCounters, big_dispatch) == 16);
static_assert(offsetof(GpuCounters, tiles_dispatch) == 32);
static_assert(offsetof(GpuCounters, raster_tris) == 48);
static_assert(offsetof(GpuCounters, small_counts) == 56);
static_assert(offsetof(GpuCounters, clipped) == 84);
static_assert(offsetof(GpuCounters, clip_list) == 88);
}  // namespace tessera::gpu
#endif

#endif  // TESSERA_GPU_TYPES_H
