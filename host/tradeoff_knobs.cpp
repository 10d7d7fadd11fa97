// The knobs of `tessera tradeoff` and their settings (docs/tradeoffs.md says why these).
#include <algorithm>
#include <cstdio>
#include <string>

#include "core/check.h"
#include "core/closest_name.h"
#include "core/lod.h"
#include "core/mesh.h"
#include "host/tradeoff.h"

namespace tessera {

const std::vector<KnobInfo>& knobs() {
  static const std::vector<KnobInfo> list = {
      {"brdf", "BRDF variant and energy compensation (blinn-phong, classic, filament, +ec)"},
      {"tessellation", "sphere slices 8..128 (fixed tessellations of every sphere)"},
      {"lod", "level of detail: off, then auto at 0.25..4 px of projected error"},
      {"anisotropy", "texture filtering: trilinear, then 2..16 anisotropic probes"},
      {"env-size", "side of the prefiltered specular cube, 16..256 texels"},
      {"env-samples", "GGX samples per prefiltered texel, 8..2048"},
      {"samples", "visibility samples per pixel (anti-aliasing): 1, 4, 8, 16"},
      {"aa-coverage", "anti-aliasing weights (at 4 samples if 1): count, analytic, silhouette"},
      {"aa-walk-steps", "silhouette coverage's walk (at 4 samples if 1): 2..6 steps, no limit"},
      {"hdr", "storage of the HDR image: fp16, fp32"},
      {"small-triangle", "pixel-box area rasterized one thread per triangle (speed only)"},
      {"tile-size", "side of the binned rasterizer's tiles: 8, 16 px (speed only)"},
      {"depth-rejection", "hierarchical depth rejection: off, on (speed only)"},
      {"shade-tiles", "shading by tiles: off, on (speed only)"},
      {"raster-shade", "small frames rasterized and shaded in one pass: off, on (speed only)"},
  };
  return list;
}

namespace {

// A copy of the command line's settings labelled `label`, marked default if it changes nothing.
KnobSetting base(const std::string& knob, const std::string& label, const FrameSettings& frame,
                 const RendererOptions& options) {
  KnobSetting s;
  s.knob = knob;
  s.label = label;
  s.frame = frame;
  s.renderer = options;
  return s;
}

// What the objects of `scene` draw with (materials and meshes no object uses cannot matter).
bool draws_a_sphere(const Scene& scene) {
  for (const Object& o : scene.objects)
    if (o.mesh < scene.meshes.size() && scene.meshes[o.mesh].analytic_sphere) return true;
  return false;
}

bool draws_a_texture(const Scene& scene) {
  for (const Object& o : scene.objects) {
    if (o.material >= scene.materials.size()) continue;
    const Material& m = scene.materials[o.material];
    for (uint32_t map : {m.base_color_map, m.metallic_roughness_map, m.normal_map, m.occlusion_map,
                         m.emissive_map})
      if (map != kNoTexture) return true;
  }
  return false;
}

// One sphere mesh's tessellation, in the terms of the knob's settings ("N slices": N segments
// and half as many stacks).
std::string sphere_tessellation(const Mesh& mesh) {
  const MeshShape shape = shape_of(mesh);
  if (shape.kind == MeshShape::Kind::icosphere) return "icosphere level " + std::to_string(shape.a);
  if (shape.kind == MeshShape::Kind::uv_sphere) {
    std::string out = std::to_string(shape.a) + " slices";
    if (shape.b != shape.a / 2) out += ", " + std::to_string(shape.b) + " stacks";
    return out;
  }
  // A sphere no builder makes as it is (a model's, say): its size says what it costs.
  return std::to_string(mesh.triangle_count()) + " triangles";
}

std::string known_knobs() {
  std::string names;
  for (const KnobInfo& k : knobs()) names += (names.empty() ? "" : ", ") + std::string(k.name);
  return names;
}

}  // namespace

std::string coarse_truth_warning(const std::vector<std::string>& knobs, const FrameSettings& frame,
                                 uint32_t truth_samples) {
  uint32_t most = frame.samples;
  for (const std::string& knob : knobs) {
    for (const KnobSetting& s : knob_settings(knob, frame, {}))
      most = std::max(most, s.frame.samples);
  }
  const uint32_t truth = truth_samples * truth_samples;
  if (most <= 1 || truth > most) return "";
  uint32_t enough = truth_samples;
  while (enough * enough <= most) ++enough;
  return "the ground truth takes " + std::to_string(truth_samples) + " x " +
         std::to_string(truth_samples) + " = " + std::to_string(truth) +
         " samples per pixel, no more than the " + std::to_string(most) +
         " of the settings measured at the most: their edge errors are the truth's as much as "
         "theirs (give --truth-samples " +
         std::to_string(enough) + " or more)";
}

std::string knob_cannot_matter(const std::string& knob, const Scene& scene,
                               const FrameSettings& frame) {
  if (knob == "brdf" && scene.lights.empty() && !scene.environment) {
    // Ambient and emitted light are added as they are (shaders/lighting.glsl).
    return "the scene has no lights and no environment, the only light a BRDF shades";
  }
  if (knob == "tessellation" && !draws_a_sphere(scene))
    return "the scene draws no spheres, the only meshes the knob re-tessellates";
  if (knob == "anisotropy" && !draws_a_texture(scene))
    return "no material the scene draws with has a texture map, the only thing it filters";
  if ((knob == "env-size" || knob == "env-samples") && !scene.environment)
    return "the scene has no environment";
  if (knob == "lod") {
    const std::vector<LodChain> chains = build_lod_chains(scene);
    const bool levels =
        std::any_of(scene.objects.begin(), scene.objects.end(), [&](const Object& o) {
          return o.mesh < chains.size() && chains[o.mesh].levels.size() > 1;
        });
    if (!levels) return "no mesh the scene draws has a level of detail but its own";
  }
  if (knob == "raster-shade") {
    // rasterizes_and_shades_in_one_pass (compute/renderer.cpp) takes one-sample frames
    // without level of detail only.
    if (frame.samples != 1)
      return "the frames are at " + std::to_string(frame.samples) +
             " samples, and only frames at 1 take the one pass";
    if (frame.lod == Lod::automatic)
      return "the frames have level of detail, and only frames without take the one pass";
  }
  return "";
}

std::string scene_sphere_tessellation(const Scene& scene) {
  std::vector<uint32_t> seen;
  std::vector<std::string> kinds;
  for (const Object& o : scene.objects) {
    if (o.mesh >= scene.meshes.size() || !scene.meshes[o.mesh].analytic_sphere) continue;
    if (std::find(seen.begin(), seen.end(), o.mesh) != seen.end()) continue;
    seen.push_back(o.mesh);
    const std::string kind = sphere_tessellation(scene.meshes[o.mesh]);
    if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) kinds.push_back(kind);
  }
  if (kinds.size() <= 1) return kinds.empty() ? "" : kinds[0];
  // A label, not a list: the first two, and how many more.
  std::string out = "mixed: " + kinds[0] + "; " + kinds[1];
  if (kinds.size() > 2) out += "; " + std::to_string(kinds.size() - 2) + " more";
  return out;
}

