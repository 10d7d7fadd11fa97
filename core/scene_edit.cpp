#include "core/scene_edit.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "core/check.h"
#include "core/materials.h"
#include "core/mesh.h"

namespace tessera {
namespace {

void require_index(uint32_t index, size_t count, const char* what) {
  if (index >= count) {
    throw Error(std::string(what) + " " + std::to_string(index) +
                " does not exist (the scene has " + std::to_string(count) + ")");
  }
}

// The element operations shared by objects, materials, meshes and lights.
template <typename T>
void insert_at(std::vector<T>& items, uint32_t index, const T& item, const char* what) {
  if (index > items.size()) require_index(index, items.size() + 1, what);  // size appends
  items.insert(items.begin() + index, item);
}
template <typename T>
T erase_at(std::vector<T>& items, uint32_t index, const char* what) {
  require_index(index, items.size(), what);
  T removed = std::move(items[index]);
  items.erase(items.begin() + index);
  return removed;
}
template <typename T>
T set_at(std::vector<T>& items, uint32_t index, const T& item, const char* what) {
  require_index(index, items.size(), what);
  return std::exchange(items[index], item);
}
template <typename T>
T pop_last(std::vector<T>& items, const char* what) {
  if (items.empty()) throw Error(std::string("the scene has no ") + what + " to remove");
  return erase_at(items, uint32_t(items.size() - 1), what);
}

struct OpApplier {
  Scene& scene;

  EditOp operator()(const edit_op::InsertObject& op) {
    insert_at(scene.objects, op.index, op.object, "object");
    return edit_op::EraseObject{op.index};
  }
  EditOp operator()(const edit_op::EraseObject& op) {
    return edit_op::InsertObject{op.index, erase_at(scene.objects, op.index, "object")};
  }
  EditOp operator()(const edit_op::SetObject& op) {
    return edit_op::SetObject{op.index, set_at(scene.objects, op.index, op.object, "object")};
  }
  EditOp operator()(const edit_op::AppendMaterial& op) {
    scene.materials.push_back(op.material);
    return edit_op::PopMaterial{};
  }
  EditOp operator()(const edit_op::PopMaterial&) {
    return edit_op::AppendMaterial{pop_last(scene.materials, "material")};
  }
  EditOp operator()(const edit_op::SetMaterial& op) {
    return edit_op::SetMaterial{op.index,
                                set_at(scene.materials, op.index, op.material, "material")};
  }
  EditOp operator()(const edit_op::AppendMesh& op) {
    scene.meshes.push_back(op.mesh);
    return edit_op::PopMesh{};
  }
  EditOp operator()(const edit_op::PopMesh&) {
    return edit_op::AppendMesh{pop_last(scene.meshes, "mesh")};
  }
  EditOp operator()(const edit_op::InsertLight& op) {
    insert_at(scene.lights, op.index, op.light, "light");
    return edit_op::EraseLight{op.index};
  }
  EditOp operator()(const edit_op::EraseLight& op) {
    return edit_op::InsertLight{op.index, erase_at(scene.lights, op.index, "light")};
  }
  EditOp operator()(const edit_op::SetLight& op) {
    return edit_op::SetLight{op.index, set_at(scene.lights, op.index, op.light, "light")};
  }
  EditOp operator()(const edit_op::SetEnvironment& op) {
    return edit_op::SetEnvironment{std::exchange(scene.environment, op.environment)};
  }
};

// How many objects use material `material`.
size_t material_users(const Scene& scene, uint32_t material) {
  size_t n = 0;
  for (const Object& o : scene.objects) n += o.material == material ? 1 : 0;
  return n;
}

}  // namespace

Edit apply_edit(Scene& scene, const Edit& edit) {
  Edit inverse{edit.label, {}};
  inverse.ops.reserve(edit.ops.size());
  try {
    for (const EditOp& op : edit.ops) inverse.ops.push_back(std::visit(OpApplier{scene}, op));
  } catch (const Error&) {
    // Roll back what was applied; each inverse succeeds on the scene its forward op left.
    for (auto it = inverse.ops.rbegin(); it != inverse.ops.rend(); ++it)
      std::visit(OpApplier{scene}, *it);
    throw;
  }
  std::reverse(inverse.ops.begin(), inverse.ops.end());
  return inverse;
}

Edit add_object_copy(const Scene& scene, uint32_t object, const glm::mat4& transform) {
  require_index(object, scene.objects.size(), "object");
  Object copy = scene.objects[object];
  copy.transform = transform;
  return {"copy object " + std::to_string(object),
          {edit_op::InsertObject{uint32_t(scene.objects.size()), copy}}};
}

Edit add_sphere(const Scene& scene, glm::vec3 centre, float radius, const Material& material) {
  if (!(std::isfinite(radius) && radius > 0.0f))
    throw Error("a sphere needs a finite radius > 0 m, not " + std::to_string(radius));
  Edit edit{"add sphere", {}};
  const Mesh sphere = make_uv_sphere(64, 32);
  uint32_t mesh = uint32_t(scene.meshes.size());
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    if (scene.meshes[m] == sphere) {
      mesh = m;
      break;
    }
  }
  if (mesh == scene.meshes.size()) edit.ops.push_back(edit_op::AppendMesh{sphere});
  edit.ops.push_back(edit_op::AppendMaterial{material});
  Object o;
  o.mesh = mesh;
  o.material = uint32_t(scene.materials.size());
  o.transform = glm::scale(glm::translate(glm::mat4(1.0f), centre), glm::vec3(radius));
  edit.ops.push_back(edit_op::InsertObject{uint32_t(scene.objects.size()), o});
  return edit;
}

