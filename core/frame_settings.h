#pragma once
// What one frame looks like, independent of the backend that renders it: the compute path
// (compute/renderer.h), the hardware baseline and the CPU reference (core/reference_renderer.h)
// all take these. No Vulkan here.

#include <cstdint>
#include <limits>
#include <string>

#include "core/check.h"
#include "shaders/shared/constants.h"

#include "core/scene.h"

namespace tessera {

/// Level of detail (docs/architecture.md, "Level of detail").
enum class Lod {
  off,        // every object drawn with its mesh as it is
  automatic,  // each object's level chosen per frame from its projected error (core/lod.h)
};

/// Storage of the linear HDR image (docs/architecture.md, "HDR storage").
enum class HdrFormat {
  fp16,  // RGBA16F: 8 bytes a pixel, radiance * 2^EV saturates at 65504 (TS_MAX_HALF)
  fp32,  // RGBA32F: 16 bytes a pixel, saturates only at the largest float (about 3.4e38)
};

/// The largest pre-exposed value an HDR image of `format` stores; larger ones saturate to it.
inline double hdr_max(HdrFormat format) {
  return format == HdrFormat::fp16 ? TS_MAX_HALF : double(std::numeric_limits<float>::max());
}

/// How anti-aliasing weighs the triangles of a pixel whose samples disagree
/// (docs/architecture.md, "Anti-aliasing").
enum class AaCoverage {
  count,       // by the fraction of the pixel's samples each holds
  analytic,    // one triangle and the background: by its outline coverage (shaders/coverage.glsl)
  silhouette,  // one surface and the background: by the area of the pixel its front faces
               // cover, up to its silhouette (shaders/outline.comp)
};

/// The name `--aa-coverage`, `tessera tradeoff` and `tessera bench --json` give `c`.
inline const char* aa_coverage_name(AaCoverage c) {
  return c == AaCoverage::analytic     ? "analytic"
         : c == AaCoverage::silhouette ? "silhouette"
                                       : "count";
}

struct FrameSettings {
  uint32_t width = 512;  // pixels, 1..16384 (TS_MAX_IMAGE_SIDE); renderers throw Error otherwise
  uint32_t height = 512;
  /// Radiance is multiplied by 2^exposure_ev before it is stored in the HDR image
  /// (pre-exposure) and tone mapped; read_hdr / --hdr-out divide it back out.
  float exposure_ev = 0.0f;
  /// Format of the HDR image: fp16 (the default) or fp32, which removes the clamp at 65504
  /// (hdr_max) for twice the memory and bandwidth. The reference renderer clamps alike.
  HdrFormat hdr_format = HdrFormat::fp16;
  ToneMap tonemap = ToneMap::aces;
  View view = View::shaded;  // debug views are written as they are, without exposure or curve
  Brdf brdf = Brdf::classic;
  /// Energy-conserving layering (classic and filament): multiple-scattering compensation of
  /// the specular lobe and a diffuse layer that takes only what it leaves (Kulla & Conty 2017).
  bool energy_compensation = false;
  /// Texture filtering: 1 is trilinear; 2 to 16 take up to that many trilinear probes along
  /// the footprint's longer axis (anisotropic filtering).
  uint32_t max_anisotropy = 1;
  /// Level of detail: off draws the meshes as they are; automatic draws each object at the
  /// coarsest level of its chain (core/lod.h) whose error projects to at most lod_error_px
  /// pixels (> 0 and finite; renderers throw Error otherwise).
  Lod lod = Lod::off;
  float lod_error_px = 0.5f;
  /// Anti-aliasing: visibility samples per pixel, 1, 4, 8 or 16, at the fixed positions of
  /// shaders/shared/constants.h (TS_SAMPLES_*); each distinct triangle of a pixel is shaded
  /// once and weighted by its coverage (aa_coverage; docs/architecture.md, "Anti-aliasing").
  uint32_t samples = 1;
  /// With samples > 1: weigh a pixel's triangles by their share of its samples (the default),
  /// or, where its samples see one triangle and the background, by the triangle's outline
  /// coverage (analytic; docs/tradeoffs.md says why it is not the default).
  AaCoverage aa_coverage = AaCoverage::count;
  /// Under silhouette coverage: the steps of the walk that measures a pixel (the first triangle
  /// step 0, its neighbours taken in step 1, ...), after which it stops with the area found so
  /// far; 0 for no limit (the default). At least 2. Fewer steps are faster and, where triangles
  /// are small against a pixel, less exact (docs/tradeoffs.md, "Anti-aliasing").
  uint32_t silhouette_steps = 0;
  /// Compute renderer: whether the visibility buffer still holds the frame's keys after it
  /// (Renderer::read_visibility, picking). Off, the shading pass empties each key it reads, and
  /// the next frame skips filling the buffer (docs/architecture.md, "The frame"): for frames
  /// nobody reads the keys of, such as `tessera bench`'s timed ones. Frames with silhouette
  /// coverage keep them (their outline pass reads them after shading).
  bool keep_visibility = true;
};

/// Throws Error naming `samples` unless it is 1, 4, 8 or 16.
inline void validate_samples(uint32_t samples) {
  if (samples != 1 && samples != 4 && samples != 8 && samples != 16) {
    throw Error("samples per pixel " + std::to_string(samples) + " is not 1, 4, 8 or 16");
  }
}

}  // namespace tessera
