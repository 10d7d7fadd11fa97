#include "core/bench_scenes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/check.h"
#include "core/mesh.h"

namespace tessera {
namespace {

constexpr BenchFamilyInfo kFamilies[] = {
    {"grid", "N spheres on a grid filling the view (triangles shrink as N grows)"},
    {"scatter", "N small spheres scattered in depth (heavy overdraw)"},
    {"huge", "N triangles each many times the screen, stacked in depth"},
    {"yardstick",
     "N spheres on a side x side grid (side = ceil(sqrt N)), the minimal graphics program's "
     "layout"},
};

// A 7 x 7 palette of metallic-roughness materials, as in the default scene.
void add_palette(Scene& s) {
  for (int row = 0; row < 7; ++row) {
    for (int col = 0; col < 7; ++col) {
      s.materials.push_back(
          {glm::vec3(0.5f, 0.1f + 0.1f * (col % 3), 0.05f), row / 6.0f, col / 6.0f});
    }
  }
}

void add_four_lights(Scene& s, float distance) {
  for (glm::vec3 d :
       {glm::vec3(-1, 1, 1), glm::vec3(1, 1, 1), glm::vec3(-1, -1, 1), glm::vec3(1, -1, 1)}) {
    Light l;
    l.position = d * distance;
    l.intensity = 3.0f * distance * distance;  // about the default scene's brightness
    s.lights.push_back(l);
  }
}

// The grid family's layout: cells of side kGridSpacing, each holding a unit sphere, centred on
// the origin in the z = 0 plane, rows by cols filling an image of aspect `aspect`.
constexpr float kGridSpacing = 2.5f;
struct GridLayout {
  uint32_t cols = 1, rows = 1;
  float camera_distance = 0.0f;  // on +z, looking at the origin, with the whole grid in view
  glm::vec3 cell(uint32_t i) const {
    return {(float(i % cols) - (cols - 1) / 2.0f) * kGridSpacing,
            (float(i / cols) - (rows - 1) / 2.0f) * kGridSpacing, 0.0f};
  }
};

GridLayout grid_layout(uint32_t objects, float aspect) {
  GridLayout g;
  g.cols = std::max(1u, uint32_t(std::ceil(std::sqrt(double(objects) * aspect))));
  g.rows = (objects + g.cols - 1) / g.cols;
  // Far enough that the whole grid fits: half extents over tan of the half angles.
  const float tan_half = std::tan(glm::radians(45.0f) / 2.0f);
  const float half_w = g.cols * kGridSpacing / 2.0f, half_h = g.rows * kGridSpacing / 2.0f;
  g.camera_distance = std::max(half_h / tan_half, half_w / (tan_half * aspect)) + 1.0f;
  return g;
}

void place_grid_camera(Scene& s, const GridLayout& g) {
  s.camera.position = {0.0f, 0.0f, g.camera_distance};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.near_plane = std::max(0.1f, g.camera_distance * 1e-3f);
}

void check_aspect(float aspect) {
  if (!(aspect > 0.0f) || !std::isfinite(aspect)) throw Error("the image aspect must be positive");
}

}  // namespace

YardstickPlacement yardstick_placement(uint32_t i, uint32_t objects) {
  TESSERA_CHECK(objects > 0 && i < objects);
  // Exact: the square root of a perfect square below 2^52 is exact in double precision.
  const uint32_t s = uint32_t(std::ceil(std::sqrt(double(objects))));
  const float fs = float(s);
  return {{((float(i % s) + 0.5f) / fs * 2.0f - 1.0f) * 3.0f,
           ((float(i / s) + 0.5f) / fs * 2.0f - 1.0f) * 1.7f, 0.0f},
          0.45f * std::min(6.0f, 3.4f) / fs};
}

std::span<const BenchFamilyInfo> bench_families() {
  return kFamilies;
}

bool is_bench_family(std::string_view name) {
  for (const BenchFamilyInfo& f : kFamilies)
    if (f.name == name) return true;
  return false;
}

std::string bench_family_names() {
  std::string names;
  for (const BenchFamilyInfo& f : kFamilies)
    names += (names.empty() ? "" : ", ") + std::string(f.name);
  return names;
}

void check_triangle_numbering(uint64_t per_copy, uint32_t copies, const std::string& copy_name,
                              const std::string& copies_name) {
  if (per_copy * copies <= 0xFFFFFFFFull) return;
  throw Error("--objects " + std::to_string(copies) + ": " + std::to_string(per_copy) +
              " triangles per " + copy_name + " make " + std::to_string(per_copy * copies) +
              " triangle instances, more than the 2^32 - 1 Tessera can number (at most " +
              std::to_string(0xFFFFFFFFull / per_copy) + " " + copies_name + ")");
}

Scene make_bench_scene(std::string_view family, uint32_t objects, uint32_t segments, float aspect) {
  if (objects == 0) throw Error("a benchmark scene needs at least one object");
  if (segments < 4)
    throw Error("spheres need at least 4 segments (got " + std::to_string(segments) + ")");
  check_aspect(aspect);
  Scene s;
  s.background = {0.02f, 0.02f, 0.025f};
  s.ambient = glm::vec3(0.03f);
  add_palette(s);
  const float tan_half = std::tan(glm::radians(45.0f) / 2.0f);

  if (family == "grid") {
    s.meshes.push_back(make_uv_sphere(segments, segments / 2));
    const GridLayout g = grid_layout(objects, aspect);
    for (uint32_t i = 0; i < objects; ++i) {
      s.objects.push_back(
          {0, (i / g.cols % 7) * 7 + i % g.cols % 7, glm::translate(glm::mat4(1.0f), g.cell(i))});
    }
    place_grid_camera(s, g);
    add_four_lights(s, std::max(10.0f, g.camera_distance * 0.5f));
    return s;
  }
  if (family == "yardstick") {
    // The minimal graphics program's scene (bench/minimal_graphics.cpp), whatever the aspect:
    // its layout is fixed in world units, as the program's is.
    s.meshes.push_back(make_uv_sphere(segments, segments / 2));
    for (uint32_t i = 0; i < objects; ++i) {
      const YardstickPlacement p = yardstick_placement(i, objects);
      s.objects.push_back(
          {0, i % uint32_t(s.materials.size()),
           glm::scale(glm::translate(glm::mat4(1.0f), p.centre), glm::vec3(p.radius))});
    }
    s.camera.position = {0.0f, 0.0f, 3.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.vertical_fov = glm::radians(60.0f);
    add_four_lights(s, kYardstickLightDistance);
    return s;
  }
  if (family == "scatter") {
    s.meshes.push_back(make_uv_sphere(segments, segments / 2));
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    // Depths 5 to 50 in front of the camera, spread over the view at each depth.
    for (uint32_t i = 0; i < objects; ++i) {
      const float depth = 5.0f + 45.0f * u(rng);
      const float x = (u(rng) * 2 - 1) * depth * tan_half * aspect * 0.9f;
      const float y = (u(rng) * 2 - 1) * depth * tan_half * 0.9f;
      glm::mat4 t = glm::scale(glm::translate(glm::mat4(1.0f), {x, y, -depth}), glm::vec3(0.6f));
      s.objects.push_back({0, uint32_t(rng() % s.materials.size()), t});
    }
    s.camera.position = {0.0f, 0.0f, 0.0f};
    s.camera.target = {0.0f, 0.0f, -1.0f};
    add_four_lights(s, 10.0f);
    return s;
  }
  if (family == "huge") {
    Mesh m;
    m.positions = {{-60.0f, -40.0f, 0.0f}, {60.0f, -40.0f, 0.0f}, {0.0f, 80.0f, 0.0f}};
    m.normals.assign(3, {0.0f, 0.0f, 1.0f});
    m.uvs = {{0, 0}, {1, 0}, {0.5f, 1}};
    m.indices = {0, 1, 2};
    s.meshes.push_back(m);
    for (uint32_t i = 0; i < objects; ++i) {
      // Nearest last, so that each new triangle overdraws the ones before it.
      const float depth = 10.0f + 10.0f * float(objects - 1 - i) / float(objects);
      s.objects.push_back({0, i % uint32_t(s.materials.size()),
                           glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -depth})});
    }
    s.camera.position = {0.0f, 0.0f, 0.0f};
    s.camera.target = {0.0f, 0.0f, -1.0f};
    add_four_lights(s, 8.0f);
    return s;
  }
  std::string known;
  for (const auto& f : kFamilies) known += (known.empty() ? "" : ", ") + std::string(f.name);
  throw Error("unknown benchmark scene '" + std::string(family) + "' (known: " + known + ")");
}

