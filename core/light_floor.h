#pragma once
// Lights nearer an object than the shading's distance floor: point and spot lights with the
// inverse-square falloff divide by max(d^2, TS_MIN_LIGHT_DISTANCE_SQUARED), so a surface closer
// than 1 cm receives what it would at 1 cm, less than 1/d^2. A light placed on a surface meets
// the floor on purpose; a scene modelled below centimetre scale (micrometre objects with lights
// micrometres away) meets it everywhere and renders nearly black. A valid scene either way,
// which the commands only note (host/scene_source.h, near_lights_note).

#include <glm/glm.hpp>

#include "core/clip_prediction.h"
#include "core/scene.h"

namespace tessera {

/// The distance in m below which the shading floors a light's distance (the square root of
/// TS_MIN_LIGHT_DISTANCE_SQUARED).
inline constexpr double kLightDistanceFloor = 0.01;

/// Distance from `point` to `box` placed by `world_from_object` (any affine transform: the box
/// becomes a parallelepiped, whose faces are the images of the box's): 0 inside it. An empty
/// box (min > max): infinity.
double distance_to_placed_box(const MeshBox& box, const glm::dmat4& world_from_object,
                              glm::dvec3 point);

/// The point and spot lights of the inverse-square falloff that lie nearer than
/// kLightDistanceFloor to some object's triangles (placed by its transform), leaving out
/// objects whose mesh has no triangles and, for a light with a range, objects beyond it (it
/// does not reach them). Classic lights floor their denominator, not the distance, and
/// directional lights have none: neither is counted.
struct NearLights {
  size_t count = 0;       // such lights; 0: none, and the rest is unset
  size_t light = 0;       // the first of them, by index into Scene::lights
  size_t object = 0;      // the object nearest to it (the first of equals), into Scene::objects
  double distance = 0.0;  // from that light to that object's surface (or box: `exact`), in m
  /// False where the triangles to measure ran past a budget (2^24 in all): some distances are
  /// then to the object's placed box (mesh_box and its transform), which its surface may lie
  /// well beyond (a light inside a room's box), and count such lights too.
  bool exact = true;
};
/// Assumes a scene validate_scene accepts. O(lights x objects), each pair a test of the
/// object's world-space bounds, then of its placed box, and only where that lies within the
/// floor, of its triangles.
NearLights lights_within_floor(const Scene& scene);

}  // namespace tessera
