// The point-lit Cornell box (data/cornell-box/cornell-point.toml) written as glTF (.gltf and .glb,
// tests/support/GltfWriter.h) and imported (core/scene/GltfLoader.h) is the same scene: the
// reference path tracer renders the same image from it and from its TOML twin with the same seed.
// data/cornell-box/cornell-point.gltf is the writer's .gltf, committed as an example scene: it must
// stay its twin's scene too.
#include "image/Metrics.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "support/GltfWriter.h"
#include "support/TestFiles.h"

using namespace bl;

TEST(GltfTwin, CornellBoxRoundTripRendersAsItsTomlTwin) {
    Scene twin = loadScene(bl::test::sourcePath("data/cornell-box/cornell-point.toml"));
    for (const char* name : {"cornell.gltf", "cornell.glb", "committed"}) {
        SCOPED_TRACE(name);
        Scene gltf = loadScene(std::string(name) == "committed" ? bl::test::sourcePath("data/cornell-box/cornell-point.gltf")
                                                                : bl::test::writeGltfScene(twin, name));
        EXPECT_EQ(gltf.triangleCount(), twin.triangleCount());
        ASSERT_EQ(gltf.lights.size(), twin.lights.size());
        for (Scene* s : {&gltf, &twin}) s->camera.resolution = {32, 32};
        for (std::uint64_t seed : {1u, 2u}) {
            const Image a = bl::test::renderReference(gltf, 16, {}, seed).radiance();
            const Image b = bl::test::renderReference(twin, 16, {}, seed).radiance();
            const ImageMetrics m = computeMetrics(a, b);
            // The same triangles, materials, light and camera (up to float rounding of the camera's
            // target and the light's colour x intensity) give the same samples.
            EXPECT_LT(m.mse, 1e-10) << "seed " << seed;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.meanRatio[c], 1.0, 1e-5) << "seed " << seed << ", channel " << c;
        }
    }
}
