#include "host/view_panel.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include <imgui.h>

#include "compute/passes.h"
#include "core/materials.h"

namespace tessera {
namespace {

void draw_timings(const PanelInput& in) {
  ImGui::Text("frame %.2f ms (%.1f fps)", in.frame_ms, in.frame_ms > 0 ? 1000.0 / in.frame_ms : 0);
  const FrameStats& s = *in.stats;
  if (!s.has_timestamps) {
    ImGui::TextUnformatted("GPU times: no timestamps on this queue");
    return;
  }
  ImGui::Text("GPU %.2f ms", s.gpu_total_ms);
  // Each pass as a bar, scaled to the frame's total.
  for (const PassInfo& p : kPasses) {
    const double ms = s.pass_ms[size_t(p.pass)];
    char label[48];
    std::snprintf(label, sizeof(label), "%.3f ms", ms);
    ImGui::ProgressBar(s.gpu_total_ms > 0 ? float(ms / s.gpu_total_ms) : 0.0f, ImVec2(120, 0),
                       label);
    ImGui::SameLine();
    ImGui::TextUnformatted(p.name);
  }
}

void draw_counts(const FrameStats& s) {
  ImGui::Text("triangles: %llu submitted, %llu rasterized",
              (unsigned long long)s.triangles_submitted, (unsigned long long)s.raster_triangles);
  if (s.rasterized_and_shaded) {
    ImGui::TextUnformatted("rasterized and shaded in one pass");
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip(
          "a small frame: every tile's workgroup tests every triangle and shades its pixels\n"
          "(--raster-shade, docs/architecture.md, \"Small frames in one pass\")");
    }
  } else {
    ImGui::Text(
        "%llu small, %llu binned to tiles", (unsigned long long)s.small_triangles,
        (unsigned long long)(s.raster_triangles - std::min(s.small_triangles, s.raster_triangles)));
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip(
          "small: a pixel box of at most the small-triangle area (128 pixels on GPUs, 4096 on\n"
          "CPU devices), rasterized by a thread per walk of its rows\n"
          "binned to tiles: larger, sorted into the screen tiles they touch (%llu bin entries of\n"
          "up to 8x8 tiles) and rasterized one workgroup per tile (docs/architecture.md)",
          (unsigned long long)s.big_triangles);
    }
  }
  ImGui::Text("culled: %llu back-facing, %llu outside the view",
              (unsigned long long)s.culled_backface, (unsigned long long)s.culled_frustum);
}

