// The texel-space reference (reference/TexelBaker.h, core/atlas/TexelRadiance.h): the path tracer
// baking an atlas's texels against closed forms, each sample on its texel's surface, and the
// comparison counting what it says it counts.
#include "atlas/Atlas.h"
#include "atlas/TexelRadiance.h"
#include "reference/EmbreeScene.h"
#include "reference/TexelBaker.h"
#include "scene/SceneLoader.h"
#include "support/AnalyticScenes.h"
#include "support/Statistics.h"
#include "support/TestFiles.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

using namespace bl;
namespace stats = bl::test::stats;
using bl::test::errorOf;
using bl::test::sourcePath;

namespace {

atlas::Atlas atlasOf(const Scene& scene, int size) {
    atlas::AtlasOptions options;
    options.size = size;
    return atlas::buildAtlas(scene, options);
}

// Mean of one channel of one side over the valid texels.
double sideMean(const atlas::TexelRadiance& r, int side) {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t t = 0; t < r.texels(); ++t) {
        if (!r.valid[t]) continue;
        sum += r.side[side][t].x;
        ++n;
    }
    return n ? sum / double(n) : 0.0;
}

} // namespace

// The white furnace (every face emits 1 inward, albedo 0.5): radiance 2 everywhere inside, so
// every texel's front side reflects exactly 2 - 1 = 1 (0.5 with paths of at most 2 segments: the
// emission reflected once); the back sides face the empty outside and reflect nothing. The
// tolerance is the bias the test is to catch (half a percent; a side swapped or the emission left
// in moves it by 100 %), the seeds' spread behind the noise gate.
TEST(TexelBaker, FurnaceTexelsReflectWhatTheClosedFormSays) {
    const Scene scene = loadScene(sourcePath("data/analytic/furnace.toml"));
    const atlas::Atlas atlas = atlasOf(scene, 32);
    for (auto [segments, expected] : {std::pair{64, 1.0}, {2, 0.5}}) {
        SCOPED_TRACE("max_segments " + std::to_string(segments));
        std::vector<double> front;
        for (std::uint32_t seed : stats::seeds(4)) {
            TexelBakeSettings settings;
            settings.samples = 64;
            settings.seed = seed;
            settings.reference.path.maxSegments = segments;
            const TexelBake bake = bakeTexels(scene, atlas, settings);
            EXPECT_EQ(bake.nonFiniteSamples, 0u);
            front.push_back(sideMean(bake.radiance, 0));
            // Not exactly 0: a path from a point a few ulps from an edge can slip through the seam.
            EXPECT_LT(sideMean(bake.radiance, 1), 1e-6) << "the outside of the box";
        }
        EXPECT_TRUE(stats::agrees(stats::summarize(front), expected, 0.005 * expected, "front sides"));
    }
}

// A light that varies over the surface: two squares (two meshes) under a point light, their
// charts on two atlas pages. Every texel's bake is the closed form rho / pi * I cos / r^2 at its
// surface (the texel's mean, against the value at its centre: for the interior texels the two
// differ by the curvature, (s^2 / 24) |f''| / f <= 1e-4 here with texels of s = 1/24 and the light
// 2 above); the noise is the light's variation across a texel (per sample <= 4 %, 256 samples:
// <= 0.25 %): 3 % per texel is 12 of those and far below what a texel baked at another texel's,
// page's or triangle's surface is off by (tens of per cent across these squares). The back sides
// face away from the light: black.
TEST(TexelBaker, PointLitSquaresOnTwoPagesMatchTheClosedFormPerTexel) {
    Scene scene;
    Material m;
    m.albedo = glm::vec3(0.5f);
    scene.materials.push_back(m);
    scene.meshes.push_back(bl::test::makeSquare(2.0f, 0, glm::vec3(-1.5f, 0.0f, 0.0f)));
    scene.meshes.push_back(bl::test::makeSquare(2.0f, 0, glm::vec3(1.5f, 0.0f, 0.5f)));
    Light light;
    light.position = glm::vec3(0.0f, 2.0f, 0.0f);
    light.intensity = glm::vec3(10.0f);
    scene.lights.push_back(light);
    scene.camera.resolution = glm::ivec2(8);
    atlas::AtlasOptions options;
    options.texelsPerUnit = 24.0f;
    options.pageSize = 64; // one chart of 48 texels and its padding per page
    const atlas::Atlas atlas = atlas::buildAtlas(scene, options);
    ASSERT_EQ(atlas.maps.pages, 2);
    TexelBakeSettings settings;
    settings.samples = 256;
    settings.reference.path.maxSegments = 2;
    const TexelBake bake = bakeTexels(scene, atlas, settings);
    EXPECT_EQ(bake.emptyTexels, 0u);
    const std::vector<std::uint8_t> border = atlas::chartBorder(atlas.maps);
    std::size_t checked = 0;
    for (std::size_t t = 0; t < atlas.maps.valid.size(); ++t) {
        if (atlas.maps.valid[t] != 1) continue;
        EXPECT_EQ(bake.radiance.side[1][t], glm::vec3(0.0f)) << "texel " << t;
        if (border[t]) continue;
        const float expected = bl::test::pointLitFloorRadiance(atlas.maps.position[t], light.position, 10.0f, 0.5f);
        ASSERT_NEAR(bake.radiance.side[0][t].x, expected, 0.03f * expected) << "texel " << t;
        ++checked;
    }
    EXPECT_GT(checked, 2u * 20u * 20u);
}

