// Packing flattened charts into one atlas. Each chart is turned to its minimum-area bounding
// rectangle (rotation allowed, from its convex hull's edge directions), lying flat, then placed
// bottom-left: at the lowest spot where its texel mask meets nothing placed before, over every
// column and its four quarter turns. Masks are exact and conservative: per texel column, the rows
// the chart's triangles touch, as a list of runs, so a chart drops into another's holes and
// concavities (a wall's window, the room under an arch), not only above its outline. Placed
// charts are grown by `padding` texels, so texels of two charts are at least `padding` apart.
#pragma once

#include "atlas/Parameterization.h"

#include <vector>

namespace bl::atlas {

// Rotates every chart's uv in place to its minimum-area bounding rectangle, lying flat.
void orientCharts(std::vector<FlatChart>& charts);

// Rows [lo, hi) per texel column of a set of triangles in texel coordinates: every texel a
// triangle touches (closed boundaries, as the atlas's coverage test) is inside a run.
struct TexelMask {
    int x0 = 0, y0 = 0;           // first column and row touched
    int width = 0, height = 0;    // columns and rows spanned
    std::vector<int> columnStart; // runs of column x0 + c: runs[columnStart[c] .. columnStart[c + 1])
    std::vector<std::pair<int, int>> runs; // absolute rows [lo, hi), sorted and disjoint per column
    std::size_t texels() const;
};

// The mask of triangles given as 3 corners each, in texel coordinates.
TexelMask rasterizeMask(const std::vector<glm::vec2>& corners);

// The bottom-left packer: each atlas column keeps its occupied row intervals.
class ChartPacker {
public:
    ChartPacker(int width, int height, int padding);
    // Marks a placed chart's texels (uv in atlas texels), grown by the padding, as taken.
    void occupy(const FlatChart& placed);
    // Finds the lowest place for an oriented chart at `density`, over its four quarter turns, and
    // takes it; false if it fits nowhere. uv -> atlas texel: turnChart(uv, turns, extent) * density + offset.
    bool place(const FlatChart& oriented, float density, glm::vec2& offset, int& turns);
    // Texels taken so far (charts grown by the padding), and the rows up to the highest one.
    std::size_t occupiedTexels() const;
    int usedHeight() const { return mUsedHeight; }

private:
    void take(const TexelMask& mask, int dx, int dy);
    int mWidth, mHeight, mPadding;
    int mUsedHeight = 0;
    std::vector<std::vector<std::pair<int, int>>> mColumns; // occupied row intervals per column
};

// Where packCharts put each chart: uv -> page texel turnChart(uv, turns, extent) * density + offset.
struct Packing {
    std::vector<glm::vec2> offsets;
    std::vector<int> turns;
    std::vector<int> pages; // page of each chart
    int pageCount = 0;
    int usedHeight = 0;     // rows the last page's charts reach
};

// Places every oriented chart, largest first, at `density` on width x height pages, each on the
// first page with room, opening at most `maxPages`; false if the charts do not fit.
bool packCharts(const std::vector<FlatChart>& charts, float density, int width, int height, int padding, int maxPages,
                Packing& out);

// An oriented chart's uv at `density`, turned and offset: atlas texel coordinates.
void placeChart(FlatChart& chart, float density, glm::vec2 offset, int turns);

// uv of an oriented chart (origin at its corner, `extent` its far corner) turned by `turns`
// quarter turns counter-clockwise, back at the origin.
glm::vec2 turnChart(glm::vec2 uv, int turns, glm::vec2 extent);

} // namespace bl::atlas
