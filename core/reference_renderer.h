#pragma once
// An independent CPU renderer in double precision, the yardstick for the compute path.
//
// It shares the scene model with the compute path, never its shading code: the BRDF, the
// camera rays and the tone curves here are written from their formulas. Coverage follows the
// same rules as the compute path, so that which triangle owns each pixel can be compared
// exactly: vertices snapped to 8 sub-pixel bits, integer edge functions with the top-left rule,
// clipping against the near plane and the same guard band, reverse depth near/w with ties to
// the lower triangle-instance id (docs/architecture.md). What it does not share is float
// arithmetic: vertices are transformed in double, so a snapped coordinate can differ from the
// GPU's by one sub-pixel step where the exact value lies within float rounding of a step
// boundary (docs/accuracy.md).

#include <cstdint>
#include <vector>

#include "core/frame_settings.h"
#include "core/image.h"
#include "core/image_metrics.h"
#include "core/reference_brdf.h"
#include "core/scene.h"

namespace tessera {

/// Ground truth to measure speed-against-accuracy settings against (docs/accuracy.md, "Ground
/// truth"). The defaults render exactly as without them, bit for bit; any other setting
/// renders every triangle with vertices snapped to 1/4096 px instead of the compute path's
/// 1/256, so ownership is no longer comparable with the compute path's exactly.
struct GroundTruthOptions {
  /// Objects whose mesh has Mesh::analytic_sphere are intersected exactly, as the ellipsoid
  /// their transform makes of that sphere (ray-quadric in object space, normals by the
  /// inverse transpose), instead of through their triangles.
  bool analytic_spheres = false;
  /// N: N x N samples per pixel, sample (i, j) at (x + (i + 0.5) / N, y + (j + 0.5) / N)
  /// rounded to 1/4096 px (exact for N a power of 2), each shaded on its own, averaged with
  /// equal weights (a box filter). 1 to 32 (throws Error otherwise); cost grows as N^2.
  uint32_t supersampling = 1;
};

struct ReferenceSettings {
  /// As for the compute path; energy compensation is reference_compensated_lobes (Kulla &
  /// Conty layering, E from the reference's own quadrature rather than the GPU's table).
  /// Level of detail (frame.lod) picks each object's level with select_lod_level
  /// (core/lod.h), in double.
  FrameSettings frame;
  CullMode cull = CullMode::back;
  /// Monte Carlo directions per lobe and pixel for the environment's light (Scene::environment).
  uint32_t environment_samples = 1024;
  unsigned threads = 0;  // rows are split over this many threads; 0: one per hardware thread
  GroundTruthOptions ground_truth;
};

constexpr uint32_t kNoTriangle = 0xFFFFFFFFu;

/// With supersampling N > 1, or anti-aliasing (FrameSettings::samples > 1), "the pixel" below
/// means its samples: `hdr` is their mean (with anti-aliasing, the compute path's: each
/// distinct triangle shaded once, docs/architecture.md "Anti-aliasing"), `owner` the id seen by
/// most of them (ties to the lower id, empty samples count as kNoTriangle), `depth` the owner's
/// largest near / w among them, `coverage` counts covered samples. An analytic sphere's id is its
/// object's first triangle-instance id; its coverage counts each side a sample's ray meets that is
/// not culled, as a closed mesh's would.
struct ReferenceFrame {
  /// Linear HDR radiance in the model of the compute path: pre-exposed, clamped to 65504 (the
  /// fp16 maximum), divided by the exposure again; as float.
  ImageF hdr;
  Image8 ldr;                   // exposure, tone curve, sRGB of the pixel's hdr, rounded to nearest
  std::vector<uint32_t> owner;  // triangle-instance id per pixel, kNoTriangle where empty
  std::vector<double> depth;    // the owner's near / w at the pixel centre, 0 where empty
  std::vector<uint32_t> coverage;  // samples covered per pixel, over all triangles not culled
  /// Triangles after culling and clipping, less those whose box of at most 2 x 2 pixels covers
  /// no sample: the compute path's FrameStats::raster_triangles (the ground truth's options
  /// drop none of them).
  uint64_t raster_triangles = 0;
  /// How the frame numbered its triangle instances: number_objects(scene), or under level of
  /// detail (FrameSettings::lod) the same slots numbered through the levels chosen.
  ObjectNumbering numbering;
  /// Anti-aliasing only (empty otherwise): the triangle-instance id of every sample,
  /// kNoTriangle where empty, FrameSettings::samples per pixel in the order of the TS_SAMPLES_*
  /// positions, pixel after pixel: laid out as the compute path's visibility buffer.
  std::vector<uint32_t> sample_ids;
  /// Ground truth only (empty otherwise, to spare memory: make it with make_ownership(width,
  /// height, 1, object_ids(frame.numbering, owner))): which object, by its
  /// ObjectNumbering slot, each sample shows, kNoObject where none.
  Ownership ownership;
};

/// Renders `scene` (which must pass validate_scene; throws Error otherwise) at the settings'
/// size. Sizes follow the compute path's limits: 1 to 16384 per side (throws Error otherwise).
/// FrameSettings::samples must be 1, 4, 8 or 16, and 1 with any ground-truth option (throws
/// Error otherwise).
ReferenceFrame render_reference(const Scene& scene, const ReferenceSettings& settings);

/// The object (ObjectNumbering slot) of each triangle-instance id, kNoObject for kNoTriangle;
/// for turning the compute path's visibility buffer into an Ownership (make_ownership). Ids
/// must be below numbering.triangle_count or kNoTriangle (checked).
std::vector<uint32_t> object_ids(const ObjectNumbering& numbering,
                                 const std::vector<uint32_t>& triangle_ids);

/// Geometry of one triangle instance as the reference sees it, for explaining differences:
/// the exact (unsnapped) distance in pixels from the centre of pixel (x, y) to the nearest edge
/// of the triangle's projection after near-plane clipping (infinite if it is culled or behind
/// the camera), and near / w of the triangle's plane along that pixel's ray (0 if the ray
/// misses the plane or hits it behind the camera).
struct ReferenceProbe {
  double edge_distance_px;
  double depth;
};
ReferenceProbe probe_reference(const Scene& scene, const ReferenceSettings& settings,
                               uint32_t triangle_id, uint32_t x, uint32_t y);

}  // namespace tessera
