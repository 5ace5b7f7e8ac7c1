// Slivers in the atlas: triangles too thin to own a texel of their chart get charts of their own,
// and the atlas counts them (AtlasStats::isolatedTriangles) so that mode atlas can warn: they cost
// charts and pages, and their texels see few hits each.
#include "atlas/Atlas.h"

#include <gtest/gtest.h>

#include <cstdio>

using namespace bl;
using namespace bl::atlas;

namespace {

// A 2 x 2 square at y = 0 facing +y, cut into `strips` strips of two triangles each.
Scene stripFloor(std::uint32_t strips) {
    Scene s;
    s.materials.emplace_back();
    Mesh m;
    for (std::uint32_t i = 0; i <= strips; ++i) {
        const float x = -1.0f + 2.0f * float(i) / float(strips);
        m.positions.push_back({x, 0.0f, -1.0f});
        m.positions.push_back({x, 0.0f, 1.0f});
        m.normals.push_back({0, 1, 0});
        m.normals.push_back({0, 1, 0});
    }
    for (std::uint32_t i = 0; i < strips; ++i) {
        const std::uint32_t a = 2 * i;
        m.triangles.push_back({a, a + 1, a + 3});
        m.triangles.push_back({a, a + 3, a + 2});
    }
    s.meshes.push_back(m);
    return s;
}

} // namespace

TEST(AtlasSlivers, TrianglesThinnerThanATexelAreCounted) {
    const Atlas plain = buildAtlas(stripFloor(1), AtlasOptions{64});
    EXPECT_EQ(plain.stats.isolatedTriangles, 0u);
    EXPECT_EQ(plain.stats.uncoveredTriangles, 0u);
    // 4,000 strips (8,000 triangles of aspect 4,000) on a 64^2 atlas: more triangles than texels,
    // so at least 8,000 - 4,096 own no texel of the floor's chart and get charts of their own.
    const Atlas slivers = buildAtlas(stripFloor(4000), AtlasOptions{64});
    EXPECT_GE(slivers.stats.isolatedTriangles, 8000u - 4096u);
    EXPECT_EQ(slivers.stats.uncoveredTriangles, 0u);
    EXPECT_EQ(slivers.stats.charts, 1u + slivers.stats.isolatedTriangles);
}

namespace {

// The 2 x 2 floor beside a small square of side `side` cut into k x k cells of two triangles: at a
// fixed atlas side its triangles are too small to own texels of their chart.
Scene floorWithCrowdedCorner(float side, std::uint32_t k) {
    Scene s = stripFloor(1);
    Mesh m;
    for (std::uint32_t j = 0; j <= k; ++j) {
        for (std::uint32_t i = 0; i <= k; ++i) {
            m.positions.push_back({1.1f + side * float(i) / float(k), 0.0f, side * float(j) / float(k)});
            m.normals.push_back({0, 1, 0});
        }
    }
    for (std::uint32_t j = 0; j < k; ++j) {
        for (std::uint32_t i = 0; i < k; ++i) {
            const std::uint32_t a = j * (k + 1) + i, b = a + k + 1;
            m.triangles.push_back({a, b, a + 1});
            m.triangles.push_back({a + 1, b, b + 1});
        }
    }
    s.meshes.push_back(m);
    return s;
}

} // namespace

// With a fixed atlas side the densest packing fills the page, so the charts of triangles that own
// no texel (found only after packing) used to spill onto a second, nearly empty page (Sponza at
// 2048^2: two pages at utilization 0.447). Where they fit in part of a page the charts are packed
// again leaving them room: one page. A 0.05-unit corner of 16 x 16 cells at 256^2: 463 triangles
// own no texel; before, 2 pages at utilization 0.470, now 1 page at 0.918.
TEST(AtlasSlivers, SingleTriangleChartsFitOnTheOnePage) {
    const Atlas a = buildAtlas(floorWithCrowdedCorner(0.05f, 16), AtlasOptions{256});
    std::printf("crowded corner at 256^2: %zu isolated triangles, %d page(s), utilization %.3f, %.2f texels per unit\n",
                a.stats.isolatedTriangles, a.stats.pages, a.stats.utilization, a.texelsPerUnit);
    EXPECT_GT(a.stats.isolatedTriangles, 300u);
    EXPECT_EQ(a.stats.uncoveredTriangles, 0u);
    EXPECT_EQ(a.stats.pages, 1);
    EXPECT_GT(a.stats.utilization, 0.8);
}
