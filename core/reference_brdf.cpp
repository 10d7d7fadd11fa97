#include "core/reference_brdf.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>

#include "core/check.h"

namespace tessera {

using glm::dvec3;

namespace {

// GGX / Trowbridge-Reitz normal distribution (Walter et al. 2007), alpha = roughness^2.
double ggx_distribution(double n_dot_h, double alpha) {
  const double a2 = alpha * alpha;
  const double denom = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
  return a2 / (kPi * denom * denom);
}

// Smith's masking-shadowing as the product of two Schlick-GGX terms, k = (r + 1)^2 / 8
// (Karis 2013).
double smith_schlick_ggx(double n_dot_v, double n_dot_l, double roughness) {
  const double k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
  auto g1 = [k](double c) { return c / (c * (1.0 - k) + k); };
  return g1(n_dot_v) * g1(n_dot_l);
}

// Schlick's approximation of the Fresnel reflectance (Schlick 1994).
dvec3 schlick_fresnel(double cos_theta, dvec3 f0) {
  return f0 + (dvec3(1.0) - f0) * std::pow(1.0 - cos_theta, 5.0);
}

// Height-correlated Smith masking-shadowing for GGX (Heitz 2014), as G / (4 N.L N.V).
double smith_ggx_correlated_visibility(double n_dot_v, double n_dot_l, double alpha) {
  const double a2 = alpha * alpha;
  const double lambda_v = n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
  const double lambda_l = n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
  return 0.5 / (lambda_v + lambda_l);
}

// Normalized Blinn-Phong lobe (n + 8) / (8 pi) cos^n, n = 2 / alpha^2 - 2 (Walter et al. 2007).
double blinn_phong_lobe(double n_dot_h, double alpha) {
  const double n = 2.0 / (alpha * alpha) - 2.0;
  return (n + 8.0) / (8.0 * kPi) * std::pow(n_dot_h, n);
}

}  // namespace

ShadingParams reference_shading_params(const Material& m) {
  ShadingParams p;
  const double metallic = std::clamp(double(m.metallic), 0.0, 1.0);
  const dvec3 base(m.base_color);
  p.roughness = std::clamp(double(m.roughness), TS_MIN_PERCEPTUAL_ROUGHNESS, 1.0);
  p.alpha = p.roughness * p.roughness;
  p.f0 = glm::mix(dvec3(TS_DIELECTRIC_F0), base, metallic);
  p.diffuse_color = (1.0 - metallic) * base;
  return p;
}

BrdfLobes reference_brdf_lobes(Brdf variant, dvec3 n, dvec3 v, dvec3 l, const Material& m) {
  const double n_dot_l = glm::dot(n, l);
  if (n_dot_l <= 0.0) return {dvec3(0.0), dvec3(0.0)};
  const double n_dot_v = std::max(glm::dot(n, v), TS_MIN_N_DOT_V);
  const dvec3 half_vector = v + l;
  const double length2 = glm::dot(half_vector, half_vector);
  const dvec3 h = length2 > 0.0 ? half_vector / std::sqrt(length2) : n;
  const auto [diffuse_color, f0, roughness, alpha] = reference_shading_params(m);
  const double n_dot_h = std::clamp(glm::dot(n, h), 0.0, 1.0);
  if (variant == Brdf::blinn_phong)
    return {diffuse_color / kPi, f0 * blinn_phong_lobe(n_dot_h, alpha)};
  const dvec3 fresnel = schlick_fresnel(std::clamp(glm::dot(v, h), 0.0, 1.0), f0);
  const double d = ggx_distribution(n_dot_h, alpha);
  if (variant == Brdf::filament) {
    return {diffuse_color / kPi,
            d * smith_ggx_correlated_visibility(n_dot_v, n_dot_l, alpha) * fresnel};
  }
  const double g = smith_schlick_ggx(n_dot_v, n_dot_l, roughness);
  return {(dvec3(1.0) - fresnel) * diffuse_color / kPi,
          d * g * fresnel / (4.0 * n_dot_l * n_dot_v)};
}

dvec3 reference_brdf(Brdf variant, dvec3 n, dvec3 v, dvec3 l, const Material& m) {
  const BrdfLobes lobes = reference_brdf_lobes(variant, n, v, l, m);
  return lobes.diffuse + lobes.specular;
}

glm::dvec2 reference_specular_albedo_terms(Brdf variant, double n_dot_v, double roughness) {
  roughness = std::clamp(roughness, TS_MIN_PERCEPTUAL_ROUGHNESS, 1.0);
  n_dot_v = std::clamp(n_dot_v, TS_MIN_N_DOT_V, 1.0);
  const double alpha = roughness * roughness;
  const double sin_v = std::sqrt(1.0 - n_dot_v * n_dot_v);
  const dvec3 v(sin_v, 0.0, n_dot_v);
  constexpr int kSteps = 64;
  // Half vectors steeper than theta_max = (theta_v + pi/2) / 2 reflect v below the horizon
  // for every phi (at phi = 0, l's polar angle is 2 theta_h - theta_v), so u stops at the u of
  // theta_max instead of spending most samples where the integrand is 0.
  const double cos_h_min = std::cos((std::acos(n_dot_v) + kPi / 2.0) / 2.0);
  const double c2 = cos_h_min * cos_h_min;
  const double u_max = std::min(1.0, (1.0 - c2) / (1.0 + c2 * (alpha * alpha - 1.0)));
  // u = 1 - t^2: the estimator's 1 / cos(theta_h) grows like 1 / sqrt(1 - u) near grazing half
  // vectors, which the substitution's du = 2t dt cancels (midpoint sums then converge fast).
  const double t_min = std::sqrt(std::max(0.0, 1.0 - u_max));
  glm::dvec2 sum(0.0);
  for (int i = 0; i < kSteps; ++i) {
    const double t = t_min + (1.0 - t_min) * (i + 0.5) / kSteps;
    const double u = 1.0 - t * t;
    const double jacobian = 2.0 * t * (1.0 - t_min);
    // Half vectors distributed as D(h) cos(theta_h): cos^2 = (1 - u) / (1 + (alpha^2 - 1) u).
    const double cos_h = std::sqrt((1.0 - u) / (1.0 + (alpha * alpha - 1.0) * u));
    const double sin_h = std::sqrt(std::max(0.0, 1.0 - cos_h * cos_h));
    // l = 2 (v.h) h - v is above the horizon where cos(phi) > c: integrate phi over that arc
    // only, so the integrand stays smooth (a cut-off integrand makes midpoint sums converge
    // slowly: 1-2 % off at N.V = 0.05 with 64 steps).
    const double denom = 2.0 * sin_v * sin_h * cos_h;
    double phi_max = 0.0;
    if (denom > 0.0) {
      const double c = n_dot_v * (1.0 - 2.0 * cos_h * cos_h) / denom;
      phi_max = c >= 1.0 ? 0.0 : c <= -1.0 ? kPi : std::acos(c);
    } else {
      phi_max = 2.0 * n_dot_v * cos_h * cos_h - n_dot_v > 0.0 ? kPi : 0.0;
    }
    for (int j = 0; j < kSteps; ++j) {
      const double phi = phi_max * (2.0 * (j + 0.5) / kSteps - 1.0);
      const dvec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
      const double v_dot_h = glm::dot(v, h);
      const dvec3 l = 2.0 * v_dot_h * h - v;
      if (l.z <= 0.0 || v_dot_h <= 0.0) continue;
      // f cos / pdf with pdf = D cos_h / (4 v.h) and F = 1: 4 G/(4 n.l n.v) n.l v.h / cos_h.
      const double visibility =
          variant == Brdf::filament
              ? smith_ggx_correlated_visibility(n_dot_v, l.z, alpha)
              : smith_schlick_ggx(n_dot_v, l.z, roughness) / (4.0 * l.z * n_dot_v);
      const double w = jacobian * visibility * 4.0 * l.z * v_dot_h / cos_h *
                       (phi_max / kPi);  // arc share of 2 pi
      sum += glm::dvec2(w * std::pow(1.0 - v_dot_h, 5.0), w);
    }
  }
  return sum / double(kSteps * kSteps);
}

double reference_specular_albedo(Brdf variant, double n_dot_v, double roughness) {
  return reference_specular_albedo_terms(variant, n_dot_v, roughness).y;
}

namespace {

std::unique_ptr<SpecularAlbedoTable> make_specular_albedo_table(Brdf variant, double roughness) {
  auto table = std::make_unique<SpecularAlbedoTable>();
  constexpr int kPoints = SpecularAlbedoTable::kPoints;
  for (int i = 0; i < kPoints; ++i) {
    const double t = double(i) / (kPoints - 1);
    table->terms[i] = reference_specular_albedo_terms(variant, t * t, roughness);
  }
  // Means 2 int g(mu) mu dmu by a 64-point midpoint rule on the quadrature itself (not on the
  // table), so they do not inherit its interpolation.
  constexpr int kMeanSteps = 64;
  for (int i = 0; i < kMeanSteps; ++i) {
    const double mu = (i + 0.5) / kMeanSteps;
    const glm::dvec2 t = reference_specular_albedo_terms(variant, mu, roughness);
    table->means += 2.0 * mu / kMeanSteps * dvec3(t.y, t.x, t.x / t.y);
  }
  return table;
}

}  // namespace

const SpecularAlbedoTable& reference_specular_albedo_table(Brdf variant, double roughness) {
  roughness = std::clamp(roughness, TS_MIN_PERCEPTUAL_ROUGHNESS, 1.0);
  static std::mutex mutex;
  static std::map<std::pair<Brdf, double>, std::unique_ptr<SpecularAlbedoTable>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  std::unique_ptr<SpecularAlbedoTable>& slot = cache[{variant, roughness}];
  if (!slot) slot = make_specular_albedo_table(variant, roughness);
  return *slot;
}

SpecularAlbedoLookup reference_specular_albedo_lookup(Brdf variant, double roughness) {
  TESSERA_CHECK(variant == Brdf::classic || variant == Brdf::filament);
  constexpr int kNodes = SpecularAlbedoLookup::kNodes;
  // Per node a once_flag, so that threads wait only for the node they need, not for each other.
  struct Node {
    std::once_flag built;
    std::unique_ptr<SpecularAlbedoTable> table;
  };
  static std::array<Node, kNodes + 1> nodes[2];
  std::array<Node, kNodes + 1>& grid = nodes[variant == Brdf::filament ? 1 : 0];
  auto table = [&](int k, double node_roughness) {
    Node& node = grid[size_t(k)];
    std::call_once(node.built,
                   [&] { node.table = make_specular_albedo_table(variant, node_roughness); });
    return node.table.get();
  };
  roughness = std::clamp(roughness, TS_MIN_PERCEPTUAL_ROUGHNESS, 1.0);
  const int k = std::min(int(roughness * kNodes), kNodes);
  // The node below 0.045 stands for 0.045 itself, the lowest roughness there is.
  const double r0 = std::max(double(k) / kNodes, TS_MIN_PERCEPTUAL_ROUGHNESS);
  const SpecularAlbedoTable* lower = table(k, r0);
  if (roughness == r0 || k == kNodes) return {lower, lower, 0.0};
  const double r1 = double(k + 1) / kNodes;
  return {lower, table(k + 1, r1), (roughness - r0) / (r1 - r0)};
}

glm::dvec2 SpecularAlbedoLookup::at(double n_dot_v) const {
  const glm::dvec2 a = lower->at(n_dot_v);
  return weight == 0.0 ? a : glm::mix(a, upper->at(n_dot_v), weight);
}

glm::dvec3 SpecularAlbedoLookup::means() const {
  return weight == 0.0 ? lower->means : glm::mix(lower->means, upper->means, weight);
}

glm::dvec2 SpecularAlbedoTable::at(double n_dot_v) const {
  const double p = std::sqrt(std::clamp(n_dot_v, 0.0, 1.0)) * (kPoints - 1);
  const int i = std::min(int(p), kPoints - 2);
  return glm::mix(terms[i], terms[i + 1], p - i);
}

namespace {

// Es: the compensated specular layer's directional albedo with Schlick Fresnel, per channel.
dvec3 specular_layer_albedo(glm::dvec2 terms, dvec3 f0) {
  const dvec3 single = f0 * (terms.y - terms.x) + terms.x;
  return glm::min(single * (1.0 + f0 * (1.0 / terms.y - 1.0)), dvec3(1.0));
}

}  // namespace

BrdfLobes reference_compensated_lobes(Brdf variant, dvec3 n, dvec3 v, dvec3 l, const Material& m) {
  const double n_dot_l = glm::dot(n, l);
  if (n_dot_l <= 0.0 || variant == Brdf::blinn_phong)
    return reference_brdf_lobes(variant, n, v, l, m);
  const SpecularAlbedoLookup table = reference_specular_albedo_lookup(variant, m.roughness);
  const double n_dot_v = std::max(glm::dot(n, v), TS_MIN_N_DOT_V);
  const double metallic = std::clamp(double(m.metallic), 0.0, 1.0);
  const dvec3 f0 = glm::mix(dvec3(TS_DIELECTRIC_F0), dvec3(m.base_color), metallic);
  const glm::dvec2 terms_v = table.at(n_dot_v);
  BrdfLobes lobes = reference_brdf_lobes(Brdf::filament, n, v, l, m);  // plain Lambert diffuse
  if (variant == Brdf::classic) {
    // The classic specular lobe (the diffuse's 1 - F weight is replaced below).
    lobes.specular = reference_brdf_lobes(Brdf::classic, n, v, l, m).specular;
  }
  lobes.specular *= 1.0 + f0 * (1.0 / terms_v.y - 1.0);
  // (f0 E + (1 - f0) E_Fc)(1 - f0 + f0 / E), averaged term by term.
  const dvec3 g = 1.0 - f0;
  const dvec3 means = table.means();
  const dvec3 average = f0 * g * means.x + f0 * f0 + g * g * means.y + f0 * g * means.z;
  lobes.diffuse *= (1.0 - specular_layer_albedo(terms_v, f0)) *
                   (1.0 - specular_layer_albedo(table.at(n_dot_l), f0)) /
                   glm::max(1.0 - average, dvec3(1e-12));
  return lobes;
}

}  // namespace tessera
