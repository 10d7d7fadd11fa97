#pragma once
// The scene model: what Tessera renders. Plain data, no Vulkan. Units are metres and radians;
// colours are linear RGB.

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/environment.h"
#include "core/texture.h"
#include "shaders/shared/constants.h"

namespace tessera {

struct Camera {
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f, 0.0f, 0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float vertical_fov = glm::radians(45.0f);  // full angle
  float near_plane = 0.1f;                   // > 0; there is no far plane
  // Memberwise, floats compared exactly (as are those of Mesh, Material, Light, Object).
  bool operator==(const Camera&) const = default;
};

/// The exact surface a mesh tessellates, for ground truth (docs/accuracy.md, "Ground truth"):
/// the sphere of `centre` and `radius` in object space, parametrised as make_uv_sphere's is
/// (v = theta / pi from +y, u growing from +x towards -z) with u = `u_at_plus_x` at +x.
struct AnalyticSphere {
  glm::vec3 centre{0.0f};
  float radius = 1.0f;
  float u_at_plus_x = 0.0f;
  bool operator==(const AnalyticSphere&) const = default;
};

/// Triangle mesh with one normal and uv per vertex. Triangles wind counter-clockwise seen from
/// outside (their front side); back faces are culled.
struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // unit length, same count as positions
  /// uv set 0: the same count as positions, or empty where every uv is (0, 0) (a glTF
  /// primitive without TEXCOORD_0), which saves 8 bytes a vertex.
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;  // 3 per triangle, each < positions.size()
  /// Optional second uv set (glTF TEXCOORD_1), read by the maps of Material::uv1_maps: empty,
  /// or the same count as positions. Costs nothing in a scene whose materials read only set 0.
  std::vector<glm::vec2> uvs1;
  /// Optional, for normal maps: xyz a unit tangent along +u orthogonal to the normal, w = +-1
  /// the handedness (bitangent = w cross(normal, tangent)). Empty: generated from `uvs` (set
  /// 0; generate_tangents) when the scene is uploaded or rendered, so a normal map that reads
  /// set 1 needs the mesh to bring tangents of that set (the glTF importer makes them for the
  /// primitives whose material has a normal map).
  std::vector<glm::vec4> tangents;
  /// Set by the sphere builders (make_uv_sphere, make_icosphere, so also the scene file's
  /// "sphere" and "icosphere" meshes): the triangles approximate this sphere, and the reference
  /// renderer may intersect it exactly instead (ReferenceSettings::ground_truth). Code that
  /// moves the vertices of such a mesh must reset it. Only the reference renderer reads it
  /// (and operator==, as any field).
  std::optional<AnalyticSphere> analytic_sphere;
  size_t triangle_count() const { return indices.size() / 3; }
  bool operator==(const Mesh&) const = default;
};

/// Material::*_map value for "no texture".
constexpr uint32_t kNoTexture = 0xFFFFFFFFu;

/// Metallic-roughness material. roughness is perceptual (alpha = roughness^2), in [0, 1].
/// Each factor may be multiplied by a texture map (indices into Scene::textures), with the
/// channel layout of glTF 2.0.
struct Material {
  glm::vec3 base_color{0.8f};
  float metallic = 0.0f;
  float roughness = 0.5f;
  glm::vec3 emissive{0.0f};  // emitted radiance, linear RGB, >= 0 (added as it is)
  float occlusion = 1.0f;    // ambient occlusion in [0, 1]: scales ambient and environment light
  uint32_t base_color_map = kNoTexture;          // RGB (sRGB texture) times base_color
  uint32_t metallic_roughness_map = kNoTexture;  // G times roughness, B times metallic
  uint32_t normal_map = kNoTexture;              // tangent-space normal, RGB * 2 - 1
  uint32_t occlusion_map = kNoTexture;           // R times occlusion
  float normal_scale = 1.0f;                     // scales the normal map's x and y
  uint32_t emissive_map = kNoTexture;            // RGB (sRGB texture) times emissive
  // Never culled by facing (whatever FrameSettings::cull says); back faces are shaded with the
  // normal and tangent frame flipped toward the viewer (glTF 2.0 doubleSided).
  bool double_sided = false;
  /// The uv set each map reads (glTF textureInfo.texCoord): a TS_MAP_* bit set here (e.g.
  /// TS_MAP_BASE_COLOR for base_color_map) makes that map read Mesh::uvs1, clear reads
  /// Mesh::uvs. Bits of the five maps only; every mesh drawn with a material that sets any bit
  /// must have uvs1 (validate_scene).
  uint32_t uv1_maps = 0;
  bool operator==(const Material&) const = default;
};

