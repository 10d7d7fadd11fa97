#pragma once
// Edits of a Scene as plain data, for the viewer's live editing: each edit is a list of
// primitive operations that can be applied and undone exactly, and EditHistory keeps the
// undo and redo stacks and whether the scene has unsaved edits.
//
// Indices: deleting an object or light shifts the later ones down by one (as
// std::vector::erase), and undo puts it back at its index. Meshes, materials and textures are
// never removed by an edit (an object's deletion leaves them in the scene, unused), so the
// indices objects hold stay valid; a new object reuses its mesh index rather than copying it.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/scene.h"

namespace tessera {

// The primitive operations. Applying one returns its inverse.
namespace edit_op {
struct InsertObject {
  uint32_t index;  // <= objects.size()
  Object object;
};
struct EraseObject {
  uint32_t index;
};
struct SetObject {
  uint32_t index;
  Object object;
};
struct AppendMaterial {
  Material material;
};
struct PopMaterial {};
struct SetMaterial {
  uint32_t index;
  Material material;
};
struct AppendMesh {
  Mesh mesh;
};
struct PopMesh {};
struct InsertLight {
  uint32_t index;  // <= lights.size()
  Light light;
};
struct EraseLight {
  uint32_t index;
};
struct SetLight {
  uint32_t index;
  Light light;
};
struct SetEnvironment {
  std::shared_ptr<const Environment> environment;  // null: none
};
}  // namespace edit_op

using EditOp = std::variant<edit_op::InsertObject, edit_op::EraseObject, edit_op::SetObject,
                            edit_op::AppendMaterial, edit_op::PopMaterial, edit_op::SetMaterial,
                            edit_op::AppendMesh, edit_op::PopMesh, edit_op::InsertLight,
                            edit_op::EraseLight, edit_op::SetLight, edit_op::SetEnvironment>;

/// One reversible edit: its operations run in order; undo runs their inverses in reverse.
struct Edit {
  std::string label;  // for people: "delete object 3"
  std::vector<EditOp> ops;
};

// Edit builders. Each reads `scene` (not changed) to check indices, throwing Error naming the
// index and the count when one is out of range, and returns the edit for EditHistory::apply,
// which checks the edited scene as a whole (validate_scene).

/// A new object (appended) with the mesh and material of `object` (shared, not copied) placed
/// by `transform` (object -> world).
Edit add_object_copy(const Scene& scene, uint32_t object, const glm::mat4& transform);

/// The unit uv sphere of `tessera render`'s scenes, make_uv_sphere(64, 32) (reused if the scene
/// already has an identical mesh, appended otherwise), scaled by `radius` m (> 0, finite) and
/// centred at `centre` (world, m), with a new material `material` (appended).
Edit add_sphere(const Scene& scene, glm::vec3 centre, float radius, const Material& material);

/// The material of a metal preset of core/materials.h (base colour its F0, metallic 1) with
/// `roughness`. Throws Error naming the unknown preset and the known ones.
Material metal_material(std::string_view preset, float roughness = 0.3f);

/// Removes object `object`; later objects move down by one index.
Edit delete_object(const Scene& scene, uint32_t object);

/// Sets the transform (object -> world) of `object`.
Edit move_object(const Scene& scene, uint32_t object, const glm::mat4& transform);

/// Gives `object` the material `material`. Copy-on-write: when another object shares the
/// object's material, a new material is appended and only this object is pointed at it (the
/// others keep theirs); when no other object uses it, it is changed in place.
Edit set_object_material(const Scene& scene, uint32_t object, const Material& material);

/// Appends a light.
Edit add_light(const Scene& scene, const Light& light);
/// Removes light `light`; later lights move down by one index.
Edit delete_light(const Scene& scene, uint32_t light);
/// Replaces light `light` (to move it, change its position or direction).
Edit set_light(const Scene& scene, uint32_t light, const Light& value);

/// Sets or (with null) removes the environment; the map is shared, not copied.
Edit set_environment(const Scene& scene, std::shared_ptr<const Environment> environment);

/// Applies the operations of `edit` to `scene` in order and returns the edit that undoes it
/// (inverse operations in reverse order, label kept). Throws Error if an operation's index is
/// out of range (the scene is then left as it was). Does not call validate_scene.
Edit apply_edit(Scene& scene, const Edit& edit);

/// Undo and redo stacks over one scene, and whether it has unsaved edits.
class EditHistory {
 public:
  /// Applies `edit` to `scene`, then validate_scene. On an Error (a bad index, or an edited
  /// scene that does not validate: a NaN transform, a negative radius...) the scene is
  /// restored and the Error rethrown, prefixed with the edit's label; the history is unchanged.
  /// On success the edit joins the undo stack and the redo stack is cleared.
  void apply(Scene& scene, const Edit& edit);

  /// Undoes the last applied edit; false if there is none. `scene` must be the scene the
  /// edits were applied to, unchanged since.
  bool undo(Scene& scene);
  /// Redoes the last undone edit; false if there is none.
  bool redo(Scene& scene);

  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  /// Labels of the next undo and redo ("" if none), for menus.
  std::string undo_label() const;
  std::string redo_label() const;

  /// True when the scene differs from the state last marked saved (initially: the state the
  /// history started from). Undoing or redoing back to the saved state clears it; a new edit
  /// after undoing past the saved state makes that state unreachable, so it stays set.
  bool dirty() const { return state_ != saved_state_; }
  /// Marks the current state as saved (after writing the scene to a file).
  void mark_saved() { saved_state_ = state_; }
  /// The current state's id: 0 before any edit, then a new id for each applied edit; undo and
  /// redo return to the ids of the states they go back to. For state kept beside the scene
  /// (the viewer's render options), keyed by it.
  uint64_t state() const { return state_; }

 private:
  struct Entry {
    Edit edit;  // what applying it now does: the inverse on the undo stack, forward on redo
    uint64_t state_before, state_after;
  };
  std::vector<Entry> undo_, redo_;
  uint64_t state_ = 0, saved_state_ = 0, next_state_ = 1;
};

}  // namespace tessera
