#pragma once
// Camera moves of `tessera view` driven by the mouse. A stand-in until core/orbit_camera.h
// (the editing branch) lands; then these forward to it.

#include "core/scene.h"

namespace tessera {

/// Radians the camera turns per window pixel dragged.
inline constexpr float kOrbitRadiansPerPixel = 0.005f;

/// Turns `camera.position` about `camera.target`: `dx` pixels right turn it about the world
/// axis `camera.up` by -dx * kOrbitRadiansPerPixel (the scene seems to turn with the pointer),
/// `dy` pixels down about the camera's right axis by -dy * kOrbitRadiansPerPixel, stopping
/// short of the poles.
void orbit_camera(Camera& camera, float dx, float dy);

/// Moves position and target together by `dx`, `dy` pixels in the view plane at the target's
/// distance, for a viewport `viewport_height` pixels high: the point under the pointer stays
/// under it.
void pan_camera(Camera& camera, float dx, float dy, float viewport_height);

/// Moves the position toward the target by 10 % of their distance per notch (away for
/// negative `notches`), never closer than the near plane.
void zoom_camera(Camera& camera, float notches);

}  // namespace tessera
