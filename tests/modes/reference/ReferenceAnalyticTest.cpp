// The reference path tracer against closed forms: the white furnace, a rectangle light over a
// floor, a point light over a plane, a sealed thin wall; determinism; NaN handling.
#include "modes/reference/ReferenceMode.h"
#include "reference/EmbreeScene.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "support/AnalyticScenes.h"
#include "support/TestFiles.h"

using namespace bl;
using bl::test::layerOf;
using bl::test::renderReference;
using bl::test::sourcePath;

TEST(ReferenceAnalytic, WhiteFurnaceByPathLength) {
    Scene s = loadScene(sourcePath("data/analytic/furnace.toml"));
    s.camera.resolution = {16, 16};
    // radiance = sum over k < N of 0.5^k: 1, 1.5, 1.75 for N = 1, 2, 3; 2 without a limit.
    for (auto [segments, expected] : {std::pair{1, 1.0}, {2, 1.5}, {3, 1.75}, {64, 2.0}}) {
        for (const char* sampling : {"emitter_sampling=area", "emitter_sampling=solid_angle"}) {
            SCOPED_TRACE(std::to_string(segments) + " " + sampling);
            ImageSet out = renderReference(s, 64, {"max_segments=" + std::to_string(segments), sampling});
            glm::dvec3 mean = out.radiance().mean();
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(mean[c], expected, 0.005 * expected);
            }
        }
    }
    // The layers split the same radiance by path length: 1, 0.5, 0.25, 0.125, and 0.125 beyond.
    // "rest" carries Russian roulette's variance (per-sample std ~0.4): 3% is 3 standard errors.
    s.camera.resolution = {64, 64};
    ImageSet out = renderReference(s, 32);
    const double layers[] = {1.0, 0.5, 0.25, 0.125, 0.125};
    const double tolerance[] = {1e-6, 0.01, 0.01, 0.01, 0.03};
    for (int l = 0; l < kPathLayerCount; ++l) {
        EXPECT_NEAR(layerOf(out, kPathLayerNames[l]).mean().x, layers[l], tolerance[l] * layers[l])
            << kPathLayerNames[l];
    }
}

TEST(ReferenceAnalytic, RectangleLightOverFloor) {
    Scene s = loadScene(sourcePath("data/analytic/rect-light.toml"));
    // Look straight down at the point below the light's centre, through a 0.5-degree window.
    s.camera.pose = {{0.0f, 0.6f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}};
    s.camera.fovDegrees = 0.5f;
    s.camera.resolution = {8, 8};
    for (const char* sampling : {"emitter_sampling=area", "emitter_sampling=solid_angle"}) {
        ImageSet out = renderReference(s, 256, {sampling});
        EXPECT_NEAR(out.radiance().mean().x, 0.367388, 0.005 * 0.367388) << sampling;
    }
}

TEST(ReferenceAnalytic, PointLightOverPlane) {
    const float albedo = 0.5f, intensity = 10.0f;
    Scene s = bl::test::pointLightOverPlane(albedo, intensity, 1.0f, 48);
    Image img = renderReference(s, 16, {"max_segments=2"}).radiance();
    int checked = 0;
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 48; ++x) {
            float t;
            glm::vec3 p = bl::test::cameraRayHitY(s, glm::vec2(x + 0.5f, y + 0.5f), 0.0f, t);
            if (t <= 0.0f || std::abs(p.x) > 3.8f || std::abs(p.z) > 3.8f) continue;
            // The box filter: the closed form averaged over the pixel's footprint.
            float expected = 0.0f;
            for (int j = 0; j < 8; ++j) {
                for (int i = 0; i < 8; ++i) {
                    glm::vec3 q = bl::test::cameraRayHitY(s, glm::vec2(x + (i + 0.5f) / 8, y + (j + 0.5f) / 8), 0.0f, t);
                    expected += bl::test::pointLitFloorRadiance(q, s.lights[0].position, intensity, albedo) / 64.0f;
                }
            }
            EXPECT_NEAR(img.at(x, y).x, expected, 0.01f * expected) << x << "," << y;
            ++checked;
        }
    }
    EXPECT_GT(checked, 1000);
}

TEST(ReferenceAnalytic, SealedThinWallLeaksNothing) {
    // The wall is 1/1000 of the room thick and seals it: no path reaches the camera's side.
    Scene s = loadScene(sourcePath("data/analytic/light-leak.toml"));
    s.camera.resolution = {24, 24};
    Image img = renderReference(s, 16).radiance();
    float brightest = 0.0f;
    for (const glm::vec3& p : img.pixels()) brightest = std::max({brightest, p.x, p.y, p.z});
    EXPECT_EQ(brightest, 0.0f);
    // And scaled to kilometres and to millimetres.
    for (float scale : {1e3f, 1e-3f}) {
        Scene scaled = s;
        scaleScene(scaled, scale);
        Image i = renderReference(scaled, 4).radiance();
        for (const glm::vec3& p : i.pixels()) brightest = std::max({brightest, p.x, p.y, p.z});
        EXPECT_EQ(brightest, 0.0f) << scale;
    }
}

