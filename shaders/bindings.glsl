// The one descriptor set every pass uses (bindings from shared/gpu_types.h).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_EXT_buffer_reference : require

#include "shared/gpu_types.h"

layout(set = 0, binding = TS_BINDING_FRAME, std140) uniform FrameBlock { GpuFrame frame; };
layout(set = 0, binding = TS_BINDING_VERTICES, std430) readonly buffer Vertices { GpuVertex vertices[]; };
// Uv set 1 of every vertex, indexed as `vertices`; holds data only when a material reads it.
layout(set = 0, binding = TS_BINDING_UV1, std430) readonly buffer Uv1 { vec2 uv1s[]; };
layout(set = 0, binding = TS_BINDING_INDICES, std430) readonly buffer Indices { uint indices[]; };
layout(set = 0, binding = TS_BINDING_ADJACENCY, std430) readonly buffer Adjacency { uint adjacency[]; };
// The level-of-detail passes (which define TS_LOD_PASS) rewrite the objects' levels each frame.
#ifdef TS_LOD_PASS
layout(set = 0, binding = TS_BINDING_OBJECTS, std430) buffer Objects { GpuObject objects[]; };
#else
layout(set = 0, binding = TS_BINDING_OBJECTS, std430) readonly buffer Objects { GpuObject objects[]; };
#endif
// The same buffer as words: the group table after the objects (TS_TRIANGLE_GROUP_BITS).
layout(set = 0, binding = TS_BINDING_OBJECTS, std430) readonly buffer ObjectWords { uint object_words[]; };
// Entry `group` of the group table: the object slot that holds triangle-instance id
// group * TS_TRIANGLE_GROUP. The words' index stays below 2^32: the renderer holds fewer than
// 2^32 / TS_OBJECT_WORDS objects, as the buffer's size does.
uint group_object(uint group) {
  return object_words[frame.object_count * TS_OBJECT_WORDS + group];
}
// Written by the object_clip pass (which defines TS_OBJECT_CLIP_PASS), read by setup and after.
#ifdef TS_OBJECT_CLIP_PASS
layout(set = 0, binding = TS_BINDING_OBJECT_CLIP, std430) writeonly buffer ObjectClip { mat4 object_clip[]; };
#else
layout(set = 0, binding = TS_BINDING_OBJECT_CLIP, std430) readonly buffer ObjectClip { mat4 object_clip[]; };
#endif
layout(set = 0, binding = TS_BINDING_MATERIALS, std430) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = TS_BINDING_LIGHTS, std430) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = TS_BINDING_RASTER_TRIS, std430) buffer RasterTris { GpuRasterTri raster_tris[]; };
layout(set = 0, binding = TS_BINDING_SMALL_LIST, std430) buffer SmallList { uint small_list[]; };
layout(set = 0, binding = TS_BINDING_BIG_LIST, std430) buffer BigList { uvec2 big_list[]; };  // (raster triangle, tile block)
layout(set = 0, binding = TS_BINDING_TILE_COUNTS, std430) buffer TileCounts { uint tile_counts[]; };
layout(set = 0, binding = TS_BINDING_TILE_OFFSETS, std430) buffer TileOffsets { uint tile_offsets[]; };
layout(set = 0, binding = TS_BINDING_TILE_CURSORS, std430) buffer TileCursors { uint tile_cursors[]; };
layout(set = 0, binding = TS_BINDING_TILE_ENTRIES, std430) buffer TileEntries { uint tile_entries[]; };
layout(set = 0, binding = TS_BINDING_COUNTERS, std430) buffer CountersBlock { GpuCounters counters[]; };
layout(set = 0, binding = TS_BINDING_VISIBILITY, std430) buffer Visibility { uint64_t visibility[]; };
layout(set = 0, binding = TS_BINDING_COVERAGE, std430) buffer Coverage { uint coverage[]; };
layout(set = 0, binding = TS_BINDING_CLIP_LIST, std430) buffer ClipList { uint clip_list[]; };
layout(set = 0, binding = TS_BINDING_TILE_FAR, std430) buffer TileFar { uint tile_far[]; };
layout(set = 0, binding = TS_BINDING_OUTLINE, std430) buffer Outline { GpuOutlinePixel outline[]; };
layout(set = 0, binding = TS_BINDING_TILE_DRAWN, std430) buffer TileDrawn { uint tile_drawn[]; };
layout(set = 0, binding = TS_BINDING_SHADE_TILES, std430) buffer ShadeTiles { uint shade_tiles[]; };
// DFG tables (shaders/dfg.comp): classic then filament, each TS_DFG_SIZE^2, row = roughness.
layout(set = 0, binding = TS_BINDING_DFG, std430) buffer Dfg { vec4 dfg[]; };
// After them, in the same buffer: the background's colours (GpuBackground).
layout(set = 0, binding = TS_BINDING_DFG, std430) buffer Background {
  layout(offset = TS_BACKGROUND_OFFSET) GpuBackground background_colours;
};
// RGBA16F or RGBA32F (FrameSettings::hdr_format), declared without a format so that one SPIR-V
// module writes either (shaderStorageImageWriteWithoutFormat, which the context requires; the
// stores clamp to GpuFrame.hdr_max first). Reading without a format is optional in Vulkan and
// lavapipe lacks it, so the resolve pass reads the same image through hdr_texture (texelFetch:
// exact texels, no filtering).
layout(set = 0, binding = TS_BINDING_HDR_IMAGE) writeonly uniform image2D hdr_image;
layout(set = 0, binding = TS_BINDING_HDR_TEXTURE) uniform sampler2D hdr_texture;
layout(set = 0, binding = TS_BINDING_LDR_IMAGE, rgba8) uniform image2D ldr_image;
// Texture maps: mip chains packed as fp16 RGBA (two halves per uint), filtered by hand
// (texture.glsl), read at GpuFrame.texels_address: a buffer reference, not a descriptor, so that
// their size is not capped by maxStorageBufferRange. A texel is loaded as one 64-bit word:
// llvmpipe (Mesa 22.3) loads a global pointer's channels lane by lane, and a uvec2 made the
// textured scene's shading pass about 15 % slower than the storage buffer it replaced.
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer TexelLevel { uint64_t texels[]; };
layout(set = 0, binding = TS_BINDING_TEXTURES, std430) readonly buffer Textures { GpuTexture textures[]; };
// The environment (a 1x1 black placeholder when the scene has none).
layout(set = 0, binding = TS_BINDING_ENV_MAP) uniform sampler2D env_map;
layout(set = 0, binding = TS_BINDING_ENV_SPECULAR) uniform samplerCube env_specular;
// Where env_prefilter.comp writes the cube's levels (fp16 RGBA, level after level, face after
// face) before they are copied into env_specular: lavapipe cannot index storage-image arrays.
layout(set = 0, binding = TS_BINDING_ENV_LEVELS, std430) buffer EnvTexels { uvec2 env_texels[]; };
layout(set = 0, binding = TS_BINDING_ENV_IRRADIANCE, std430) buffer EnvIrradiance { vec4 env_irradiance[9]; };