Sphere bounding_sphere(const Scene& scene) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Object& o : scene.objects) {
    for (const glm::vec3& p : scene.meshes[o.mesh].positions) {
      const glm::vec3 w = glm::vec3(o.transform * glm::vec4(p, 1.0f));
      lo = glm::min(lo, w);
      hi = glm::max(hi, w);
    }
  }
  if (lo.x > hi.x) throw Error("the scene has no vertices to place");
  Sphere b{(lo + hi) * 0.5f, 0.0f};
  for (const Object& o : scene.objects) {
    for (const glm::vec3& p : scene.meshes[o.mesh].positions) {
      b.radius =
          std::max(b.radius, glm::distance(b.center, glm::vec3(o.transform * glm::vec4(p, 1.0f))));
    }
  }
  return b;
}

namespace {

// The scale that maps `bound` onto a unit sphere (a flat or point-like model still gets a
// finite one).
float unit_scale(const Sphere& bound) {
  return 1.0f / std::max(bound.radius, 1e-20f);
}

// The file's lights, moved with the content to the grid: centred, and scaled so that its
// bounding sphere covers the grid's (half diagonal), which keeps each light where it was
// relative to the model. Inverse-square intensities grow with the squared scale so the
// irradiance on the content is unchanged; ranges and classic attenuation scale with length.
InstancedLights place_lights(const Scene& content, const Sphere& bound, const GridLayout& g) {
  const float grid_radius =
      0.5f * kGridSpacing * std::sqrt(float(g.cols * g.cols + g.rows * g.rows));
  InstancedLights out{content.lights, grid_radius * unit_scale(bound)};
  const float k = out.length;
  for (Light& l : out.lights) {
    l.position = (l.position - bound.center) * k;
    if (l.falloff == Falloff::inverse_square && l.kind != LightKind::directional)
      l.intensity *= k * k;
    l.range *= k;
    l.attenuation = {l.attenuation.x, l.attenuation.y / k, l.attenuation.z / (k * k)};
  }
  return out;
}

}  // namespace

