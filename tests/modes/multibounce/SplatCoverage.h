// Imperfect bundles ([TO12p]) measured against perfect bundles of the same frames: how far point
// splats cut to discs stand in for the triangles. Geometry only (which fragments a ray meets), no
// light: SplatCoverageTest.cpp checks the curve's shape, MultibounceTest.cpp derives the imperfect
// bundles' bias bound from segmentsChanged.
#pragma once

#include "scene/Scene.h"
#include "vk/Context.h"

#include <cstdint>
#include <vector>

namespace bl::test {

struct SplatCoveragePoint {
    double scale = 0.0;
    double holes = 0.0;            // share of perfect first hits the imperfect bundle misses
    double redundantPerPixel = 0.0; // imperfect nodes minus perfect nodes, per pixel with a hit
    double nodeRatio = 0.0;        // imperfect nodes / perfect nodes
    // The share of bundle segments that end elsewhere: from every perfect fragment (a surface point
    // of the bundle's cosine-weighted segments), forward and backward along the bundle, the next
    // imperfect fragment against the next perfect one (a hole: the ray passes through the surface;
    // a splat reaching past an edge: the ray stops where no surface is).
    double segmentsChanged = 0.0;
};

// For each splat scale: `directions` Halton directions of resolution^2 pixels over the scene's
// bounding sphere, `points` splats per direction (seed 1, iteration 0).
std::vector<SplatCoveragePoint> measureSplatCoverage(const vk::Context& ctx, const Scene& scene,
                                                     const std::vector<double>& scales, std::uint32_t directions,
                                                     std::uint32_t points, std::uint32_t resolution);

} // namespace bl::test