TEST(ReferenceAnalytic, DeterministicWhateverTheThreadCount) {
    Scene s = loadScene(sourcePath("data/cornell-box/cornell.toml"));
    s.camera.resolution = {24, 24};
    Image one = renderReference(s, 3, {"threads=1"}, 5).radiance();
    Image two = renderReference(s, 3, {"threads=2"}, 5).radiance();
    EXPECT_EQ(one.pixels(), two.pixels());
    Image other = renderReference(s, 3, {"threads=2"}, 6).radiance();
    EXPECT_NE(one.pixels(), other.pixels()); // the seed matters
}

TEST(ReferenceAnalytic, NonFiniteSamplesAreCountedNotAveraged) {
    // Emitters at the top of the float range: every path's sum overflows to infinity.
    Scene s = loadScene(sourcePath("data/analytic/furnace.toml"));
    s.camera.resolution = {4, 4};
    for (Mesh& m : s.meshes) m.emission = glm::vec3(3.0e38f);
    std::unique_ptr<Mode> mode = createMode("reference");
    mode->setScene(s, nullptr);
    mode->iterate({0, 0, 0.0});
    ImageSet out = mode->resolve();
    EXPECT_EQ(out.nonFiniteSamples, 16u);
    EXPECT_EQ(out.radiance().countNonFinite(), 0u);
    // The bad sample can be replayed alone, with its path.
    std::vector<std::string> log;
    PathSample again = static_cast<ReferenceMode&>(*mode).replay(2, 3, 0, 0, log);
    EXPECT_FALSE(again.finite());
    EXPECT_FALSE(log.empty());
}

TEST(ReferenceAnalytic, EnvironmentLightsALambertianSquare) {
    // A square of albedo 0.5 facing up, alone under an environment of radiance 2 above the horizon
    // and 0 below: it reflects 0.5 * 2 = 1 (the lower half is hidden behind it anyway).
    Scene s;
    Material m;
    m.albedo = glm::vec3(0.5f);
    s.materials.push_back(m);
    s.meshes.push_back(bl::test::makeSquare(2.0f, 0));
    s.camera.pose = {{0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}};
    s.camera.fovDegrees = 5.0f;
    s.camera.resolution = {8, 8};
    s.environment.present = true;
    s.environment.map = Image(64, 32);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 64; ++x) s.environment.map.at(x, y) = glm::vec3(2.0f);
    // Bilinear filtering blurs the horizon over half a texel (2.8 degrees): ~0.1% of the irradiance.
    for (const char* sampling : {"env_sampling=luminance", "env_sampling=uniform"}) {
        Image img = renderReference(s, 256, {sampling, "max_segments=2"}).radiance();
        EXPECT_NEAR(img.mean().x, 1.0, 0.005) << sampling;
    }
    s.environment.map = Image();
    s.environment.radiance = glm::vec3(2.0f); // constant: the same answer
    EXPECT_NEAR(renderReference(s, 256).radiance().mean().x, 1.0, 0.005);
}

// Rays leaving a point light keep the shared clearance (ScenePrecision.h), as shadow rays ending at
// it do: a light lying on a plane does not catch the rays that leave into the plane (bidir's traced
// VPLs put a VPL at the light itself there, at distance 0: an infinite area density), and one a
// clearance above it still does.
TEST(ReferenceAnalytic, RaysFromALightOnAPlaneLeaveThroughIt) {
    Scene s = bl::test::pointLightOverPlane(0.5f, 1.0f, 1.0f, 8); // the plane y = 0
    const EmbreeScene rt(s, 0.0);
    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    SurfaceHit hit;
    const glm::vec3 onPlane(0.0f, 0.0f, 0.0f);
    EXPECT_FALSE(rt.intersectFromLight(onPlane, down, hit)) << "hit at t = " << hit.t;
    EXPECT_TRUE(rt.intersect(onPlane, down, 1.0f, hit)); // what the VPL sampler traced before
    const glm::vec3 above(0.0f, 4.0f * rt.lightClearance(), 0.0f);
    ASSERT_TRUE(rt.intersectFromLight(above, down, hit));
    EXPECT_NEAR(hit.t, 4.0f * rt.lightClearance(), 1e-3f * rt.lightClearance());
}
