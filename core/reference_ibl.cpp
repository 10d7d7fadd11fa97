// Image-based lighting in the reference: brute-force Monte Carlo over the hemisphere.
#include <algorithm>
#include <cmath>

#include "core/environment.h"
#include "core/reference_brdf.h"

namespace tessera {
namespace {

using glm::dvec2;
using glm::dvec3;

// Hammersley point i of n (van der Corput radical inverse in base 2).
dvec2 hammersley(uint32_t i, uint32_t n) {
  uint32_t bits = i;
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return {(i + 0.5) / n, bits * 2.3283064365386963e-10};
}

}  // namespace

dvec3 reference_environment_light(const Environment& environment, Brdf variant, dvec3 n, dvec3 v,
                                  const Material& m, dvec3 specular_scale, uint32_t samples,
                                  bool energy_compensation) {
  samples = std::max(samples, 1u);
  if (energy_compensation) specular_scale = dvec3(1.0);
  auto lobes = [&](dvec3 l) {
    return energy_compensation ? reference_compensated_lobes(variant, n, v, l, m)
                               : reference_brdf_lobes(variant, n, v, l, m);
  };
  // Orthonormal basis around n (Duff et al. 2017).
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z), b = n.x * n.y * a;
  const dvec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const dvec3 bt(b, sign + n.y * n.y * a, -n.y);
  auto to_world = [&](dvec3 local) { return t * local.x + bt * local.y + n * local.z; };

  const double alpha = reference_shading_params(m).alpha;
  dvec3 diffuse(0.0), specular(0.0);
  for (uint32_t i = 0; i < samples; ++i) {
    const dvec2 u = hammersley(i, samples);
    const double phi = 2.0 * kPi * u.y;
    // Diffuse lobe: cosine-distributed l, pdf = cos / pi, so f cos / pdf = f pi.
    {
      const double r = std::sqrt(u.x);
      const dvec3 l = to_world({r * std::cos(phi), r * std::sin(phi), std::sqrt(1.0 - u.x)});
      diffuse += lobes(l).diffuse * kPi * environment_radiance(environment, l);
    }
    // Specular lobe: half vectors distributed as D(h) (n.h), pdf_l = D (n.h) / (4 v.h).
    {
      const double cos2 = (1.0 - u.x) / (1.0 + (alpha * alpha - 1.0) * u.x);
      const double cos_h = std::sqrt(cos2), sin_h = std::sqrt(std::max(0.0, 1.0 - cos2));
      const dvec3 h = to_world({sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h});
      const double v_dot_h = glm::dot(v, h);
      if (v_dot_h <= 0.0) continue;
      const dvec3 l = 2.0 * v_dot_h * h - v;
      const double n_dot_l = glm::dot(n, l);
      if (n_dot_l <= 0.0) continue;
      const double a2 = alpha * alpha;
      const double denom = cos2 * (a2 - 1.0) + 1.0;
      const double pdf = a2 / (kPi * denom * denom) * cos_h / (4.0 * v_dot_h);
      specular += lobes(l).specular * n_dot_l / pdf * environment_radiance(environment, l);
    }
  }
  return (diffuse + specular * specular_scale) / double(samples);
}

}  // namespace tessera