std::vector<KnobSetting> knob_settings(const std::string& knob, const FrameSettings& frame,
                                       const RendererOptions& options, const Scene* scene) {
  std::vector<KnobSetting> out;
  if (knob == "brdf") {
    struct Variant {
      const char* label;
      Brdf brdf;
      bool ec;
    };
    for (const Variant v :
         {Variant{"blinn-phong", Brdf::blinn_phong, false},
          Variant{"classic", Brdf::classic, false}, Variant{"classic+ec", Brdf::classic, true},
          Variant{"filament", Brdf::filament, false},
          Variant{"filament+ec", Brdf::filament, true}}) {
      KnobSetting s = base(knob, v.label, frame, options);
      s.frame.brdf = v.brdf;
      s.frame.energy_compensation = v.ec;
      s.is_default = v.brdf == frame.brdf && v.ec == frame.energy_compensation;
      out.push_back(s);
    }
  } else if (knob == "tessellation") {
    const std::string spheres = scene ? scene_sphere_tessellation(*scene) : "";
    KnobSetting own = base(knob, spheres.empty() ? "scene's own" : "scene's own (" + spheres + ")",
                           frame, options);
    own.is_default = true;
    out.push_back(own);
    for (uint32_t segments : {8u, 16u, 32u, 64u, 128u}) {
      // The scene's own spheres already measure this one (the spheres scene's 64 slices were
      // rendered and timed twice, two marks on one spot).
      if (spheres == std::to_string(segments) + " slices") continue;
      KnobSetting s = base(knob, std::to_string(segments) + " slices", frame, options);
      s.sphere_segments = segments;
      out.push_back(s);
    }
  } else if (knob == "lod") {
    KnobSetting off = base(knob, "off", frame, options);
    off.frame.lod = Lod::off;
    off.is_default = frame.lod == Lod::off;
    out.push_back(off);
    // From a quarter pixel, below the half pixel of the default, to 4 px, where the coarsest
    // levels already show as polygons (docs/tradeoffs.md, "Level of detail").
    for (const float px : {0.25f, 0.5f, 1.0f, 2.0f, 4.0f}) {
      char label[32];
      std::snprintf(label, sizeof(label), "auto %g px", double(px));
      KnobSetting s = base(knob, label, frame, options);
      s.frame.lod = Lod::automatic;
      s.frame.lod_error_px = px;
      s.is_default = frame.lod == Lod::automatic && frame.lod_error_px == px;
      out.push_back(s);
    }
  } else if (knob == "hdr") {
    for (const HdrFormat f : {HdrFormat::fp16, HdrFormat::fp32}) {
      KnobSetting s = base(knob, f == HdrFormat::fp16 ? "fp16" : "fp32", frame, options);
      s.frame.hdr_format = f;
      s.is_default = f == frame.hdr_format;
      out.push_back(s);
    }
  } else if (knob == "anisotropy") {
    for (uint32_t n : {1u, 2u, 4u, 8u, 16u}) {
      KnobSetting s = base(knob, n == 1 ? "trilinear" : std::to_string(n) + "x", frame, options);
      s.frame.max_anisotropy = n;
      s.is_default = n == frame.max_anisotropy;
      out.push_back(s);
    }
  } else if (knob == "env-size") {
    for (uint32_t side : {16u, 32u, 64u, 128u, 256u}) {
      KnobSetting s = base(knob, std::to_string(side) + " px", frame, options);
      s.renderer.environment.specular_size = side;
      s.is_default = side == options.environment.specular_size;
      out.push_back(s);
    }
  } else if (knob == "env-samples") {
    for (uint32_t n : {8u, 32u, 128u, 512u, 2048u}) {
      KnobSetting s = base(knob, std::to_string(n), frame, options);
      s.renderer.environment.specular_samples = n;
      s.is_default = n == options.environment.specular_samples;
      out.push_back(s);
    }
  } else if (knob == "samples") {
    for (uint32_t n : {1u, 4u, 8u, 16u}) {
      KnobSetting s =
          base(knob, n == 1 ? "1 sample" : std::to_string(n) + " samples", frame, options);
      s.frame.samples = n;
      s.is_default = n == frame.samples;
      out.push_back(s);
    }
  } else if (knob == "aa-coverage") {
    // At the command line's sample count, or 4 where that is 1 (one sample has no weights).
    const uint32_t n = std::max(frame.samples, 4u);
    for (const AaCoverage c : {AaCoverage::count, AaCoverage::analytic, AaCoverage::silhouette}) {
      KnobSetting s =
          base(knob, std::to_string(n) + " samples, " + aa_coverage_name(c), frame, options);
      s.frame.samples = n;
      s.frame.aa_coverage = c;
      s.is_default = c == frame.aa_coverage;  // the command line's mode, at its samples or 4
      out.push_back(s);
    }
  } else if (knob == "aa-walk-steps") {
    // Silhouette coverage at the command line's sample count, or 4 where that is 1.
    const uint32_t n = std::max(frame.samples, 4u);
    for (uint32_t steps : {2u, 3u, 4u, 6u, 0u}) {
      KnobSetting s =
          base(knob,
               std::to_string(n) + " samples, " +
                   (steps == 0 ? std::string("no limit") : std::to_string(steps) + " steps"),
               frame, options);
      s.frame.samples = n;
      s.frame.aa_coverage = AaCoverage::silhouette;
      s.frame.silhouette_steps = steps;
      s.is_default = steps == frame.silhouette_steps;  // the command line's limit, as aa-coverage
      out.push_back(s);
    }
  } else if (knob == "small-triangle") {
    for (uint32_t area : {0u, 16u, 64u, 128u, 256u, 4096u}) {
      KnobSetting s = base(knob, std::to_string(area) + " px", frame, options);
      s.renderer.small_triangle_max_area = area;
      s.is_default = area == options.small_triangle_max_area;
      s.speed_only = true;
      out.push_back(s);
    }
  } else if (knob == "tile-size") {
    for (uint32_t side : {8u, 16u}) {
      KnobSetting s = base(knob, std::to_string(side) + " px", frame, options);
      s.renderer.tile_size = side;
      s.is_default = side == options.tile_size;
      s.speed_only = true;
      out.push_back(s);
    }
  } else if (knob == "depth-rejection" || knob == "shade-tiles" || knob == "raster-shade") {
    for (bool on : {false, true}) {
      KnobSetting s = base(knob, on ? "on" : "off", frame, options);
      if (knob == "depth-rejection") {
        s.renderer.depth_rejection = on;
        s.is_default = on == options.depth_rejection;
      } else if (knob == "shade-tiles") {
        s.renderer.shade_tiles = on;
        s.is_default = on == options.shade_tiles;
      } else {
        // The one pass does not go with shading by tiles (a CPU device's default): "on" turns
        // that off, so that the setting measures the one pass.
        s.renderer.raster_shade = on;
        if (on) s.renderer.shade_tiles = false;
        const bool one_pass =
            options.raster_shade.value_or(false) && !options.shade_tiles.value_or(false);
        s.is_default = on == one_pass;
      }
      s.speed_only = true;
      out.push_back(s);
    }
  } else {
    std::vector<std::string> names;
    for (const KnobInfo& k : knobs()) names.push_back(k.name);
    const std::string near = closest_name(knob, names);
    throw Error("unknown knob '" + knob + "' (known: " + known_knobs() + ")" +
                (near.empty() ? "" : ", did you mean '" + near + "'?"));
  }
  return out;
}

}  // namespace tessera
