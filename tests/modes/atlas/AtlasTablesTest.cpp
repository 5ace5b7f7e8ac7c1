// The exact texel areas of mode atlas (modes/atlas/AtlasTables.h): the clipping against known
// areas, and the sum over texels against the scene's surface area.
#include "atlas/AtlasLink.h"
#include "modes/atlas/AtlasTables.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

using namespace bl;

TEST(AtlasTables, ClippedTriangleAreas) {
    // A triangle inside one texel keeps its area; one over four texels splits into known pieces.
    EXPECT_NEAR(atlasmode::clippedTriangleArea({0.1, 0.1}, {0.9, 0.1}, {0.1, 0.9}, 0, 0), 0.32, 1e-12);
    EXPECT_NEAR(atlasmode::clippedTriangleArea({0.1, 0.1}, {0.9, 0.1}, {0.1, 0.9}, 1, 0), 0.0, 1e-12);
    // Right triangle (0,0) (2,0) (0,2): texel (0,0) is whole, (1,0) and (0,1) half each.
    const glm::dvec2 a{0, 0}, b{2, 0}, c{0, 2};
    EXPECT_NEAR(atlasmode::clippedTriangleArea(a, b, c, 0, 0), 1.0, 1e-12);
    EXPECT_NEAR(atlasmode::clippedTriangleArea(a, b, c, 1, 0), 0.5, 1e-12);
    EXPECT_NEAR(atlasmode::clippedTriangleArea(c, b, a, 0, 1), 0.5, 1e-12); // winding does not matter
    EXPECT_NEAR(atlasmode::clippedTriangleArea(a, b, c, 1, 1), 0.0, 1e-12);
}

// Every bit of surface maps to exactly one texel, so the texels' areas sum to the scene's area
// (the atlas's own per-texel areas do too; what differs is where the area sits, checked per
// texel by the furnace test of AtlasModeTest).
TEST(AtlasTables, TexelAreasSumToTheSceneArea) {
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    atlas::AtlasOptions options;
    options.size = 256;
    const atlas::Atlas a = atlas::buildAtlas(s, options);
    const atlas::AtlasLink link = atlas::linkAtlas(s, a);
    const atlasmode::AtlasTables t = atlasmode::buildAtlasTables(a, link);
    double sceneArea = 0.0;
    for (const Mesh& m : s.meshes) {
        for (const glm::uvec3& tri : m.triangles) {
            sceneArea += 0.5 * glm::length(glm::cross(glm::dvec3(m.positions[tri.y] - m.positions[tri.x]),
                                                      glm::dvec3(m.positions[tri.z] - m.positions[tri.x])));
        }
    }
    EXPECT_EQ(t.degenerateTriangles, 0u);
    EXPECT_NEAR(t.totalArea / sceneArea, 1.0, 1e-6);
    EXPECT_EQ(t.triangles.size(), link.indices.size() / 3);
}
