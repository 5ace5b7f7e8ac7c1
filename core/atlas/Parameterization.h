// Flattening a chart: planar charts by orthogonal projection (isometric), curved ones by least
// squares conformal maps (Levy et al. 2002, an Eigen sparse solve with two pinned vertices),
// scaled so the flat area equals the surface area. A result with a flipped triangle or an L2
// stretch (Sander et al. 2001) over the bound is rejected; the caller splits the chart.
#pragma once

#include "scene/Mesh.h"

#include <glm/glm.hpp>
#include <vector>

namespace bl::atlas {

struct FlatChart {
    std::uint32_t mesh = 0;
    std::uint32_t page = 0; // atlas page, once packed
    std::vector<std::uint32_t> faces;
    std::vector<glm::vec2> uv; // 3 per face (corner order), in world units
    bool planar = false;
    float stretch = 1.0f;      // L2 stretch of the chart (1: isometric)
    std::size_t flipped = 0;   // faces with non-positive signed area
};

// Angle (radians) under which every face normal must lie to the chart normal to be projected.
inline constexpr float kPlanarToleranceRadians = 1e-3f;

FlatChart flatten(const Mesh& mesh, std::uint32_t meshIndex, const std::vector<std::uint32_t>& faces,
                  const std::vector<std::uint32_t>& welded);

// Measures flips and L2 stretch of `chart` in place (uv may have been rotated or scaled).
void measure(const Mesh& mesh, FlatChart& chart);

} // namespace bl::atlas
