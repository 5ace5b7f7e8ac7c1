// Packing flattened charts into one atlas: each chart turned to its minimum-area bounding
// rectangle (rotation allowed, from its convex hull's edge directions) and lying flat, then dropped,
// tallest first, onto a skyline of the atlas: the chart's lower outline (per texel column, from its
// triangles' bounding boxes, so conservative) rests on the outline of what is already placed, at the
// column and half-turn that keep it lowest, like a Tetris piece. Charts interlock instead of
// wasting their bounding rectangles. Every outline is grown by `padding` texels, so the texels two
// charts touch are at least `padding` apart.
#pragma once

#include "atlas/Parameterization.h"

#include <vector>

namespace bl::atlas {

struct Placement {
    glm::vec2 offset{0.0f}; // atlas texel coordinates of the chart's uv origin after `rotation`
    float rotation = 0.0f;  // radians, applied to uv before scaling
    bool fits = false;
};

// Rotates every chart's uv in place to its minimum-area bounding rectangle, lying flat.
void orientCharts(std::vector<FlatChart>& charts);

// Places the (oriented) charts at `density` texels per world unit in a width x height atlas; false
// if they do not fit. uv -> atlas texel: orient(uv, turns[i], extent) * density + offset.
bool packCharts(const std::vector<FlatChart>& charts, float density, int width, int height, int padding,
                std::vector<glm::vec2>& offsets, std::vector<int>& turns);

// uv of an oriented chart (origin at its corner, `extent` its far corner) turned by `turns`
// quarter turns counter-clockwise, back at the origin.
glm::vec2 turnChart(glm::vec2 uv, int turns, glm::vec2 extent);

} // namespace bl::atlas