#ifdef TS_ENV_PASS
layout(push_constant) uniform EnvPassBlock { GpuEnvPass env_pass; };
#else
layout(push_constant) uniform BatchBlock { GpuBatch batch; };
#endif

// Last object whose first triangle-instance id is <= `tri` (objects are sorted by it).
uint find_object(uint tri) {
  uint lo = 0u;
  uint hi = frame.object_count;
  while (hi - lo > 1u) {
    uint mid = (lo + hi) >> 1;
    if (objects[mid].first_triangle <= tri) lo = mid; else hi = mid;
  }
  return lo;
}

// Vertex indices (into `vertices`) of triangle-instance `tri` of object `o`.
uvec3 triangle_vertices(GpuObject o, uint tri) {
  uint base = o.first_index + 3u * (tri - o.first_triangle);
  return uvec3(indices[base], indices[base + 1u], indices[base + 2u]) + o.base_vertex;
}

const float PI_BINDINGS = 3.14159265358979323846;

// Equirectangular coordinates of unit direction d (core/environment.h has the convention):
// u around y starting from -z, v from +y (0) down to -y (1).
vec2 equirect_uv(vec3 d) {
  return vec2(0.5 + atan(d.x, -d.z) / (2.0 * PI_BINDINGS), acos(clamp(d.y, -1.0, 1.0)) / PI_BINDINGS);
}

// Row-major index of a pixel in the visibility and coverage buffers.
uint pixel_index(ivec2 pixel) {
  return uint(pixel.y) * frame.image_size.x + uint(pixel.x);
}

// The factor the shading stages multiply radiance by before it meets the fp16 HDR image
// (pre-exposure: Lagarde & de Rousiers 2014, "Moving Frostbite to Physically Based Rendering",
// 5.1; Filament does the same): the camera's exposure 2^EV, so that scenes in physical units
// (sunlight ~1e5 W/m^2) keep their exposed range inside fp16. Renderer::read_hdr divides it back
// out. Debug views are written as they are.
float pre_exposure() {
  return frame.view == TS_VIEW_SHADED ? frame.exposure_scale : 1.0;
}
