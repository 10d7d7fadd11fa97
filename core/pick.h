#pragma once
// Picking: which object a pixel of the visibility buffer shows. The buffer already knows it
// (each key holds the triangle-instance id of the nearest triangle), so no ray is cast.

#include <cstdint>
#include <optional>

#include "core/scene.h"
#include "shaders/shared/constants.h"

namespace tessera {

/// Visibility-buffer value of a pixel no triangle covers (TS_VIS_EMPTY: all bits set).
inline constexpr uint64_t kEmptyVisibilityKey = TS_VIS_EMPTY;

/// The triangle-instance id in a 64-bit visibility key (shaders/raster_common.glsl,
/// visibility_key: the bits of the inverted depth above, the id in the low 32 bits), or
/// nullopt for kEmptyVisibilityKey (the background).
std::optional<uint32_t> triangle_of_key(uint64_t key);

/// Index into Scene::objects of the object that triangle instance `triangle_id` belongs to,
/// under `numbering` (number_objects of the scene that was rendered). Throws Error if
/// triangle_id >= numbering.triangle_count (a key from another scene's frame).
uint32_t object_of_triangle(const ObjectNumbering& numbering, uint64_t triangle_id);

/// The object a visibility key shows: nullopt for the background, otherwise as
/// object_of_triangle (and its Error).
std::optional<uint32_t> pick_object(const ObjectNumbering& numbering, uint64_t key);

}  // namespace tessera
