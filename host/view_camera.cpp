#include "host/view_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace tessera {
namespace {

// How close to straight up or down (radians) an orbit may turn the view: at the pole the
// view direction is parallel to `up` and the view matrix is undefined.
constexpr float kPoleMargin = 0.01f;

glm::vec3 rotate(const glm::vec3& v, float angle, const glm::vec3& axis) {
  return glm::vec3(glm::rotate(glm::mat4(1.0f), angle, axis) * glm::vec4(v, 0.0f));
}

}  // namespace

void orbit_camera(Camera& camera, float dx, float dy) {
  const glm::vec3 up = glm::normalize(camera.up);
  glm::vec3 offset = camera.position - camera.target;
  offset = rotate(offset, -dx * kOrbitRadiansPerPixel, up);
  const float distance = glm::length(offset);
  const float elevation = std::asin(std::clamp(glm::dot(offset, up) / distance, -1.0f, 1.0f));
  const float limit = glm::half_pi<float>() - kPoleMargin;
  const float pitch = std::clamp(elevation - dy * kOrbitRadiansPerPixel, -limit, limit) - elevation;
  if (pitch != 0.0f) {
    const glm::vec3 right = glm::normalize(glm::cross(up, offset));
    offset = rotate(offset, -pitch, right);
  }
  camera.position = camera.target + offset;
}

void pan_camera(Camera& camera, float dx, float dy, float viewport_height) {
  const glm::vec3 forward = camera.target - camera.position;
  const float distance = glm::length(forward);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::vec3 up = glm::normalize(glm::cross(right, forward));
  // World units per pixel at the target's distance.
  const float scale =
      2.0f * distance * std::tan(camera.vertical_fov * 0.5f) / std::max(viewport_height, 1.0f);
  const glm::vec3 move = (-dx * right + dy * up) * scale;
  camera.position += move;
  camera.target += move;
}

void zoom_camera(Camera& camera, float notches) {
  const glm::vec3 offset = camera.position - camera.target;
  const float distance = glm::length(offset);
  const float wanted = distance * std::pow(0.9f, notches);
  camera.position =
      camera.target + offset * (std::max(wanted, camera.near_plane * 2.0f) / distance);
}

}  // namespace tessera