InstancedLights instanced_bench_lights(const Scene& content, uint32_t copies, float aspect) {
  if (copies == 0) throw Error("a benchmark scene needs at least one copy");
  check_aspect(aspect);
  return place_lights(content, bounding_sphere(content), grid_layout(copies, aspect));
}

Scene make_instanced_bench_scene(const Scene& content, uint32_t copies, float aspect) {
  if (copies == 0) throw Error("a benchmark scene needs at least one copy");
  check_aspect(aspect);
  const Sphere bound = bounding_sphere(content);
  const float scale = unit_scale(bound);
  const glm::mat4 normalise =
      glm::translate(glm::scale(glm::mat4(1.0f), glm::vec3(scale)), -bound.center);
  Scene s = content;
  s.objects.clear();
  s.objects.reserve(size_t(copies) * content.objects.size());
  const GridLayout g = grid_layout(copies, aspect);
  for (uint32_t i = 0; i < copies; ++i) {
    const glm::mat4 cell = glm::translate(glm::mat4(1.0f), g.cell(i)) * normalise;
    for (const Object& o : content.objects)
      s.objects.push_back({o.mesh, o.material, cell * o.transform});
  }
  s.camera = Camera{};  // the grid's field of view, not the file's
  place_grid_camera(s, g);
  if (content.lights.empty()) {
    add_four_lights(s, std::max(10.0f, g.camera_distance * 0.5f));
    return s;
  }
  s.lights = place_lights(content, bound, g).lights;
  return s;
}

}  // namespace tessera