// Every valid texel's sample becomes a hit on the triangle the atlas says it lies on, at the
// sample point, with that triangle's normal: the baker traces from the texel's own surface (the
// Cornell box has several meshes, so the scene triangle -> mesh mapping is exercised too).
TEST(TexelBaker, EachSampleIsAPointOfItsTexelsTriangle) {
    const Scene scene = loadScene(sourcePath("data/cornell-box/cornell.toml"));
    const atlas::Atlas atlas = atlasOf(scene, 64);
    const EmbreeScene geometry(scene, 0.0);
    const std::vector<std::uint32_t> first = atlas::firstSceneTriangles(scene);
    const float scale = scene.bounds().radius();
    std::size_t checked = 0;
    for (std::size_t t = 0; t < atlas.maps.valid.size(); ++t) {
        if (atlas.maps.valid[t] != 1) continue;
        const std::uint32_t global = atlas.maps.triangle[t];
        std::uint32_t mesh = 0;
        while (mesh + 1 < first.size() && first[mesh + 1] <= global) ++mesh;
        const SurfaceHit hit = geometry.surfaceAt(mesh, global - first[mesh], atlas.maps.position[t]);
        ASSERT_LT(glm::distance(hit.position, atlas.maps.position[t]), 1e-5f * scale) << "texel " << t;
        ASSERT_GT(std::abs(glm::dot(hit.geometricNormal, glm::normalize(atlas.maps.normal[t]))), 0.999f) << "texel " << t;
        ++checked;
    }
    EXPECT_GT(checked, 1000u);
    // A point off the triangle is clamped onto it.
    glm::vec3 a, b, c;
    geometry.triangle(0, 0, a, b, c);
    const SurfaceHit outside = geometry.surfaceAt(0, 0, a + 10.0f * (a - (b + c) * 0.5f));
    EXPECT_LT(glm::distance(outside.position, a), 1e-4f * scale);
}

// The comparison: identical texels give 0; a side black in both is not counted (it would pull the
// mean toward 0), a side black in one is; texels of another atlas are refused.
TEST(TexelRadiance, MetricsCountTheLitSidesOfTheSameAtlas) {
    atlas::TexelMaps maps;
    maps.width = 2;
    maps.height = 1;
    maps.valid = {1, 1};
    atlas::TexelRadiance ref = atlas::TexelRadiance::like(maps);
    ref.side[0] = {glm::vec3(1.0f), glm::vec3(2.0f)};
    EXPECT_EQ(atlas::texelMetrics(ref, ref).relMse, 0.0);
    atlas::TexelRadiance test = ref;
    test.side[0][1] = glm::vec3(1.0f);
    // Two sides count (the two fronts); one is off by 1 against 2: (1 / (4 + 0.01)) / 2.
    EXPECT_NEAR(atlas::texelMetrics(test, ref).relMse, 0.5 / 4.01, 1e-9);
    test.side[1][0] = glm::vec3(3.0f); // a back side lit in the test alone counts: 9 / 0.01
    EXPECT_NEAR(atlas::texelMetrics(test, ref).relMse, (1.0 / 4.01 + 900.0) / 3.0, 1e-6);
    atlas::TexelRadiance other = ref;
    other.valid = {1, 0};
    EXPECT_NE(errorOf([&] { atlas::texelMetrics(other, ref); }).find("not of the same atlas"), std::string::npos);
    const atlas::TexelRadiance dark = atlas::TexelRadiance::like(maps);
    EXPECT_NE(errorOf([&] { atlas::texelMetrics(dark, dark); }).find("no texel side is lit"), std::string::npos);
}