void draw_material(const PanelInput& in, PanelChanges& changes) {
  if (in.selected < 0) {
    ImGui::TextUnformatted("click an object to select it");
    return;
  }
  const Object& object = in.scene->objects[size_t(in.selected)];
  Material m = in.scene->materials[object.material];
  ImGui::TextWrapped("object %d (mesh %u, material %u)", in.selected, object.mesh, object.material);
  bool changed = false;
  if (ImGui::BeginCombo("preset", "metal preset...")) {
    for (const MetalPreset& p : metal_presets()) {
      const std::string name(p.name);
      if (ImGui::Selectable(name.c_str())) {
        m.base_color = p.f0;
        m.metallic = 1.0f;
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  // Three number fields need room; a narrow panel shows the swatch, whose picker has them.
  const ImGuiColorEditFlags fields =
      ImGui::CalcItemWidth() < 150.0f ? ImGuiColorEditFlags_NoInputs : ImGuiColorEditFlags_None;
  changed |= ImGui::ColorEdit3("base colour", &m.base_color.x, ImGuiColorEditFlags_Float | fields);
  changed |= ImGui::SliderFloat("metallic", &m.metallic, 0.0f, 1.0f);
  changed |= ImGui::SliderFloat("roughness", &m.roughness, 0.0f, 1.0f);
  changed |= ImGui::ColorEdit3("emissive", &m.emissive.x,
                               ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR | fields);
  if (changed) changes.material = m;
}

const char* light_kind_name(LightKind kind) {
  switch (kind) {
    case LightKind::point:
      return "point";
    case LightKind::spot:
      return "spot";
    case LightKind::directional:
      return "directional";
  }
  return "?";
}

void draw_lights(const PanelInput& in, PanelChanges& changes) {
  const std::vector<Light>& lights = in.scene->lights;
  for (size_t i = 0; i < lights.size(); ++i) {
    Light light = lights[i];
    ImGui::PushID(int(i));
    const std::string label = std::to_string(i) + " " + light_kind_name(light.kind);
    if (ImGui::TreeNode(label.c_str())) {
      bool changed = false;
      if (light.kind != LightKind::directional) {
        changed |= ImGui::DragFloat3("position", &light.position.x, 0.05f);
      }
      changed |= ImGui::ColorEdit3(
          "colour", &light.color.x,
          ImGuiColorEditFlags_Float |
              (ImGui::CalcItemWidth() < 150.0f ? ImGuiColorEditFlags_NoInputs : 0));
      changed |= ImGui::DragFloat("intensity", &light.intensity, 1.0f, 0.0f, 1e6f);
      if (changed) {
        changes.light = light;
        changes.light_index = uint32_t(i);
      }
      if (ImGui::Button("delete")) {
        changes.delete_light = true;
        changes.light_index = uint32_t(i);
      }
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  if (ImGui::Button("add a light at the eye (L)")) changes.add_light = true;
}

// Each option's widget, with the label its undo step and log line get.
void draw_options(const PanelInput& in, const FrameSettings& frame, PanelChanges& changes) {
  RenderOptions o = render_options_of(frame);
  auto changed = [&](const std::string& label) {
    changes.options = o;
    changes.options_label = label;
    // The first change of a drag starts an undo step; the rest of the drag joins it.
    changes.continuing = !ImGui::IsItemActivated();
  };
  int brdf = int(o.brdf);
  const char* brdfs[] = {"classic", "filament", "blinn-phong"};
  static_assert(uint32_t(Brdf::classic) == 0 && uint32_t(Brdf::filament) == 1 &&
                uint32_t(Brdf::blinn_phong) == 2);
  if (ImGui::Combo("BRDF", &brdf, brdfs, 3)) {
    o.brdf = Brdf(brdf);
    changed(std::string("BRDF ") + brdfs[brdf]);
  }
  if (ImGui::Checkbox("energy compensation", &o.energy_compensation))
    changed(o.energy_compensation ? "energy compensation on" : "energy compensation off");
  if (in.has_environment) {
    bool on = in.environment_on;
    if (ImGui::Checkbox("environment", &on)) changes.toggle_environment = true;
  }
  int view = int(o.view);
  const char* views[] = {"shaded", "normal", "uv", "triangle", "object"};
  if (ImGui::Combo("view", &view, views, 5)) {
    o.view = View(view);
    changed(std::string("view ") + views[view]);
  }
  int tonemap = int(o.tonemap);
  const char* tonemaps[] = {"aces", "reinhard", "clamp"};
  if (ImGui::Combo("tone map", &tonemap, tonemaps, 3)) {
    o.tonemap = ToneMap(tonemap);
    changed(std::string("tone map ") + tonemaps[tonemap]);
  }
  if (ImGui::SliderFloat("exposure (EV)", &o.exposure_ev, -8.0f, 8.0f)) {
    char label[48];
    std::snprintf(label, sizeof(label), "exposure %.2f EV", o.exposure_ev);
    changed(label);
  }
}

// The axis-aligned box around the vertices of `mesh` (empty: lo > hi).
void mesh_box(const Mesh& mesh, glm::vec3& lo, glm::vec3& hi) {
  lo = glm::vec3(std::numeric_limits<float>::max());
  hi = -lo;
  for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
}

}  // namespace

void draw_selection_mark(const Scene& scene, int selected, float width, float height) {
  if (selected < 0 || size_t(selected) >= scene.objects.size() || width <= 0 || height <= 0) return;
  const Object& object = scene.objects[size_t(selected)];
  glm::vec3 lo, hi;
  mesh_box(scene.meshes[object.mesh], lo, hi);
  if (lo.x > hi.x) return;
  const glm::mat4 clip = projection_matrix(scene.camera, width / height) *
                         view_matrix(scene.camera) * object.transform;
  // The rectangle around the box's corners in front of the eye; a box reaching behind the eye
  // spans the whole window.
  glm::vec2 a(std::numeric_limits<float>::max()), b(-std::numeric_limits<float>::max());
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
    const glm::vec4 c = clip * glm::vec4(p, 1.0f);
    if (c.w <= scene.camera.near_plane * 0.5f) {
      a = glm::vec2(0.0f);
      b = glm::vec2(width, height);
      break;
    }
    // Vulkan's clip space: y grows down the image, as window pixels do.
    const glm::vec2 pixel{(c.x / c.w * 0.5f + 0.5f) * width, (c.y / c.w * 0.5f + 0.5f) * height};
    a = glm::min(a, pixel);
    b = glm::max(b, pixel);
  }
  a = glm::clamp(a, glm::vec2(1.0f), glm::vec2(width - 2, height - 2));
  b = glm::clamp(b, glm::vec2(1.0f), glm::vec2(width - 2, height - 2));
  if (a.x >= b.x || a.y >= b.y) return;  // off screen
  // Corner brackets a quarter of the shorter side long, dark under light so they show on any
  // background.
  const float arm = std::max(4.0f, 0.25f * std::min(b.x - a.x, b.y - a.y));
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  for (const auto& [colour, thickness] :
       {std::pair{IM_COL32(0, 0, 0, 200), 4.0f}, std::pair{IM_COL32(255, 200, 40, 255), 2.0f}}) {
    for (int corner = 0; corner < 4; ++corner) {
      const ImVec2 at{corner & 1 ? b.x : a.x, corner & 2 ? b.y : a.y};
      const float sx = corner & 1 ? -arm : arm, sy = corner & 2 ? -arm : arm;
      const ImVec2 bend[] = {{at.x + sx, at.y}, at, {at.x, at.y + sy}};
      draw->AddPolyline(bend, 3, colour, ImDrawFlags_None, thickness);
    }
  }
}

RenderOptions render_options_of(const FrameSettings& f) {
  return {f.brdf, f.tonemap, f.exposure_ev, f.energy_compensation, f.view};
}

void set_render_options(FrameSettings& f, const RenderOptions& o) {
  f.brdf = o.brdf;
  f.tonemap = o.tonemap;
  f.exposure_ev = o.exposure_ev;
  f.energy_compensation = o.energy_compensation;
  f.view = o.view;
}

PanelChanges draw_view_panel(const PanelInput& in, const FrameSettings& frame, float width,
                             float height) {
  PanelChanges changes;
  // At most 40% of the window's width (but room for the widgets in a small window), as tall as
  // its content up to the window's height, scrolling inside beyond that.
  constexpr float kMargin = 8.0f;
  const float panel_width = std::clamp(0.4f * width, std::min(220.0f, width - 2 * kMargin), 460.0f);
  ImGui::SetNextWindowPos(ImVec2(kMargin, kMargin), ImGuiCond_Always);
  ImGui::SetNextWindowSizeConstraints(ImVec2(panel_width, 0.0f),
                                      ImVec2(panel_width, std::max(height - 2 * kMargin, 32.0f)));
  const std::string title = std::string("tessera") + (in.unsaved ? " (unsaved edits)" : "") +
                            "###panel";  // ### keeps the window's identity across titles
  if (ImGui::Begin(title.c_str(), nullptr,
                   ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove)) {
    // Labels get a fixed column at the right; the widgets the rest.
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 7.5f);
    ImGui::TextWrapped("frame %.1f ms (%.1f fps), GPU %.1f ms", in.frame_ms,
                       in.frame_ms > 0 ? 1000.0 / in.frame_ms : 0, in.stats->gpu_total_ms);
    if (ImGui::CollapsingHeader("material", ImGuiTreeNodeFlags_DefaultOpen))
      draw_material(in, changes);
    if (ImGui::CollapsingHeader("render options", ImGuiTreeNodeFlags_DefaultOpen))
      draw_options(in, frame, changes);
    if (ImGui::CollapsingHeader("lights")) draw_lights(in, changes);
    if (ImGui::CollapsingHeader("timing")) draw_timings(in);
    if (ImGui::CollapsingHeader("triangles")) draw_counts(*in.stats);
    // The keys open at the start where the window has room for them under the rest.
    if (ImGui::CollapsingHeader("keys", height >= 600.0f ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
      ImGui::PushTextWrapPos(0.0f);  // wrap at the panel's right edge
      ImGui::TextUnformatted(
          "click selects; Delete deletes; C copies, N adds a sphere, M moves the selection to "
          "the pointer; Ctrl+Z/Y undo/redo; Ctrl+S saves; P screenshot; F frames the scene, "
          "Shift+F the selection, Home the scene's camera; F1 hides this panel");
      ImGui::PopTextWrapPos();
    }
    ImGui::PopItemWidth();
  }
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  changes.rect = {{pos.x, pos.y}, {pos.x + size.x, pos.y + size.y}};
  ImGui::End();
  return changes;
}

}  // namespace tessera
