#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Level of detail, third pass: one thread per object, as the lod pass's workgroups: each
// object's first triangle-instance id is its workgroup's offset (lod_scan) plus the triangles
// of the objects before it in the workgroup, so ids stay consecutive in the objects' canonical
// order and setup and shading find an object by binary search as without level of detail.
#define TS_LOD_PASS
#include "bindings.glsl"

layout(local_size_x = TS_LOD_GROUP_SIZE) in;

layout(set = 0, binding = TS_BINDING_LOD_SUMS, std430) readonly buffer LodSums { uint lod_sums[]; };

shared uint subgroup_totals[TS_LOD_GROUP_SIZE];

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint triangles = i < frame.object_count ? objects[i].triangle_count : 0u;
  uint within = subgroupExclusiveAdd(triangles);
  if (gl_SubgroupInvocationID == gl_SubgroupSize - 1u) subgroup_totals[gl_SubgroupID] = within + triangles;
  barrier();
  uint before = lod_sums[gl_WorkGroupID.x];
  for (uint s = 0u; s < gl_SubgroupID; ++s) before += subgroup_totals[s];
  if (i < frame.object_count) objects[i].first_triangle = before + within;
}
