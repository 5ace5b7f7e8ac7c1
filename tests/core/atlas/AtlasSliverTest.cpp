// Slivers in the atlas: triangles too thin to own a texel of their chart get charts of their own,
// and the atlas counts them (AtlasStats::isolatedTriangles) so that mode atlas can warn: they cost
// charts and pages, and their texels see few hits each.
#include "atlas/Atlas.h"

#include <gtest/gtest.h>

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
