// Points on a closed unit box and the query buffers of the crease tests that run a GPU visibility
// test on them (shaders/tests/BoxQueries.glsl): tests/core/bundle/ClosedBoxCreaseTest.cpp (depth
// maps, bundle walks) and tests/core/gpu/ShadowCubeCreaseTest.cpp (shadow cubes).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace bl::test {

// One query: a point and a normal of either sign (BoxQuery of BoxQueries.glsl).
struct BoxQuery {
    glm::vec4 position;
    glm::vec4 normal;
};

// BoxQueries.glsl's BoxQueryPush: the buffers' addresses, the count and the variant.
struct BoxQueryPush {
    glm::uvec2 queries;
    glm::uvec2 results;
    std::uint32_t count;
    std::uint32_t centreOnly;
};

struct BoxPoint {
    glm::vec3 position;
    glm::vec3 outward;
};

// Points on the unit box's faces: a grid of `grid` x `grid` per face, and `alongEdge` x
// `acrossEdge` within `band` of each of every face's four edges (where a point's own pixel or texel
// can straddle the crease).
std::vector<BoxPoint> boxPoints(int grid, int alongEdge, int acrossEdge, float band);

} // namespace bl::test