/// A scalar parameter of Material and the values validate_scene accepts for it (inclusive;
/// NaN and infinities never). Every float of Material has its line, so a new parameter is
/// validated by adding it here.
struct MaterialScalar {
  const char* name;
  float Material::*field;
  float min, max;
};
inline constexpr float kAnyFinite = std::numeric_limits<float>::max();
inline constexpr MaterialScalar kMaterialScalars[] = {
    // Outside [0, 1] metallic and roughness are clamped when shading, as glTF allows.
    {"metallic", &Material::metallic, -kAnyFinite, kAnyFinite},
    {"roughness", &Material::roughness, -kAnyFinite, kAnyFinite},
    {"occlusion", &Material::occlusion, 0.0f, 1.0f},
    {"normal scale", &Material::normal_scale, -kAnyFinite, kAnyFinite},
};

/// The kinds of light, numbered as the shaders number them (TS_LIGHT_*, which also orders the
/// uploaded lights).
enum class LightKind : uint32_t {
  point = TS_LIGHT_POINT,
  spot = TS_LIGHT_SPOT,
  directional = TS_LIGHT_DIRECTIONAL,
};

/// How a point or spot light's intensity falls with distance d.
enum class Falloff : uint32_t {
  /// Physically based: intensity / d^2, faded to zero at `range` by
  /// saturate(1 - (d / range)^4)^2 (Karis 2013); no fade when range is 0.
  inverse_square = TS_FALLOFF_INVERSE_SQUARE,
  /// The classic model: intensity / (Kc + Kl d + Kq d^2), with `attenuation` = (Kc, Kl, Kq).
  classic = TS_FALLOFF_CLASSIC,
};

/// Units: colour is linear RGB and dimensionless; intensity is radiant intensity (W/sr) for
/// point and spot lights, so a surface 1 m away facing the light receives `intensity` W/m^2,
/// and irradiance (W/m^2) for directional lights.
struct Light {
  LightKind kind = LightKind::point;
  glm::vec3 position{0.0f};                // all but directional lights
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // directional and spot lights: the way light travels
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  Falloff falloff = Falloff::inverse_square;
  float range = 0.0f;                       // inverse-square fade radius in m (0: none)
  glm::vec3 attenuation{1.0f, 0.0f, 0.0f};  // classic falloff: Kc, Kl, Kq (>= 0, not all 0)
  float inner_angle = 0.35f;                // spot: half angles in radians, 0 <= inner <= outer
  float outer_angle = 0.5f;                 //       < pi/2; full intensity inside the inner cone
  bool operator==(const Light&) const = default;
};

/// One placed instance of a mesh; many objects may share a mesh and a material.
struct Object {
  uint32_t mesh = 0;
  uint32_t material = 0;
  glm::mat4 transform{1.0f};  // object -> world
  bool operator==(const Object&) const = default;
};

enum class ToneMap { aces, reinhard, clamp };

/// The BRDF of the shading model (docs/shading.md).
/// Values are the shaders' TS_BRDF_*.
enum class Brdf : uint32_t {
  classic = TS_BRDF_CLASSIC,    // GGX, Smith with Schlick-GGX k = (r+1)^2/8, Schlick F on V.H,
                                // (1-F)(1-m) Lambert
  filament = TS_BRDF_FILAMENT,  // GGX, height-correlated Smith visibility, Schlick F on V.H,
                                // (1-m) Lambert
  blinn_phong = TS_BRDF_BLINN_PHONG,  // normalized Blinn-Phong, the non-physical baseline
};

/// Which triangles are culled by their facing. Front faces wind counter-clockwise as seen.
enum class CullMode { back, front, none };

/// What an image shows: the shaded scene, or a debug view of what the rasterizer produced.
enum class View { shaded, normal, uv, triangle, object };

/// The ranges validate_scene accepts for lights and positions (docs/shading.md, "Accepted
/// ranges"). Within them every intermediate of the light arithmetic stays finite in fp32.
/// Positions: every light, the camera and every vertex in world space, per coordinate, in m.
inline constexpr float kMaxSceneCoordinate = 1e15f;
/// Whether every coordinate of `p` is within +-kMaxSceneCoordinate (what validate_scene requires).
inline bool within_scene_coordinates(glm::vec3 p) {
  return glm::all(glm::lessThanEqual(glm::abs(p), glm::vec3(kMaxSceneCoordinate)));
}
/// Intensity times the largest colour component: W/sr (point, spot) or W/m^2 (directional).
inline constexpr float kMaxLightIntensity = 1e26f;
/// Inverse-square range, in m: 0 (no fade) or within [kMinLightRange, kMaxLightRange].
inline constexpr float kMinLightRange = 1e-3f;
inline constexpr float kMaxLightRange = 1e9f;
/// Classic falloff: each of Kc, Kl, Kq within [0, kMaxAttenuation], not all 0.
inline constexpr float kMaxAttenuation = 1e6f;

