#include "host/quality.h"

#include <cstdio>

#include "core/check.h"

namespace tessera {

// The table of docs/tradeoffs.md, "Presets" (tests/quality_test.cpp reads it from there), which
// gives the rule and the measured figures behind each entry: per knob, on its measured front,
// draft takes the cheapest setting within 0.01 mean relative error of the knob's best setting,
// balanced the cheapest within 0.001, reference the best.
const QualityPreset& quality_preset(Quality quality) {
  static const QualityPreset draft{.brdf = Brdf::classic,
                                   .energy_compensation = true,
                                   .samples = 1,
                                   .lod = Lod::automatic,
                                   .lod_error_px = 0.5f,
                                   .max_anisotropy = 1,
                                   .env_specular_size = 16,
                                   .env_specular_samples = 8,
                                   .hdr_format = HdrFormat::fp16,
                                   .small_triangle_area = 128,
                                   .tile_size = 16};
  static const QualityPreset balanced{.brdf = Brdf::filament,
                                      .energy_compensation = true,
                                      .samples = 4,
                                      .lod = Lod::off,
                                      .lod_error_px = 0.5f,
                                      .max_anisotropy = 4,
                                      .env_specular_size = 32,
                                      .env_specular_samples = 32,
                                      .hdr_format = HdrFormat::fp16,
                                      .small_triangle_area = 128,
                                      .tile_size = 16};
  static const QualityPreset reference{.brdf = Brdf::filament,
                                       .energy_compensation = true,
                                       .samples = 16,
                                       .lod = Lod::off,
                                       .lod_error_px = 0.5f,
                                       .max_anisotropy = 16,
                                       .env_specular_size = 256,
                                       .env_specular_samples = 512,
                                       .hdr_format = HdrFormat::fp32,
                                       .small_triangle_area = 128,
                                       .tile_size = 16};
  switch (quality) {
    case Quality::draft:
      return draft;
    case Quality::balanced:
      return balanced;
    case Quality::reference:
      return reference;
    case Quality::none:
      break;
  }
  TESSERA_CHECK(!"quality_preset needs a preset");
  return draft;
}

const char* brdf_name(Brdf brdf) {
  return brdf == Brdf::classic ? "classic" : brdf == Brdf::filament ? "filament" : "blinn-phong";
}

const char* quality_name(Quality quality) {
  switch (quality) {
    case Quality::draft:
      return "draft";
    case Quality::balanced:
      return "balanced";
    case Quality::reference:
      return "reference";
    case Quality::none:
      break;
  }
  return "";
}

std::string option_source(Quality quality, bool given, const std::string& option,
                          const std::string& value) {
  const std::string set = option + " " + value;
  if (given || quality == Quality::none) return set;
  return "--quality " + std::string(quality_name(quality)) + " sets " + set;
}

std::string quality_settings_line(Quality quality, const FrameSettings& frame,
                                  const EnvironmentOptions* env, uint32_t tile_size) {
  if (quality == Quality::none) return "";
  // Blinn-Phong has no energy compensation (shaders/lighting.glsl).
  const bool ec = frame.energy_compensation && frame.brdf != Brdf::blinn_phong;
  std::string out = "--quality " + std::string(quality_name(quality)) + ": " +
                    brdf_name(frame.brdf) + " BRDF" + (ec ? " with energy compensation" : "") +
                    ", " + std::to_string(frame.samples) +
                    (frame.samples == 1 ? " sample" : " samples") + " per pixel";
  if (frame.samples > 1)
    out += std::string(" (") + aa_coverage_name(frame.aa_coverage) + " coverage)";
  char lod[48];
  std::snprintf(lod, sizeof(lod), "auto at %g px", double(frame.lod_error_px));
  out += ", level of detail " + std::string(frame.lod == Lod::automatic ? lod : "off");
  out += frame.max_anisotropy == 1
             ? ", trilinear texture filtering"
             : ", " + std::to_string(frame.max_anisotropy) + "x anisotropic texture filtering";
  if (env)
    out += ", environment cube of " + std::to_string(env->specular_size) + " px and " +
           std::to_string(env->specular_samples) + " samples per texel";
  out += frame.hdr_format == HdrFormat::fp32 ? ", fp32 HDR" : ", fp16 HDR";
  if (env) out += ", tiles of " + std::to_string(tile_size) + " px";
  return out;
}

bool preset_sets_small_triangle_area(VkPhysicalDeviceType type) {
  return type != VK_PHYSICAL_DEVICE_TYPE_CPU;
}

void apply_quality(Quality quality, const std::function<bool(const std::string&)>& given,
                   FrameSettings* frame, EnvironmentOptions* env, uint32_t* tile_size,
                   uint32_t* small_triangle_area) {
  if (quality == Quality::none) return;
  const QualityPreset& p = quality_preset(quality);
  if (frame) {
    if (!given("--brdf")) frame->brdf = p.brdf;
    if (!given("--brdf") && !given("--energy-compensation"))
      frame->energy_compensation = p.energy_compensation;
    if (!given("--samples")) frame->samples = p.samples;
    if (!given("--lod")) frame->lod = p.lod;
    if (!given("--lod-error")) frame->lod_error_px = p.lod_error_px;
    if (!given("--anisotropy")) frame->max_anisotropy = p.max_anisotropy;
    if (!given("--hdr-format")) frame->hdr_format = p.hdr_format;
  }
  if (env) {
    if (!given("--env-size")) env->specular_size = p.env_specular_size;
    if (!given("--env-samples")) env->specular_samples = p.env_specular_samples;
  }
  if (tile_size && !given("--tile-size")) *tile_size = p.tile_size;
  if (small_triangle_area && !given("--small-triangle-area"))
    *small_triangle_area = p.small_triangle_area;
}

}  // namespace tessera
