// Chart packing: texel masks are exact (every texel a triangle touches, and only those), and the
// packer keeps charts `padding` apart while dropping small charts into the holes of large ones.
#include "atlas/Packing.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

using namespace bl::atlas;

namespace {

using Texel = std::pair<int, int>; // (x, y)

std::set<Texel> maskTexels(const TexelMask& m) {
    std::set<Texel> out;
    for (int c = 0; c < m.width; ++c) {
        for (int r = m.columnStart[c]; r < m.columnStart[c + 1]; ++r) {
            for (int y = m.runs[r].first; y < m.runs[r].second; ++y) out.insert({m.x0 + c, y});
        }
    }
    return out;
}

// Points of a triangle: a barycentric grid and its edges, at most `spacing` apart along edges.
std::vector<glm::vec2> samples(const glm::vec2 t[3], float spacing) {
    std::vector<glm::vec2> out;
    const int n = 200;
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; i + j <= n; ++j) out.push_back(t[0] + (t[1] - t[0]) * float(i) / float(n) + (t[2] - t[0]) * float(j) / float(n));
    }
    for (int k = 0; k < 3; ++k) {
        const glm::vec2 a = t[k], b = t[(k + 1) % 3];
        const int steps = 1 + int(glm::distance(a, b) / spacing);
        for (int s = 0; s <= steps; ++s) out.push_back(a + (b - a) * float(s) / float(steps));
    }
    return out;
}

// A square ring in uv: outer side `outer`, a centred square hole of side `hole` (8 triangles).
FlatChart ring(float outer, float hole) {
    const float a = 0.5f * (outer - hole), b = a + hole;
    const glm::vec2 o[4] = {{0, 0}, {outer, 0}, {outer, outer}, {0, outer}};
    const glm::vec2 i[4] = {{a, a}, {b, a}, {b, b}, {a, b}};
    FlatChart c;
    for (int k = 0; k < 4; ++k) {
        const int n = (k + 1) % 4;
        for (glm::vec2 p : {o[k], o[n], i[n], o[k], i[n], i[k]}) c.uv.push_back(p);
        c.faces.push_back(2 * k);
        c.faces.push_back(2 * k + 1);
    }
    return c;
}

FlatChart square(float side) {
    FlatChart c;
    for (glm::vec2 p : {glm::vec2(0, 0), glm::vec2(side, 0), glm::vec2(side, side), glm::vec2(0, 0), glm::vec2(side, side),
                        glm::vec2(0, side)}) {
        c.uv.push_back(p);
    }
    c.faces = {0, 1};
    return c;
}

} // namespace

TEST(Packing, MaskHoldsExactlyTheTexelsATriangleTouches) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coord(0.0f, 12.0f);
    for (int trial = 0; trial < 200; ++trial) {
        glm::vec2 t[3] = {{coord(rng), coord(rng)}, {coord(rng), coord(rng)}, {coord(rng), coord(rng)}};
        if (trial % 4 == 0) t[1] = t[0] + glm::vec2(coord(rng) * 0.05f, 0.0f); // slivers, along a row too
        if (trial % 10 == 0) t[0] = glm::floor(t[0]);                          // corners on texel corners
        const std::set<Texel> mask = maskTexels(rasterizeMask({t[0], t[1], t[2]}));
        // Every texel holding a point of the triangle is in the mask ...
        for (const glm::vec2& p : samples(t, 0.004f)) {
            ASSERT_TRUE(mask.count({int(std::floor(p.x)), int(std::floor(p.y))})) << "trial " << trial << " point " << p.x << "," << p.y;
        }
        // ... and the mask holds no texel the triangle stays clear of (0.01 texel of slack).
        for (const Texel& texel : mask) {
            bool near = false;
            for (const glm::vec2& p : samples(t, 0.004f)) {
                near = near || (p.x >= texel.first - 0.01f && p.x <= texel.first + 1.01f && p.y >= texel.second - 0.01f &&
                                p.y <= texel.second + 1.01f);
            }
            ASSERT_TRUE(near) << "trial " << trial << " texel " << texel.first << "," << texel.second;
        }
    }
}

