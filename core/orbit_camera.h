#pragma once
// The interactive camera of `tessera view`: a camera orbiting a target point, driven by mouse
// and keyboard, and converted to the tessera::Camera every renderer takes, so that the window
// and `tessera render` see through the same Camera. Plain data and free functions; no window.
//
// Geometry: the eye sits at target + distance * orbit_offset(yaw, pitch), with
//   orbit_offset = cos(pitch) (sin(yaw) r + cos(yaw) b) + sin(pitch) u
// where u = normalize(up) and (r, u, b) is the orbit basis of u (orbit_basis): for the usual
// up = +y, r = +x and b = +z, so yaw 0, pitch 0 puts the eye on +z looking down -z (the default
// Camera), positive yaw turns the eye toward +x and positive pitch raises it above the target.
// Units: metres and radians; pixel arguments are window pixels (x right, y down).

#include <cstdint>
#include <numbers>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace tessera {

/// Pitch is kept within +-kMaxOrbitPitch by orbit(): at +-pi/2 the view direction would be
/// parallel to `up`, where the view's right axis cross(forward, up) vanishes (the camera is
/// undefined and validate_scene refuses it) and, close to it, yaw spins the image about the
/// view axis. 89 degrees keeps the right axis well conditioned.
inline constexpr float kMaxOrbitPitch = glm::radians(89.0f);
/// orbit distance limits (m) kept by zoom() and frame_scene(): > 0 so the eye never reaches
/// the target, and small enough that positions stay far inside kMaxSceneCoordinate (1e15 m).
/// Framing fits spheres of radius 1e-7 sin(fov / 2) to 1e14 sin(fov / 2): at 45 degrees from
/// 38 nm to 3.8e13 m (limits of 1e-4 and 1e9 m left a model 10 um across small in the view and
/// put the camera inside one of radius 1e9 m, which then drew nothing).
inline constexpr float kMinOrbitDistance = 1e-7f;
inline constexpr float kMaxOrbitDistance = 1e14f;

struct OrbitCamera {
  glm::vec3 target{0.0f};
  float distance = 5.0f;  // m from target to eye, in [kMinOrbitDistance, kMaxOrbitDistance]
  float yaw = 0.0f;       // radians about up, see above
  float pitch = 0.0f;     // radians above the plane through the target orthogonal to up
  glm::vec3 up{0.0f, 1.0f, 0.0f};            // world up: non-zero, copied to Camera::up as is
  float vertical_fov = glm::radians(45.0f);  // full angle, as Camera::vertical_fov
  float near_plane = 0.1f;                   // m, as Camera::near_plane (there is no far plane)

  // Sensitivities.
  float orbit_radians_per_height =
      std::numbers::pi_v<float>;     // turn for a drag over the whole height
  float zoom_ratio_per_step = 0.9f;  // distance factor per wheel step toward the target, (0, 1)
  float fly_distances_per_second = 1.0f;  // fly speed, in orbit distances per second
};

/// Window size in pixels; both > 0 (a minimised window has none: do not call then).
struct Viewport {
  uint32_t width = 0, height = 0;
};

/// The orthonormal basis (right, up, back) of an orbit around `up` (non-zero): up normalized;
/// back is +z made orthogonal to it (+x when up is along z), right = cross(up, back).
struct OrbitBasis {
  glm::vec3 right, up, back;
};
OrbitBasis orbit_basis(glm::vec3 up);

/// The Camera the renderers take: position = target + distance * orbit_offset, target, up,
/// vertical_fov and near_plane copied. The window and screenshots both render this Camera.
Camera to_camera(const OrbitCamera& orbit);

/// The orbit camera that gives back `camera` (which must pass validate_scene's camera checks):
/// target, up, fov and near copied, distance = |position - target|, yaw and pitch from the
/// offset (pitch not clamped, so to_camera(from_camera(c)) equals c up to float rounding in
/// the position). Sensitivities are taken from `settings`.
OrbitCamera from_camera(const Camera& camera, const OrbitCamera& settings = {});