Material metal_material(std::string_view preset, float roughness) {
  const MetalPreset* p = find_metal_preset(preset);
  if (!p) {
    std::string known;
    for (const MetalPreset& m : metal_presets())
      known += (known.empty() ? "" : ", ") + std::string(m.name);
    throw Error("unknown material preset \"" + std::string(preset) + "\" (known: " + known + ")");
  }
  Material m;
  m.base_color = p->f0;
  m.metallic = 1.0f;
  m.roughness = roughness;
  return m;
}

Edit delete_object(const Scene& scene, uint32_t object) {
  require_index(object, scene.objects.size(), "object");
  return {"delete object " + std::to_string(object), {edit_op::EraseObject{object}}};
}

Edit move_object(const Scene& scene, uint32_t object, const glm::mat4& transform) {
  require_index(object, scene.objects.size(), "object");
  Object moved = scene.objects[object];
  moved.transform = transform;
  return {"move object " + std::to_string(object), {edit_op::SetObject{object, moved}}};
}

Edit set_object_material(const Scene& scene, uint32_t object, const Material& material) {
  require_index(object, scene.objects.size(), "object");
  const uint32_t current = scene.objects[object].material;
  const std::string label = "material of object " + std::to_string(object);
  if (material_users(scene, current) <= 1)
    return {label, {edit_op::SetMaterial{current, material}}};
  Object changed = scene.objects[object];
  changed.material = uint32_t(scene.materials.size());
  return {label, {edit_op::AppendMaterial{material}, edit_op::SetObject{object, changed}}};
}

Edit add_light(const Scene& scene, const Light& light) {
  return {"add light", {edit_op::InsertLight{uint32_t(scene.lights.size()), light}}};
}

Edit delete_light(const Scene& scene, uint32_t light) {
  require_index(light, scene.lights.size(), "light");
  return {"delete light " + std::to_string(light), {edit_op::EraseLight{light}}};
}

Edit set_light(const Scene& scene, uint32_t light, const Light& value) {
  require_index(light, scene.lights.size(), "light");
  return {"change light " + std::to_string(light), {edit_op::SetLight{light, value}}};
}

Edit set_environment(const Scene&, std::shared_ptr<const Environment> environment) {
  const char* label = environment ? "set environment" : "remove environment";
  return {label, {edit_op::SetEnvironment{std::move(environment)}}};
}

void EditHistory::apply(Scene& scene, const Edit& edit) {
  Edit inverse;
  try {
    inverse = apply_edit(scene, edit);
  } catch (const Error& e) {
    throw Error(edit.label + ": " + e.what());
  }
  try {
    validate_scene(scene);
  } catch (const Error& e) {
    apply_edit(scene, inverse);
    throw Error(edit.label + ": " + e.what());
  }
  undo_.push_back({std::move(inverse), state_, next_state_});
  state_ = next_state_++;
  redo_.clear();
}

bool EditHistory::undo(Scene& scene) {
  if (undo_.empty()) return false;
  Entry e = std::move(undo_.back());
  undo_.pop_back();
  e.edit = apply_edit(scene, e.edit);
  state_ = e.state_before;
  redo_.push_back(std::move(e));
  return true;
}

bool EditHistory::redo(Scene& scene) {
  if (redo_.empty()) return false;
  Entry e = std::move(redo_.back());
  redo_.pop_back();
  e.edit = apply_edit(scene, e.edit);
  state_ = e.state_after;
  undo_.push_back(std::move(e));
  return true;
}

std::string EditHistory::undo_label() const {
  return undo_.empty() ? "" : undo_.back().edit.label;
}

std::string EditHistory::redo_label() const {
  return redo_.empty() ? "" : redo_.back().edit.label;
}

}  // namespace tessera
