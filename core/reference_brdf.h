#pragma once
// The shading model's BRDF in double precision, written from its formulas for the reference
// renderer (never sharing code with shaders/brdf.glsl), and the reference's image-based
// lighting by Monte Carlo integration.

#include <cstdint>
#include <numbers>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "shaders/shared/constants.h"

namespace tessera {

// The shading model's guards (TS_MIN_*) are shared with the compute path through
// shaders/shared/constants.h, which gives the reasons: they are part of the model, not of
// either implementation.
inline constexpr double kPi = std::numbers::pi;

/// The shading parameters of a material (the reference's counterpart of brdf.glsl's
/// PixelParams): the glTF 2.0 metallic-roughness model with metallic clamped to [0, 1] and
/// roughness to [TS_MIN_PERCEPTUAL_ROUGHNESS, 1]. Every material parameter that changes the
/// BRDF is applied here, once, for the lights, the environment and energy compensation alike.
struct ShadingParams {
  glm::dvec3 diffuse_color;  // Lambert albedo
  glm::dvec3 f0;             // specular reflectance at normal incidence
  double roughness;          // perceptual
  double alpha;              // roughness^2
};
ShadingParams reference_shading_params(const Material& m);

/// The two lobes of f(l, v) (without the cosine): diffuse and specular, each 0 for N.L <= 0.
struct BrdfLobes {
  glm::dvec3 diffuse, specular;
};
BrdfLobes reference_brdf_lobes(Brdf variant, glm::dvec3 n, glm::dvec3 v, glm::dvec3 l,
                               const Material& m);

/// The BRDF f(l, v) of `variant` for unit normal n, view v and light l (without the cosine),
/// with the shading model's guards (roughness >= 0.045, N.V >= 1e-4); 0 for N.L <= 0.
glm::dvec3 reference_brdf(Brdf variant, glm::dvec3 n, glm::dvec3 v, glm::dvec3 l,
                          const Material& m);

/// Directional albedo E of the specular lobe of `variant` with F = 1, for view cosine n_dot_v
/// and perceptual roughness (>= 0.045 applied): a 64 x 64 midpoint quadrature over half vectors
/// distributed as GGX. The reference's independent counterpart of the GPU's DFG table.
double reference_specular_albedo(Brdf variant, double n_dot_v, double roughness);

/// The same quadrature, also weighted by the Schlick factor (1 - v.h)^5: (E_Fc, E).
glm::dvec2 reference_specular_albedo_terms(Brdf variant, double n_dot_v, double roughness);

/// (E_Fc, E) of one variant and roughness at kPoints cosines (i / (kPoints - 1))^2, denser at
/// grazing angles where E bends most, read with linear interpolation in sqrt(cosine), and the
/// cosine-weighted means 2 int g(mu) mu dmu of E, E_Fc and E_Fc / E (a 64-point midpoint rule over
/// mu of the quadrature itself).
struct SpecularAlbedoTable {
  static constexpr int kPoints = 129;
  glm::dvec2 terms[kPoints];
  glm::dvec3 means{0.0};
  glm::dvec2 at(double n_dot_v) const;
};
/// Built on first use per (variant, roughness >= 0.045 applied) and cached; thread-safe.
const SpecularAlbedoTable& reference_specular_albedo_table(Brdf variant, double roughness);

/// The specular albedo at any roughness, as energy compensation reads it: the tables of the two
/// roughness nodes k / kNodes around it (the lowest node raised to 0.045), mixed linearly by
/// roughness; at a node, its table alone. A roughness map makes nearly every sample's roughness
/// a new value, and a table (193 quadratures) per value made a textured ground truth take an hour;
/// the nodes' tables are built once each. Mixing changes E by at most 1.3e-5 against the table
/// of the exact roughness (filament at roughness 0.08, grazing; 7e-7 for classic), the means by
/// 3e-7: below the quadrature's own error (docs/accuracy.md, "Ground truth").
struct SpecularAlbedoLookup {
  static constexpr int kNodes = 1024;
  const SpecularAlbedoTable* lower;
  const SpecularAlbedoTable* upper;  // equals lower at a node
  double weight;                     // of upper, in [0, 1)
  glm::dvec2 at(double n_dot_v) const;
  glm::dvec3 means() const;
};
/// Builds the nodes' tables on first use, each once, without holding other threads' lookups
/// back; thread-safe. Roughness is clamped to [0.045, 1]; `variant` classic or filament
/// (blinn-phong has no compensation; checked).
SpecularAlbedoLookup reference_specular_albedo_lookup(Brdf variant, double roughness);

/// The lobes with energy compensation (Kulla & Conty 2017): the specular lobe times
/// 1 + F0 (1 / E(n.v) - 1), and a Lambert diffuse lobe (for classic too, whose 1 - F weight it
/// replaces) times (1 - Es(n.v)) (1 - Es(n.l)) / (1 - Es_avg), Es the compensated specular
/// layer's albedo with Schlick Fresnel and Es_avg its cosine-weighted mean. Reciprocal in its
/// diffuse lobe; a white material's directional albedo is 1. Blinn-Phong: the plain lobes.
BrdfLobes reference_compensated_lobes(Brdf variant, glm::dvec3 n, glm::dvec3 v, glm::dvec3 l,
                                      const Material& m);

/// Radiance reflected towards unit v by a surface with unit normal n and material m lit by
/// `environment` alone: the integral of f(l, v) L(l) (n.l) over the hemisphere, estimated with
/// `samples` stratified (Hammersley) directions per lobe: cosine-distributed for the diffuse
/// lobe, GGX-distributed half vectors for the specular lobe (times `specular_scale`). No
/// split-sum, no prefiltering: the yardstick for the GPU's image-based lighting.
/// With `energy_compensation` the lobes are reference_compensated_lobes' (specular_scale is
/// then ignored).
glm::dvec3 reference_environment_light(const Environment& environment, Brdf variant, glm::dvec3 n,
                                       glm::dvec3 v, const Material& m, glm::dvec3 specular_scale,
                                       uint32_t samples, bool energy_compensation = false);

}  // namespace tessera
