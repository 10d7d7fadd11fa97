#pragma once
// Distant lighting from an environment: an equirectangular radiance map, from a Radiance .hdr
// file or made procedurally. Direction convention (right-handed, y up): column u, row v of the
// map look along d = (sin(theta) sin(phi), cos(theta), -sin(theta) cos(phi)) with
// phi = 2 pi (u - 1/2) and theta = pi v, so the map's centre looks down -z, its top row up.

#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "core/image.h"

namespace tessera {

struct Environment {
  ImageF radiance;  // linear RGB radiance per direction (alpha unused), rows top (+y) down
};

/// Reads an equirectangular environment from a Radiance .hdr (RGBE) or .pfm file. Throws Error
/// naming the path and the problem for an unreadable file, another format, a map that is not
/// about twice as wide as high (0.5 to 4 accepted), or NaN, infinite or negative radiance.
Environment load_environment(const std::string& path);

/// A procedural clear sky, `width` x width/2 texels: a zenith-to-horizon blue gradient, a
/// brighter horizon, a dark ground below it and a smooth sun lobe (about 17 degrees wide),
/// all finite and smooth so that Monte Carlo references converge.
Environment make_sky_environment(uint32_t width = 512);

/// A map of constant radiance (the white furnace).
Environment make_uniform_environment(glm::vec3 radiance);

/// Checks an environment for bad input (size, NaN, Inf, negative values); throws Error.
void validate_environment(const Environment& environment);

/// Equirectangular coordinates of unit direction d: u in [0, 1) around y from -z, v in [0, 1]
/// from +y down.
glm::dvec2 equirect_uv(glm::dvec3 d);
glm::dvec3 equirect_direction(glm::dvec2 uv);

/// Radiance along unit direction d: bilinear over the map's texel centres, wrapping in u and
/// clamping in v (the same lookup the GPU's sampler makes at level 0).
glm::dvec3 environment_radiance(const Environment& environment, glm::dvec3 d);

}  // namespace tessera
