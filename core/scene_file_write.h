#pragma once
// Writing a Scene as Tessera's JSON scene format (docs/scene-format.md, "Saving"), so that
// load_scene_file gives back the same Scene, every field bit for bit.

#include <string>

#include "core/scene.h"
#include "core/scene_file.h"

namespace tessera {

/// Writes `scene` (which must pass validate_scene; throws its Error otherwise) to the scene
/// file `path`, with the "render" block `render` if given. What each part becomes:
/// - meshes equal to a built-in shape (make_uv_sphere, make_icosphere, make_cube, make_plane)
///   are written as that shape; others inline as "triangles" (with their tangents, if any);
/// - textures as lossless RGBA8 PNG files next to the scene, PATH_STEM-texture-I.png, with
///   their srgb flag (a Scene keeps no texture source, so procedural and imported maps alike);
/// - the environment as "sky" or "uniform" when it equals that map, otherwise as the
///   32-bit float PFM PATH_STEM-environment.pfm (RGB bit-exact; alpha, which is unused, reads
///   back as 1);
/// - objects with a column-major "matrix"; names are generated (material3, mesh0, ...).
/// Floats are written as the shortest decimal that reads back as the same float (unit normals
/// and light directions are then kept by the reader as written). Angles are written in
/// degrees, as the float whose glm::radians (the reader's conversion, in single precision)
/// gives the stored radians; where no float does (single-precision degrees cannot reach
/// every radian value), the nearest comes back, within an ulp or two. Angles that came from
/// degrees (files, and editors working in degrees) always come back exactly.
/// The scene file is written to PATH.tmp and renamed over `path`, so a failed save leaves an
/// existing file as it was, and removes the texture and environment files it created. Throws
/// Error naming the path and the reason (unwritable_reason, or the OS error) when a file
/// cannot be written, and naming the field when a value is outside what the format accepts
/// (e.g. roughness outside [0, 1], a field of view over 179 degrees) or the file would exceed
/// the reader's 64 MiB.
/// A non-empty `description` is written as the file's "description".
void save_scene_file(const Scene& scene, const std::string& path,
                     const RenderDefaults* render = nullptr, const std::string& description = {});

}  // namespace tessera
