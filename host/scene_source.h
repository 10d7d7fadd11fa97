#pragma once
// Where `--scene NAME|FILE` comes from: a built-in scene's file in the scenes folder (scenes/
// of the source tree, or share/tessera/scenes of an installation), or any scene file.

#include <string>
#include <vector>

#include "core/frame_settings.h"
#include "core/scene_file.h"

namespace tessera {

/// The folders searched for built-in scene files, in order: $TESSERA_SCENES, the installed
/// folder (../share/tessera/scenes beside the executable), the source tree's scenes/. The first
/// call prints scenes_variable_problem() to stderr as a warning, where there is one.
std::vector<std::string> scene_folders();

/// "TESSERA_SCENES is 'X', which does not exist; ..." (or "is not a folder", or "cannot be
/// read (why)") when the variable is set but names no readable folder, else "".
std::string scenes_variable_problem();

/// What `tessera scenes` says of the scene file `path`: its description, or, where it cannot
/// be loaded (load_scene_file), "(cannot be loaded: FILE:LINE:COLUMN: what is wrong)".
std::string scene_file_summary(const std::string& path);

/// True if `argument` names a file rather than a scene: it has a '/' or ends in .json.
bool is_scene_path(const std::string& argument);

/// True if `name` is a scene file NAME.json in one of scene_folders() (what `tessera scenes`
/// lists).
bool is_named_scene(const std::string& name);

/// Every scene a name loads, sorted: the scene files of the first scenes folder that has any
/// (what `tessera scenes` lists) and the built-in scenes made in code.
std::vector<std::string> known_scene_names();

/// Throws Error "unknown scene 'NAME' (known scenes: ...)" listing known_scene_names(), unless
/// `name` is one of them.
void check_scene_name(const std::string& name);

/// Throws Error "'PATH' is a file of a format Tessera does not read: ..." for a file `path`
/// whose extension is neither .json nor a model's (is_model_path) and whose first
/// non-blank character is not a JSON object's '{' ("models/box.fbx"); an extensionless or
/// .txt file holding a scene is read as one. `path` must name a readable regular file.
void check_scene_file_format(const std::string& path);

/// True if `argument` names a model file an importer reads: it ends in .gltf, .glb or .obj.
bool is_model_path(const std::string& argument);

/// Loads `name_or_file`: a model file (is_model_path) is the scene load_model_scene makes of
/// it, lit by light_unlit_model where it brings no lights (its note printed to stderr unless
/// `quiet`), its camera still the default one (frame_model_camera frames it); any other path
/// (anything with a '/' or ending in .json) is read as a scene file; a name is NAME.json in
/// the first scene folder that has it, or, when no folder has it, the built-in scene of that
/// name made in code (the same scene, core/builtin_scenes.h). Throws Error for an unknown name
/// (listing the known ones) and anything load_scene_file or the importers refuse. Warnings are
/// printed to stderr unless `quiet`.
SceneFile load_scene_argument(const std::string& name_or_file, bool strict, bool quiet);

/// A model brings no lights more often than not (OBJ has none): where `scene` has none, adds
/// the sun of the built-in scene 'textured' (directional, intensity 2.5, travelling along
/// (-0.5, -0.8, -0.6), so lighting the front of the framed view from above right) and raises
/// the ambient light to at least 0.08, and returns "note: NAME has no lights: lit by ...";
/// else changes nothing and returns "".
std::string light_unlit_model(Scene& scene, const std::string& name);

/// For a model file given as --scene (is_model_path(name)) and no --camera: sets the scene's
/// camera to framed_camera (core/orbit_camera.h) for an image of `width` x `height`.
/// Changes nothing otherwise: a scene file's camera is its own.
void frame_model_camera(Scene& scene, const std::string& name, bool camera_given, uint32_t width,
                        uint32_t height);

/// `--camera N`: sets file.scene.camera to the file's model camera N (SceneFile::model_cameras,
/// numbered from 0). Throws UsageError "--camera N: ..." (a bad command line, whose usage
/// `help_command` shows) naming the cameras there are, or that the scene's models bring none,
/// when N is past them.
void use_model_camera(SceneFile& file, uint32_t index, const std::string& help_command);

/// Fills in the frame settings a command line left unset (the `*_given` flags false) from a
/// scene file's "render" block, where it has them. Energy compensation is on if either turns
/// it on (the command line's flag cannot turn it off).
void apply_render_defaults(const RenderDefaults& defaults, FrameSettings& frame, bool size_given,
                           bool exposure_given, bool tonemap_given, bool brdf_given,
                           bool view_given = false);

/// "note: NAME has no objects: the image shows only the background" when `scene` has no
/// objects, in any view; else "note: NAME has no lights, ...: its objects are black" when
/// `scene` has nothing to light it (has_light) and `view` is the shaded one (debug views need no
/// light), else "". A note, not a warning: such a scene is valid, so --strict does not make it an
/// error. `env_removed`: the file had an environment that `--env none` took away, which the note
/// then says rather than that the file has none.
std::string unlit_scene_note(const Scene& scene, const std::string& name, View view,
                             bool env_removed = false);

/// "note: object K of NAME lies D m from the origin, where 32-bit positions are S m apart, ..."
/// when `scene` has objects that coarse_positions (core/scene.h) finds, else "". A note: such
/// a scene is valid, only imprecise on the GPU.
std::string coarse_positions_note(const Scene& scene, const std::string& name);

/// "note: light L of NAME lies D m from object K (its bounding box), ...: the shading treats
/// distances below 1 cm as 1 cm, ..." when `scene` has lights that lights_within_floor
/// (core/light_floor.h) finds, else "". A note: a light on a surface is valid, and a scene
/// modelled below centimetre scale only too dark. The floor is the reference's too.
std::string near_lights_note(const Scene& scene, const std::string& name);

/// `tessera scenes`: the scene files of every scene folder, in the order `--scene NAME` searches
/// them, each with its scene_file_summary, or marked where an earlier folder's file of the same
/// name is the one that loads; the built-in scenes when no folder has one.
std::string scene_listing();

}  // namespace tessera
