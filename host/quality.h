#pragma once
// `--quality draft|balanced|reference`: one setting of each speed-against-accuracy knob, picked
// from the Pareto fronts that `tessera tradeoff` measured (docs/tradeoffs.md, "Presets", gives
// the rule and the figures behind every entry). Explicit options win over the preset; the
// preset wins over a scene file's "render" block.

#include <cstdint>
#include <functional>
#include <string>

#include <vulkan/vulkan.h>

#include "compute/environment_gpu.h"
#include "core/frame_settings.h"

namespace tessera {

enum class Quality { none, draft, balanced, reference };

/// What a preset sets. Each command applies the members it has options for.
struct QualityPreset {
  Brdf brdf;
  bool energy_compensation;
  uint32_t samples;  // FrameSettings::samples
  Lod lod;
  float lod_error_px;
  uint32_t max_anisotropy;
  uint32_t env_specular_size;     // EnvironmentOptions::specular_size
  uint32_t env_specular_samples;  // EnvironmentOptions::specular_samples
  HdrFormat hdr_format;
  uint32_t small_triangle_area;  // RendererOptions::small_triangle_max_area
  uint32_t tile_size;            // RendererOptions::tile_size
};

/// Whether a preset's small-triangle area applies on a device of `type`: on GPUs, where the
/// presets' value was measured. A CPU device (lavapipe) keeps its own (raster_tuning): the
/// setting changes the speed and never the image, and the presets keep a speed-only knob at
/// its default unless another setting was measured faster (docs/tradeoffs.md, "Presets"),
/// which on a CPU device is that tuning.
bool preset_sets_small_triangle_area(VkPhysicalDeviceType type);

/// The model's name as --brdf takes it: "classic", "filament", "blinn-phong".
const char* brdf_name(Brdf brdf);

/// The preset's name as --quality takes it: "draft", "balanced", "reference" ("" for none).
const char* quality_name(Quality quality);

/// `option value` as a message names it: as given, or "--quality reference sets --samples 16"
/// where the command line did not give `option` and `quality` set it: a message about a value
/// the user never typed must say where it came from.
std::string option_source(Quality quality, bool given, const std::string& option,
                          const std::string& value);

/// The settings a preset governs as a frame uses them (`frame`, and `env` and `tile_size` where
/// `env` is given: the compute path's), after the options given and the scene file: "--quality
/// reference: filament BRDF with energy compensation, 16 samples per pixel, ...", for `tessera
/// render` to print, since nothing else shows what a preset chose. "" for Quality::none.
std::string quality_settings_line(Quality quality, const FrameSettings& frame,
                                  const EnvironmentOptions* env, uint32_t tile_size);

/// The settings of preset `quality` (not Quality::none).
const QualityPreset& quality_preset(Quality quality);

/// Sets what `quality` picks into `frame` and `env` (either may be null), the tile size and
/// small-triangle area into `tile_size` and `small_triangle_area` (either may be null), except
/// what the command line gave: `given(name)` is true for an option given by name ("--brdf",
/// "--energy-compensation", "--samples", "--lod", "--lod-error", "--anisotropy", "--env-size",
/// "--env-samples", "--hdr-format", "--small-triangle-area", "--tile-size"; the small-triangle
/// area is the preset's on GPUs alone, which the caller decides once the device is known:
/// preset_sets_small_triangle_area). A given --brdf also keeps the preset's energy compensation
/// off, since the tradeoff measures the two as one knob. Nothing for Quality::none.
void apply_quality(Quality quality, const std::function<bool(const std::string&)>& given,
                   FrameSettings* frame, EnvironmentOptions* env, uint32_t* tile_size,
                   uint32_t* small_triangle_area);

}  // namespace tessera
