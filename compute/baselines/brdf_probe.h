#pragma once
// Tests only: the GPU's BRDF evaluated for given directions
// (compute/baselines/shaders/brdf_probe.comp).

#include <vector>

#include <glm/glm.hpp>

#include "compute/context.h"
#include "core/scene.h"

namespace tessera {

struct BrdfSample {
  glm::vec3 n, v, l;  // unit vectors
  Material material;
};

/// f(l, v) * N.L per sample, for unit incident radiance, as the shading pass computes it with
/// `variant` (including its guards: roughness >= 0.045, N.V >= 1e-4).
std::vector<glm::vec3> evaluate_brdf_on_gpu(const Context& ctx, Brdf variant,
                                            const std::vector<BrdfSample>& samples);

}  // namespace tessera