TEST(Packing, SmallChartDropsIntoTheHoleOfARing) {
    // A 60-texel ring with a 40-texel hole, then a 20-texel square: with padding 2 the square
    // fits inside the hole, below the ring's top. An outline without holes would put it above.
    const int width = 64, padding = 2;
    ChartPacker packer(width, 256, padding);
    glm::vec2 offset;
    int turns = 0;
    FlatChart big = ring(60.0f, 40.0f), small = square(20.0f);
    ASSERT_TRUE(packer.place(big, 1.0f, offset, turns));
    placeChart(big, 1.0f, offset, turns);
    ASSERT_TRUE(packer.place(small, 1.0f, offset, turns));
    placeChart(small, 1.0f, offset, turns);
    const TexelMask ringMask = rasterizeMask(big.uv), squareMask = rasterizeMask(small.uv);
    EXPECT_LT(squareMask.y0 + squareMask.height, ringMask.y0 + ringMask.height);
    // Padding kept: no square texel within `padding` texels (Chebyshev) of a ring texel.
    const std::set<Texel> ringTexels = maskTexels(ringMask);
    for (const Texel& t : maskTexels(squareMask)) {
        for (int dy = -padding; dy <= padding; ++dy) {
            for (int dx = -padding; dx <= padding; ++dx) {
                EXPECT_FALSE(ringTexels.count({t.first + dx, t.second + dy})) << t.first << "," << t.second;
            }
        }
    }
}

TEST(Packing, ManyChartsNeverOverlapAndReportTheirHeight) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> side(1.0f, 30.0f);
    std::vector<FlatChart> charts;
    for (int i = 0; i < 120; ++i) charts.push_back(i % 3 ? square(side(rng)) : ring(side(rng) + 10.0f, 6.0f));
    orientCharts(charts);
    Packing packing;
    ASSERT_TRUE(packCharts(charts, 1.0f, 256, 100000, 2, 1, packing));
    EXPECT_EQ(packing.pageCount, 1);
    std::map<Texel, std::size_t> owner;
    int top = 0;
    for (std::size_t i = 0; i < charts.size(); ++i) {
        placeChart(charts[i], 1.0f, packing.offsets[i], packing.turns[i]);
        const TexelMask m = rasterizeMask(charts[i].uv);
        top = std::max(top, m.y0 + m.height);
        EXPECT_GE(m.x0, 0);
        EXPECT_LE(m.x0 + m.width, 256);
        for (const Texel& t : maskTexels(m)) {
            auto [it, fresh] = owner.emplace(t, i);
            EXPECT_TRUE(fresh) << "charts " << it->second << " and " << i << " share texel " << t.first << "," << t.second;
        }
    }
    EXPECT_EQ(packing.usedHeight, top);
    // Too narrow an atlas is refused, not overrun.
    EXPECT_FALSE(packCharts(charts, 1.0f, 30, 100000, 2, 1, packing));
}

TEST(Packing, ChartsSpillOntoFurtherPages) {
    // Twelve 30-texel squares on 64^2 pages with padding 2: two fit side by side and two above
    // (4 per page), so three pages; with two pages allowed the packing is refused.
    std::vector<FlatChart> charts(12, square(30.0f));
    orientCharts(charts);
    Packing packing;
    ASSERT_TRUE(packCharts(charts, 1.0f, 64, 64, 2, 8, packing));
    EXPECT_EQ(packing.pageCount, 3);
    std::map<std::pair<int, Texel>, std::size_t> owner;
    for (std::size_t i = 0; i < charts.size(); ++i) {
        FlatChart placed = charts[i];
        placeChart(placed, 1.0f, packing.offsets[i], packing.turns[i]);
        const TexelMask m = rasterizeMask(placed.uv);
        EXPECT_GE(m.y0, 0);
        EXPECT_LE(m.y0 + m.height, 64);
        for (const Texel& t : maskTexels(m)) EXPECT_TRUE(owner.emplace(std::make_pair(packing.pages[i], t), i).second);
    }
    EXPECT_FALSE(packCharts(charts, 1.0f, 64, 64, 2, 2, packing));
}
