// The texture atlas: invariants that the `atlas` mode's accuracy rests on (no flips, no texel
// shared by two charts, every triangle owning a texel, bounded stretch, texel samples on their
// surfaces, texel areas summing to the surface area) on the Cornell box, a scanned bunny and a
// deliberately broken mesh.
#include "atlas/Atlas.h"
#include "base/Error.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace bl;
using namespace bl::atlas;

namespace {

double surfaceArea(const Scene& s) {
    double a = 0.0;
    for (const Mesh& m : s.meshes) {
        for (const glm::uvec3& t : m.triangles) {
            a += 0.5 * glm::length(glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]));
        }
    }
    return a;
}

void expectInvariants(const Scene& scene, const Atlas& a, double maxStretch) {
    EXPECT_EQ(a.stats.flippedTriangles, 0u);
    EXPECT_EQ(a.stats.overlappingTexels, 0u);
    EXPECT_EQ(a.stats.uncoveredTriangles, 0u);
    EXPECT_LE(a.stats.maxStretch, maxStretch);
    EXPECT_GE(a.stats.meanStretch, 0.999);
    // Texel areas add up to the surface they stand for.
    double area = 0.0;
    std::size_t covered = 0;
    for (std::size_t t = 0; t < a.maps.valid.size(); ++t) {
        if (a.maps.valid[t] != 1) continue;
        area += a.maps.area[t];
        ++covered;
        EXPECT_NEAR(glm::length(a.maps.normal[t]), 1.0f, 1e-4f);
    }
    EXPECT_NEAR(area, surfaceArea(scene), 1e-3 * surfaceArea(scene));
    EXPECT_NEAR(double(covered) / double(a.maps.valid.size()), a.stats.utilization, 1e-12);
    // Atlas uvs: one per split vertex, inside [0, 1], and as many triangles as the scene.
    std::size_t triangles = 0;
    for (const Mesh& m : a.meshes) {
        triangles += m.triangles.size();
        for (const glm::vec2& uv : m.uvs) {
            EXPECT_GE(uv.x, 0.0f);
            EXPECT_LE(uv.x, 1.0f);
            EXPECT_GE(uv.y, 0.0f);
            EXPECT_LE(uv.y, 1.0f);
        }
    }
    EXPECT_EQ(triangles, scene.triangleCount());
    // Bilinear lookups anywhere on a triangle (corners, edge midpoints, centroid) read only texels
    // of that triangle's own chart, covered or dilated: no empty texel, no neighbour's radiance.
    const int w = a.maps.width, h = a.maps.height;
    std::size_t badLookups = 0;
    ASSERT_EQ(a.vertexPages.size(), a.meshes.size());
    for (std::size_t mi = 0; mi < a.meshes.size(); ++mi) {
        const Mesh& m = a.meshes[mi];
        ASSERT_EQ(a.vertexPages[mi].size(), m.positions.size());
        for (const glm::uvec3& t : m.triangles) {
            const std::uint32_t page = a.vertexPages[mi][t.x];
            ASSERT_TRUE(a.vertexPages[mi][t.y] == page && a.vertexPages[mi][t.z] == page);
            ASSERT_LT(page, std::uint32_t(a.maps.pages));
            const std::size_t pageStart = std::size_t(page) * h * w;
            const glm::vec2 uv[3] = {m.uvs[t.x], m.uvs[t.y], m.uvs[t.z]};
            const glm::vec2 centroid = (uv[0] + uv[1] + uv[2]) / 3.0f;
            const int chart = a.maps.chart[pageStart + std::size_t(std::floor(centroid.y * h)) * w + std::size_t(std::floor(centroid.x * w))];
            for (int k = 0; k < 7; ++k) {
                const glm::vec2 p = k < 3 ? uv[k] : (k < 6 ? 0.5f * (uv[k - 3] + uv[(k - 2) % 3]) : centroid);
                const glm::ivec2 base = glm::ivec2(glm::floor(p * glm::vec2(w, h) - 0.5f));
                for (int dy = 0; dy <= 1; ++dy) {
                    for (int dx = 0; dx <= 1; ++dx) {
                        const int x = std::clamp(base.x + dx, 0, w - 1), y = std::clamp(base.y + dy, 0, h - 1);
                        const std::size_t texel = pageStart + std::size_t(y) * w + x;
                        badLookups += a.maps.valid[texel] == 0 || a.maps.chart[texel] != chart;
                    }
                }
            }
        }
    }
    EXPECT_EQ(badLookups, 0u);
}

} // namespace

