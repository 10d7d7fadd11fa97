#pragma once
// Procedural meshes. Every mesh is closed where its shape is (spheres, cube), winds its
// triangles counter-clockwise seen from outside, and has unit normals and uvs. Vertices that
// meet at a seam are bit-identical copies, so shared edges snap to the same fixed-point
// coordinates and the rasterizer leaves no cracks. Tangents for normal maps are generated
// from the uvs (generate_tangents).

#include <cstdint>

#include "core/scene.h"

namespace tessera {

/// Unit sphere (radius 1, centre at the origin) as `segments` slices around the y axis and
/// `rings` stacks from pole to pole. Requires segments >= 3 and rings >= 2 (throws Error).
/// Triangle count: 2 * segments * (rings - 1). Marks the mesh as the unit sphere
/// (Mesh::analytic_sphere). Seen from afar along z (segments even), its outline is the
/// regular 2 * rings-gon of the meridians at u = 0 and 1/2, inscribed in the sphere's: with
/// rings = segments / 2 its chord error (the largest gap to the true outline) is
/// 1 - cos(pi / segments).
Mesh make_uv_sphere(uint32_t segments, uint32_t rings);

/// Unit icosphere: an icosahedron subdivided `level` times (0..8, throws Error otherwise),
/// 20 * 4^level triangles, vertices shared between triangles. Marked as the unit sphere
/// (Mesh::analytic_sphere) with u = 0.5 at +x, as its uvs are.
Mesh make_icosphere(uint32_t level);

/// Cube from -1 to 1 on each axis, 12 triangles, flat normals per face.
Mesh make_cube();

/// Plane from -1 to 1 in x and y at z = 0, facing +z, split into `nx` by `ny` quads
/// (2 * nx * ny triangles). Requires nx, ny >= 1 (throws Error).
Mesh make_plane(uint32_t nx, uint32_t ny);

/// Which of the builders above makes `mesh` bit for bit, and with what: the scene file writer
/// saves such a mesh as that shape, and `tessera tradeoff` names a scene's spheres by it.
struct MeshShape {
  enum class Kind { none, uv_sphere, icosphere, cube, plane };
  Kind kind = Kind::none;
  uint32_t a = 0;  // uv_sphere: segments; icosphere: level; plane: nx
  uint32_t b = 0;  // uv_sphere: rings; plane: ny
};
MeshShape shape_of(const Mesh& mesh);

}  // namespace tessera
