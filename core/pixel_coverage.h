#pragma once
// Analytic anti-aliasing coverage in double precision, for the reference renderer
// (FrameSettings::aa_coverage analytic; the compute path's version is shaders/coverage.glsl):
// the area of a convex polygon inside a pixel, and how much of a pixel a surface covers from
// the edges of the one triangle its samples see.

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

namespace tessera {

/// Area in px^2 (0..1) of the convex polygon `corners` (in pixels, relative to the pixel's
/// top-left corner, either winding; fewer than 3 corners give 0) inside the pixel square
/// [0, 1]^2: clipped to its four sides (Sutherland & Hodgman 1974), then the shoelace formula.
double area_in_pixel(std::vector<glm::dvec2> corners);

/// Outline coverage of a pixel whose samples see one triangle and the background: the area
/// (px^2, 0..1) of the pixel square inside the lines of the triangle's outline edges, those
/// with at least one of `empty_samples` on or beyond them and none of `covered_samples` beyond
/// (taken as where the surface ends); its other edges do not cut, the surface continuing
/// across them. -1 if no edge is an outline edge; 0 if the polygon has no area. `corners`:
/// the triangle as the convex polygon the rasterizer saw (clipped and snapped), either winding;
/// everything in pixels relative to the pixel's top-left corner.
double outline_coverage(const std::vector<glm::dvec2>& corners,
                        const std::vector<glm::dvec2>& empty_samples,
                        const std::vector<glm::dvec2>& covered_samples);

/// Silhouette coverage of a pixel whose samples see triangles of one surface and the background
/// (shaders/outline.comp states the method): the area (px^2, 0..1) of the pixel covered by the
/// surface's triangles that wind as the first seen does, taken in by a breadth-first walk across
/// their edges from it, which leaves out triangles winding the other way (or edge-on) and those not
/// reaching into the pixel. `seen`: the ids of the triangles the samples see (at least one; the
/// walk starts from the smallest). `polygon(id)`: that triangle as the rasterizer saw it (clipped
/// and snapped), in pixels relative to the pixel's top-left corner; `neighbours(id)`: the ids
/// across its three edges in corner order (kNoNeighbourId: none). The walk does not go on from the
/// triangles of step `max_steps` - 1 (the first triangle is step 0, the neighbours taken in from it
/// step 1, and so on). -1 if a seen triangle is not taken in, or if more than `max_triangles` would
/// be.
inline constexpr uint64_t kNoNeighbourId = ~uint64_t(0);
double silhouette_coverage(const std::vector<uint64_t>& seen,
                           const std::function<std::vector<glm::dvec2>(uint64_t)>& polygon,
                           const std::function<std::array<uint64_t, 3>(uint64_t)>& neighbours,
                           size_t max_triangles, size_t max_steps);

}  // namespace tessera
