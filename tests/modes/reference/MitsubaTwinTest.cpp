// Mitsuba 3's own Cornell box (../shared/data/cornell-box/mitsuba-cbox/cbox-rgb.xml: includes,
// defaults, forward references across files) imported, against its hand-written TOML twin
// (data/external/mitsuba-cbox.toml): the same scene, so the reference path tracer renders the same
// image from either with the same seed.
#include "image/Metrics.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"

using namespace bl;

TEST(MitsubaTwin, CornellBoxImportRendersAsItsTomlTwin) {
    BL_SKIP_WITHOUT_SHARED("data/cornell-box/mitsuba-cbox/cbox-rgb.xml");
    BL_SKIP_WITHOUT_SCENE_FILES("data/external/mitsuba-cbox.toml");
    Scene xml = loadScene(bl::test::sharedPath("data/cornell-box/mitsuba-cbox/cbox-rgb.xml"));
    Scene twin = loadScene(bl::test::sourcePath("data/external/mitsuba-cbox.toml"));
    EXPECT_EQ(xml.triangleCount(), twin.triangleCount());
    EXPECT_EQ(xml.camera.resolution, twin.camera.resolution);
    EXPECT_EQ(xml.camera.fovAxis, twin.camera.fovAxis);
    EXPECT_FLOAT_EQ(xml.camera.fovDegrees, twin.camera.fovDegrees);
    for (Scene* s : {&xml, &twin}) s->camera.resolution = {32, 32};
    for (std::uint64_t seed : {1u, 2u}) {
        const Image a = bl::test::renderReference(xml, 16, {}, seed).radiance();
        const Image b = bl::test::renderReference(twin, 16, {}, seed).radiance();
        const ImageMetrics m = computeMetrics(a, b);
        // The same geometry, materials and camera give the same samples: equal up to float
        // rounding (here bit-identical).
        EXPECT_LT(m.mse, 1e-12) << "seed " << seed;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.meanRatio[c], 1.0, 1e-6) << "seed " << seed << ", channel " << c;
    }
}

// Veach's MIS scene as Mitsuba writes it (../shared/data/glossy/veach-mis/veach_mis.xml: spheres,
// roughplastic, a lookat sensor with fov_axis "smaller" of a wide film) against its hand-written
// TOML twin (data/external/veach-mis.toml: the spheres as one unit-sphere OBJ scaled and moved, the
// roughplastic mapping typed from its formula). The twin's sphere vertices are rounded once more
// (float OBJ, then scale and translate) than the importer's, so the images agree to float rounding,
// not to the bit: relMSE 1e-9..2e-7 measured, while two seeds differ by 0.6 and the mutation
// "one plate's exponent 199.5 -> 180" gives 8.3e-4. Bound: 1e-5.
TEST(MitsubaTwin, VeachMisImportRendersAsItsTomlTwin) {
    BL_SKIP_WITHOUT_SHARED("data/glossy/veach-mis/veach_mis.xml");
    Scene xml = loadScene(bl::test::sharedPath("data/glossy/veach-mis/veach_mis.xml"));
    Scene twin = loadScene(bl::test::sourcePath("data/external/veach-mis.toml"));
    EXPECT_EQ(xml.triangleCount(), twin.triangleCount());
    EXPECT_EQ(xml.camera.resolution, twin.camera.resolution);
    EXPECT_EQ(xml.camera.fovAxis, twin.camera.fovAxis);
    EXPECT_FLOAT_EQ(xml.camera.fovDegrees, twin.camera.fovDegrees);
    for (Scene* s : {&xml, &twin}) s->camera.resolution = {48, 32};
    for (std::uint64_t seed : {1u, 2u}) {
        const Image a = bl::test::renderReference(xml, 16, {}, seed).radiance();
        const Image b = bl::test::renderReference(twin, 16, {}, seed).radiance();
        const ImageMetrics m = computeMetrics(a, b);
        EXPECT_LT(m.relMse, 1e-5) << "seed " << seed;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.meanRatio[c], 1.0, 1e-4) << "seed " << seed << ", channel " << c;
    }
}
