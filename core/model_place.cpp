#include "core/model_place.h"

#include <cstdlib>
#include <optional>
#include <sstream>

namespace tessera {
namespace {

// A vector as messages print numbers: (2e+15, 0, 1.5).
std::string point(glm::vec3 p) {
  std::ostringstream s;
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

// K of a message that starts with `prefix` and K.
std::optional<size_t> index_after(const std::string& message, const std::string& prefix) {
  if (message.rfind(prefix, 0) != 0) return std::nullopt;
  return std::strtoull(message.c_str() + prefix.size(), nullptr, 10);
}

std::string object_message(const Scene& scene, const ModelInScene& m, size_t k,
                           const std::string& message) {
  const size_t local = k - m.first_object;
  const ImportedPlaces& places = *m.places;
  // validate_scene tests the corners of the mesh's box; the first vertex out of range is what
  // the user can find in the model file (none where only a rotated box's corner is).
  const Object& o = scene.objects[k];
  const std::vector<glm::vec3>& positions = scene.meshes[o.mesh].positions;
  const auto placed = [&](glm::vec3 p) { return glm::vec3(o.transform * glm::vec4(p, 1.0f)); };
  size_t v = 0;
  while (v < positions.size() && within_scene_coordinates(placed(positions[v]))) ++v;
  if (m.obj) {
    if (v == positions.size()) return model_file_place(m.file, true, "") + message;
    const glm::vec3 p = positions[v];
    size_t line = obj_vertex_line(m.file, [&](glm::vec3 q) { return q == p; });
    if (!line)
      line = obj_vertex_line(m.file,
                             [&](glm::vec3 q) { return !within_scene_coordinates(placed(q)); });
    return model_file_place(m.file, true, "", line) + message + " (its vertex " + point(p) +
           " is placed at " + point(placed(p)) + ")";
  }
  const size_t mesh = o.mesh - m.first_mesh;
  if (local >= places.objects.size() || mesh >= places.meshes.size()) return "";
  std::string tail = " (" + places.meshes[mesh];
  if (v < positions.size()) {
    const glm::vec3 p = positions[v];
    // A flat-shaded primitive's vertices are its triangles' corners, not its elements.
    tail += ".attributes.POSITION " +
            (places.vertices_are_elements[mesh]
                 ? "element " + std::to_string(v) + ", " + point(p) + ", is"
                 : "value " + point(p) + " is") +
            " placed at " + point(placed(p));
  }
  return model_file_place(m.file, false, places.objects[local]) + message + tail + ")";
}

}  // namespace

std::string model_file_place(const std::string& file, bool obj, const std::string& place,
                             size_t line) {
  if (obj) return "'" + file + "'" + (line ? " line " + std::to_string(line) : "") + ": ";
  return file + ": " + (place.empty() ? "" : place + ": ");
}

std::string model_part_message(const Scene& scene, const ModelInScene& m,
                               const std::string& message) {
  if (!m.places) return "";
  if (const std::optional<size_t> k = index_after(message, "invalid scene: object ")) {
    if (*k < m.first_object || *k - m.first_object >= m.objects || *k >= scene.objects.size())
      return "";
    return object_message(scene, m, *k, message);
  }
  if (const std::optional<size_t> k = index_after(message, "invalid scene: light ")) {
    if (*k < m.first_light || *k - m.first_light >= m.lights) return "";
    if (*k - m.first_light >= m.places->lights.size()) return "";
    const auto& [node, light] = m.places->lights[*k - m.first_light];
    // The limits on intensity and range are the light's own; its position, its node's.
    if (message.find(" range is ") != std::string::npos)
      return model_file_place(m.file, m.obj, light + ".range") + message;
    if (message.find(" intensity times color is ") != std::string::npos)
      return model_file_place(m.file, m.obj, light + ".intensity") + message +
             " (KHR_lights_punctual's candela or lux divided by 683 lm/W)";
    return model_file_place(m.file, m.obj, node + " (" + light + ")") + message;
  }
  return "";
}

}  // namespace tessera
