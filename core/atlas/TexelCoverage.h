// Which texels of a packed atlas each placed triangle covers, and which triangle each texel's sample
// belongs to (core/atlas/Atlas.h): coverage is conservative, in software (lavapipe has no
// conservative rasterization), every texel a triangle touches counts; a texel's sample is the
// point of its nearest touching triangle closest to the texel centre.
#pragma once

#include "atlas/BuildProgress.h"
#include "atlas/Parameterization.h"

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/ext/vector_double2.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace bl::atlas {

// Does triangle p overlap the unit square at (x, y)? (Separating axes.)
bool overlapsTexel(const glm::vec2 p[3], float x, float y);

// The part of triangle (a, b, c) inside the unit square [x, x + 1] x [y, y + 1] (Sutherland-Hodgman),
// a convex polygon; empty where they share no area.
std::vector<glm::dvec2> clipTriangleToTexel(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, int x, int y);
// Its area, and the area of any simple polygon.
double clippedTriangleArea(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, int x, int y);
double polygonArea(const std::vector<glm::dvec2>& polygon);

// Closest point of triangle p to q, as barycentrics.
glm::vec3 closestBarycentric(const glm::vec2 p[3], glm::vec2 q);

// The triangle a texel's sample lies on: face `face` of chart `chart` at barycentrics `bary`.
struct TexelOwner {
    std::int32_t chart = -1;
    std::int32_t face = -1; // index within the chart
    float distance = std::numeric_limits<float>::max();
    glm::vec3 bary{0.0f};
    std::int32_t otherChart = -1; // a second chart touching it: an overlap
};

// Conservative coverage of every placed triangle, each texel's sample and owner, and the
// triangles left owning no texel (after taking texels from triangles that own several).
// `owned` counts the texels each (chart, face) owns. Returns the (chart, face) pairs owning none.
std::vector<std::pair<std::size_t, std::size_t>> coverTexels(const std::vector<FlatChart>& charts, int width,
                                                             int height, int pages, std::vector<TexelOwner>& owner,
                                                             std::map<std::pair<int, int>, int>& owned,
                                                             ProgressLog& progress);

} // namespace bl::atlas
