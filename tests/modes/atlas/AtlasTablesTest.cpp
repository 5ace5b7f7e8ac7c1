// The exact texel areas of mode atlas (modes/atlas/AtlasTables.h): the clipping against known
// areas, and the sum over texels against the scene's surface area.
#include "atlas/AtlasLink.h"
#include "base/Error.h"
#include "modes/atlas/AtlasTables.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"

#include <cstdio>
#include <string>
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

namespace {
// A patch of cells x cells squares (two triangles each) 0.02 wide, a fraction of a texel, beside a
// 20 x 20 quad that sets the density of the atlas.
Scene crowdBesideQuad(int cells) {
    Scene s;
    s.materials.push_back(Material{});
    Mesh m;
    m.name = "crowd";
    for (int j = 0; j <= cells; ++j) {
        for (int i = 0; i <= cells; ++i) {
            m.positions.push_back({0.02f * float(i), 0.02f * float(j), 1.0f});
            m.normals.push_back({0.0f, 0.0f, 1.0f});
        }
    }
    for (int j = 0; j < cells; ++j) {
        for (int i = 0; i < cells; ++i) {
            const auto v = std::uint32_t(j * (cells + 1) + i);
            m.triangles.push_back({v, v + 1, v + std::uint32_t(cells) + 2});
            m.triangles.push_back({v, v + std::uint32_t(cells) + 2, v + std::uint32_t(cells) + 1});
        }
    }
    const auto base = std::uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), {{0, 0, -1}, {20, 0, -1}, {20, 20, -1}, {0, 20, -1}});
    m.normals.insert(m.normals.end(), 4, glm::vec3(0.0f, 0.0f, 1.0f));
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
    s.meshes.push_back(m);
    return s;
}
} // namespace

// Every triangle gets into the atlas, even where its texels are too coarse: 72 triangles a fraction
// of a texel wide find too few texels, and their single-triangle charts no room on the first page;
// they go onto further pages (the generator dropped them once, and the atlas link then refused the
// scene: Sponza, Sibenik and the bunny at 512^2).
TEST(AtlasTables, CrowdedTrianglesOpenPages) {
    const Scene s = crowdBesideQuad(6);
    atlas::AtlasOptions options;
    options.size = 64;
    const atlas::Atlas a = atlas::buildAtlas(s, options);
    std::size_t inAtlas = 0;
    for (const auto& sources : a.triangleSources) inAtlas += sources.size();
    std::printf("crowd: %d page(s), %zu charts, %zu of %zu triangles\n", a.maps.pages, a.stats.charts, inAtlas,
                s.triangleCount());
    EXPECT_EQ(inAtlas, s.triangleCount());
    EXPECT_GT(a.maps.pages, 1);
    EXPECT_NO_THROW(atlas::linkAtlas(s, a));
}

// Where such charts would outweigh the atlas many times over (200 sub-texel triangles in a 16^2
// atlas: up to 28 pages for 0.01% of the area, past the budget of 16; the stress suite's sliver
// floors: hundreds of pages and minutes of packing), the atlas refuses up front and says what to do.
TEST(AtlasTables, OutweighingSubTexelTrianglesAreRefused) {
    atlas::AtlasOptions options;
    options.size = 16;
    options.singleChartFloorTexels = 0.0; // the budget of a 16^2 atlas itself, not of a 512^2 page
    try {
        atlas::buildAtlas(crowdBesideQuad(10), options);
        FAIL() << "no refusal";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(" of the scene's 202 triangles are too thin or too small"), std::string::npos) << what;
        EXPECT_NE(what.find("remesh"), std::string::npos) << what;
    }
}
