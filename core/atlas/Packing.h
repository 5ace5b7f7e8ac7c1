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

// The same placement problem, but each atlas column keeps the list of its occupied row intervals
// instead of one skyline height, so a chart can drop into the room under another chart's overhang
// (bottom-left placement over column intervals). Slower than the skyline: it refines a density the
// skyline found, and adds charts to a finished atlas without moving the others.
class HoleFiller {
public:
    HoleFiller(int width, int height, int padding);
    // Marks a placed chart's texels (uv in atlas texels), grown by the padding, as taken.
    void occupy(const FlatChart& placed);
    // Finds the lowest place for an oriented chart at `density`, over its four quarter turns, and
    // takes it; false if it fits nowhere.
    bool place(const FlatChart& oriented, float density, glm::vec2& offset, int& turns);

private:
    int mWidth, mHeight, mPadding;
    std::vector<std::vector<std::pair<int, int>>> mColumns; // occupied row intervals per column
};

bool packChartsFillingHoles(const std::vector<FlatChart>& charts, float density, int width, int height, int padding,
                            std::vector<glm::vec2>& offsets, std::vector<int>& turns);

// An oriented chart's uv at `density`, turned and offset: atlas texel coordinates.
void placeChart(FlatChart& chart, float density, glm::vec2 offset, int turns);

// uv of an oriented chart (origin at its corner, `extent` its far corner) turned by `turns`
// quarter turns counter-clockwise, back at the origin.
glm::vec2 turnChart(glm::vec2 uv, int turns, glm::vec2 extent);

} // namespace bl::atlas
