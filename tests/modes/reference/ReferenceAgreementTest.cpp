// The reference against an independent path tracer (Tungsten, 1024 spp) on McGuire's Cornell box.
#include "image/ImageIO.h"
#include "image/Metrics.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"

using namespace bl;

TEST(ReferenceAgreement, McGuireCornellBoxMatchesTungsten) {
    BL_SKIP_WITHOUT_SCENE_FILES("data/external/cornell-mcguire.toml");
    BL_SKIP_WITHOUT_SHARED("references/cornell-mcguire/mcguire-CornellBox-Original_256_1024spp.exr");
    Scene s = loadScene(bl::test::sourcePath("data/external/cornell-mcguire.toml"));
    ASSERT_EQ(s.camera.resolution, glm::ivec2(256, 256));
    // 256 spp: block-ratio noise ~1.1% (it halves with 4x the block area: noise, not bias).
    Image ours = bl::test::renderReference(s, 256).radiance();
    Image tungsten = readImage(
        bl::test::sharedPath("references/cornell-mcguire/mcguire-CornellBox-Original_256_1024spp.exr"));
    ImageMetrics m = computeMetrics(ours, tungsten);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(m.meanRatio[c], 1.0, 0.005) << "channel " << c;
    }
    EXPECT_LT(m.blockRatios.rms, 0.015);
    EXPECT_GT(m.blockRatios.blocks, 900u);
    if (HasFailure()) {
        std::string dir = bl::test::tempDir();
        writeExr(dir + "/ours.exr", ours);
        writeExr(dir + "/tungsten.exr", tungsten);
        ADD_FAILURE() << "images written to " << dir;
    }
}