/// Left drag by (dx, dy) pixels: yaw -= dx * s and pitch += dy * s with
/// s = orbit_radians_per_height / viewport.height, pitch then clamped to +-kMaxOrbitPitch.
/// Dragging right swings the eye toward -r (the scene turns with the cursor), dragging down
/// raises the eye. Throws Error for an empty viewport.
void orbit(OrbitCamera& camera, float dx_pixels, float dy_pixels, Viewport viewport);

/// Middle (or shift) drag by (dx, dy) pixels: moves the target (and the eye with it) in the
/// view plane so that a point at the target's depth stays under the cursor: one pixel is
/// 2 distance tan(vertical_fov / 2) / viewport.height metres at that depth; the target moves
/// by -dx of those along the view's right axis and +dy along its up axis. Throws Error for an
/// empty viewport.
void pan(OrbitCamera& camera, float dx_pixels, float dy_pixels, Viewport viewport);

/// Wheel by `steps` notches (positive: toward the target): distance *= zoom_ratio_per_step ^
/// steps, clamped to [kMinOrbitDistance, kMaxOrbitDistance]. The target stays.
void zoom(OrbitCamera& camera, float steps);

/// Keys held for fly(): W forward, S back (along the view direction), A left, D right (the
/// view's right axis), Q down, E up (along world up).
struct FlyKeys {
  bool forward = false, back = false, left = false, right = false, down = false, up = false;
};

/// Moves target and eye together for `seconds` (>= 0) with the held keys: the sum of the
/// keys' unit directions, normalized (so diagonals are not faster), times
/// fly_distances_per_second * distance * seconds metres. Opposite keys cancel. Throws Error
/// for negative or non-finite seconds.
void fly(OrbitCamera& camera, const FlyKeys& keys, float seconds);

/// A sphere enclosing every vertex of every object of `scene` in world space: each mesh's
/// sphere (centre of its vertex bounding box, radius the farthest vertex from it) placed by
/// the object's transform (radius times the transform's largest axis scale), then the
/// smallest sphere about the centre of those spheres' bounding box that holds them all.
/// Radius < 0 when no object has a vertex.
struct BoundingSphere {
  glm::vec3 centre{0.0f};
  float radius = -1.0f;  // m
};
BoundingSphere scene_bounds(const Scene& scene);

/// The sphere of `object` (an index into scene.objects; throws Error naming it otherwise) as
/// scene_bounds places each object's: radius < 0 if its mesh has no vertex.
BoundingSphere object_bounds(const Scene& scene, uint32_t object);

/// Keeps yaw, pitch and up, moves the target to `bounds.centre` and sets the distance so that
/// the sphere just fits the narrower of the two fields of view: distance = radius /
/// sin(min(vertical_fov, horizontal_fov) / 2), horizontal_fov = 2 atan(tan(vertical_fov / 2)
/// aspect), clamped to [kMinOrbitDistance, kMaxOrbitDistance]. The near plane becomes
/// min(`preferred_near`, (distance - radius) / 2), so that it never cuts into the sphere (a
/// model smaller than the preferred near distance would vanish), and `preferred_near` again
/// where there is room (framing a large scene after a small one); `preferred_near` where the
/// distance was clamped. `aspect` = width / height > 0 and `preferred_near` > 0 (throws Error
/// otherwise). Returns false, changing nothing, if the radius is < 0.
bool frame_sphere(OrbitCamera& camera, const BoundingSphere& bounds, float aspect,
                  float preferred_near);

/// F key: frame_sphere of scene_bounds. Returns false, changing nothing, if the scene has no
/// vertex.
bool frame_scene(OrbitCamera& camera, const Scene& scene, float aspect, float preferred_near);

/// The camera of a model file given as a scene (`tessera render --scene model.glb`): the
/// default Camera's view (from +z down -z, y up, 45 degrees; a glTF model's front) moved by
/// frame_scene at `aspect`, with the default near plane (0.1 m) preferred: min(0.1 m, (distance
/// - radius) / 2), so that a model smaller than the default near distance is not clipped away.
/// The default Camera when the scene has no vertex.
Camera framed_camera(const Scene& scene, float aspect);

}  // namespace tessera
