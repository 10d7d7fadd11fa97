#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Level of detail, first of three passes (docs/architecture.md, "Level of detail"): one thread
// per object chooses the coarsest level of its mesh's chain whose error projects to at most
// --lod-error pixels (select_lod_level in core/lod.h states it in double), writes the level's
// triangles into the object, and sums its workgroup's triangle counts for lod_scan.
#define TS_LOD_PASS
#include "bindings.glsl"

layout(local_size_x = TS_LOD_GROUP_SIZE) in;

layout(set = 0, binding = TS_BINDING_LOD_LEVELS, std430) readonly buffer LodLevels { GpuLodLevel lod_levels[]; };
layout(set = 0, binding = TS_BINDING_LOD_MESHES, std430) readonly buffer LodMeshes { GpuLodMesh lod_meshes[]; };
layout(set = 0, binding = TS_BINDING_LOD_SUMS, std430) writeonly buffer LodSums { uint lod_sums[]; };
// VkDrawIndexedIndirectCommand per object, for the hardware baseline (TS_BATCH_LOD_DRAWS).
layout(set = 0, binding = TS_BINDING_LOD_DRAWS, std430) writeonly buffer LodDraws { uint lod_draws[]; };

shared uint group_triangles;

// An object-space error e moves no visible point of the object by more than
// e * scale * pixels_per_unit / depth pixels (core/lod.cpp derives pixels_per_unit), for depth
// the view depth of the nearest point of its bounding sphere, clamped to the near plane (what
// is nearer is clipped). lod_scale divides by the bound, so a level passes where
// error * scale * lod_scale <= depth.
uint choose_level(GpuObject o, GpuLodMesh m) {
  vec3 centre = (o.model * vec4(m.centre, 1.0)).xyz;
  float scale = max(max(length(o.model[0].xyz), length(o.model[1].xyz)), length(o.model[2].xyz));
  float depth = (frame.view_proj * vec4(centre, 1.0)).w;  // clip w: the view depth
  float near_side = max(depth - m.radius * scale, frame.near_plane);
  float per_unit = scale * frame.lod_scale;
  for (uint l = m.level_count - 1u; l > 0u; --l) {
    if (lod_levels[m.first_level + l].error * per_unit <= near_side) return l;
  }
  return 0u;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint triangles = 0u;
  if (i < frame.object_count) {
    GpuObject o = objects[i];
    GpuLodMesh m = lod_meshes[o.mesh];
    GpuLodLevel level = lod_levels[m.first_level + choose_level(o, m)];
    objects[i].first_index = level.first_index;
    objects[i].base_vertex = level.base_vertex;
    objects[i].triangle_count = level.triangle_count;
    triangles = level.triangle_count;
    if ((batch.flags & TS_BATCH_LOD_DRAWS) != 0u) {
      // index count, instance count, first index, vertex offset, first instance (the slot)
      lod_draws[5u * i] = 3u * level.triangle_count;
      lod_draws[5u * i + 1u] = 1u;
      lod_draws[5u * i + 2u] = level.first_index;
      lod_draws[5u * i + 3u] = level.base_vertex;
      lod_draws[5u * i + 4u] = i;
    }
  }
  if (gl_LocalInvocationIndex == 0u) group_triangles = 0u;
  barrier();
  // An integer sum: the same whatever order the subgroups add in.
  uint sum = subgroupAdd(triangles);
  if (subgroupElect()) atomicAdd(group_triangles, sum);
  barrier();
  if (gl_LocalInvocationIndex == 0u) lod_sums[gl_WorkGroupID.x] = group_triangles;
}