struct Scene {
  Camera camera;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Object> objects;
  std::vector<Light> lights;
  glm::vec3 background{0.0f};  // linear HDR colour of pixels no triangle covers
  glm::vec3 ambient{0.0f};     // constant ambient radiance, times the base colour
  std::vector<Texture> textures;
  /// Distant light from every direction (image-based lighting), also drawn as the background
  /// instead of `background`. Shared, so copies of a scene do not copy the map.
  std::shared_ptr<const Environment> environment;
};

/// Checks `scene` for bad input: out-of-range mesh, material or vertex indices, NaN or
/// infinite values in positions, normals, transforms, materials, lights or the camera, a
/// degenerate camera, positions, light intensities, ranges and attenuations outside the
/// accepted ranges above. Throws tessera::Error naming the first problem found (which mesh,
/// object, vertex or field).
void validate_scene(const Scene& scene);

/// Whether anything gives `scene` light to shade with: a light, ambient light, an environment,
/// or an object whose material emits. Without any of them every shaded object is black: a
/// valid scene, which the commands only note (host/scene_source.h, unlit_scene_note).
bool has_light(const Scene& scene);

/// Objects placed so far from the origin that 32-bit positions, which the GPU shades with (the
/// CPU reference works in double), resolve them coarsely: where a float's spacing at the
/// object's farthest coordinate exceeds 1/1024 of its box's largest side (a 1 m object beyond
/// 8192 m; at 1e6 m floats are 0.0625 m apart), its shading and outline show that grain as
/// stripes. A valid scene, which the commands only note (host/scene_source.h).
struct CoarsePositions {
  size_t count = 0;       // objects so placed; 0: none, and the rest is unset
  size_t first = 0;       // the first of them, by index into Scene::objects
  double distance = 0.0;  // its farthest coordinate from the origin (m, absolute value)
  double spacing = 0.0;   // a float's spacing there (m)
  double size = 0.0;      // its world box's largest side (m)
};
/// Assumes a scene validate_scene accepts. O(objects + vertices).
CoarsePositions coarse_positions(const Scene& scene);

/// The camera part of validate_scene, with its messages ("invalid scene: the camera's ..."),
/// for cameras that are not yet a scene's (a scene file's model cameras, core/scene_file.h).
void validate_camera(const Camera& camera);

/// How objects are numbered for rendering. Objects are sorted by their content (mesh,
/// material, transform), not by their position in Scene::objects, and their triangles numbered
/// consecutively in that order, so that the triangle-instance ids that break depth ties, and
/// so the image, do not depend on the order objects were submitted in. Objects whose mesh has
/// no triangles are left out.
struct ObjectNumbering {
  std::vector<uint32_t> objects;         // indices into Scene::objects, in numbering order
  std::vector<uint64_t> first_triangle;  // id of each listed object's triangle 0
  uint64_t triangle_count = 0;           // ids run from 0 to triangle_count - 1
};

/// Numbers the objects of `scene` (which must have passed validate_scene).
ObjectNumbering number_objects(const Scene& scene);

/// Colour that the debug views give an id (PCG hash, O'Neill 2014); each channel in [0, 1].
glm::vec3 id_colour(uint32_t id);

/// World -> view transform of `camera` (right-handed, looking down -z).
glm::mat4 view_matrix(const Camera& camera);

/// True if `transform` mirrors what it places: its upper 3x3 has a negative determinant. Such
/// an object's counter-clockwise triangles wind clockwise in the world, so its front faces are
/// the clockwise ones (as glTF 2.0 requires), and its tangent frames change handedness. The one
/// decision used by the compute path, the hardware baseline and the reference renderer.
bool is_mirroring(const glm::mat4& transform);

/// View -> clip projection for Vulkan's y-down NDC. clip.w is the distance along the view
/// axis; clip.z is unused by the rasterizer (depth is near / w). `aspect` = width / height.
glm::mat4 projection_matrix(const Camera& camera, float aspect);

}  // namespace tessera