TEST(Atlas, CornellBoxEachWallOneChart) {
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    AtlasOptions o;
    o.size = 512;
    Atlas a = buildAtlas(s, o);
    // Floor, ceiling, three walls, the light, and five faces for each block: all planar quads.
    EXPECT_EQ(a.stats.charts, 16u);
    EXPECT_NEAR(a.stats.maxStretch, 1.0, 1e-4);
    expectInvariants(s, a, 1.0001);
    // Every covered texel's sample lies on the surface of its mesh: inside the box.
    const Bounds b = s.bounds();
    for (std::size_t t = 0; t < a.maps.valid.size(); ++t) {
        if (!a.maps.valid[t]) continue;
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE(a.maps.position[t][k], b.lo[k] - 1e-3f);
            EXPECT_LE(a.maps.position[t][k], b.hi[k] + 1e-3f);
        }
    }
    // The light's texels carry its emission.
    std::size_t emitting = 0;
    for (std::size_t t = 0; t < a.maps.valid.size(); ++t) emitting += a.maps.valid[t] == 1 && a.maps.emission[t].x == 17.0f;
    EXPECT_GT(emitting, 0u);
}

TEST(Atlas, FixedDensitySpillsOntoPages) {
    // 0.4 texels per unit on 256^2 pages: the box's 16 charts need several pages.
    Scene s = loadScene(bl::test::sourcePath("data/cornell-box/cornell.toml"));
    AtlasOptions o;
    o.texelsPerUnit = 0.4f;
    o.pageSize = 256;
    Atlas a = buildAtlas(s, o);
    EXPECT_EQ(a.maps.width, 256);
    EXPECT_GT(a.maps.pages, 1);
    EXPECT_EQ(a.stats.pages, a.maps.pages);
    EXPECT_EQ(a.stats.charts, 16u);
    EXPECT_FLOAT_EQ(a.texelsPerUnit, 0.4f);
    expectInvariants(s, a, 1.0001);
    // A density no page can hold is an error, not a crash.
    o.texelsPerUnit = 0.5f; // the back wall alone is 278 texels wide
    EXPECT_THROW(buildAtlas(s, o), Error);
}

TEST(Atlas, ScannedBunny) {
    BL_SKIP_WITHOUT_SHARED("data/bunny/stanford/bun_zipper_res2.ply");
    Scene s = loadScene(bl::test::sharedPath("data/bunny/stanford/bun_zipper_res2.ply"));
    AtlasOptions o;
    o.size = 1024;
    Atlas a = buildAtlas(s, o);
    expectInvariants(s, a, 2.0);
    EXPECT_GT(a.stats.charts, 10u);
    EXPECT_GT(a.stats.utilization, 0.70); // measured 0.745
}

// The targets at 2048^2 on the full scans (Sponza's are measured by
// experiments/bench/atlas.sh): utilization >= 0.70, no flips, overlaps or uncovered triangles,
// stretch <= 2.
TEST(Atlas, TargetsOnTheFullScans) {
    BL_SKIP_WITHOUT_SHARED("data/bunny/stanford/bun_zipper.ply");
    BL_SKIP_WITHOUT_SHARED("data/dragon/dragon_43k_ascii.ply");
    for (const char* path : {"data/bunny/stanford/bun_zipper.ply", "data/dragon/dragon_43k_ascii.ply"}) {
        SCOPED_TRACE(path);
        Scene s = loadScene(bl::test::sharedPath(path));
        Atlas a = buildAtlas(s, AtlasOptions{2048});
        expectInvariants(s, a, 2.0);
        EXPECT_GE(a.stats.utilization, 0.70);
    }
}

TEST(Atlas, BrokenMeshIsHandledAndCounted) {
    // A fan of three triangles on one edge (non-manifold), a duplicate vertex, a zero-area
    // triangle, a flipped neighbour and an isolated triangle.
    std::string obj = bl::test::writeTempFile("broken.obj",
                                              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 1 0 0\nv 2 0 0\n"
                                              "v 5 5 5\nv 6 5 5\nv 5 6 5\n"
                                              "f 1 2 3\nf 2 1 4\nf 1 2 5\nf 6 7 2\nf 8 9 10\nf 3 6 1\n");
    Scene s = loadScene(obj);
    Atlas a = buildAtlas(s, AtlasOptions{256});
    EXPECT_GE(a.stats.nonManifoldFaces, 1u);
    expectInvariants(s, a, 2.0);
}
