// Mode atlas against closed forms and the CPU reference path tracer (never against itself).
#include "image/Metrics.h"
#include "modes/Registry.h"
#include "modes/atlas/AtlasMode.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <algorithm>
#include <cstdio>

using namespace bl;

namespace {

class Atlas : public bl::test::VulkanTest {
protected:
    std::unique_ptr<Mode> run(const Scene& scene, std::uint32_t directions, const std::vector<std::string>& settings,
                              std::uint64_t seed = 1) {
        std::unique_ptr<Mode> mode = createMode("atlas", settings);
        mode->setScene(scene, &ctx());
        for (std::uint32_t i = 0; i < directions; ++i) {
            mode->iterate({i, seed, 0.0});
        }
        return mode;
    }
};

Scene loadSmall(const std::string& path, int resolution) {
    Scene s = loadScene(bl::test::sourcePath(path));
    s.camera.resolution = {resolution, resolution};
    return s;
}

} // namespace

// A closed box of albedo 1/2 emitting radiance 1 inward everywhere: the radiance of every texel's
// inner side is 1 / (1 - 1/2) = 2. Checks the estimator's weight rho a_pix / (pi p_r A_T), the
// exact texel areas (the atlas's own shares are off by 10-50% at triangle borders) and the
// interleaved sender, texel by texel.
TEST_F(Atlas, FurnaceTexelsReachTwo) {
    Scene s = loadSmall("data/analytic/furnace.toml", 16);
    std::unique_ptr<Mode> mode = run(s, 1024, {"atlas_resolution=64", "bundle_resolution=256"});
    const AtlasMode::TexelRadiance texels = static_cast<AtlasMode&>(*mode).readTexels();
    double worst = 0.0, mean = 0.0, areaSum = 0.0;
    std::size_t counted = 0;
    for (std::size_t t = 0; t < texels.area.size(); ++t) {
        if (texels.area[t] <= 0.0f) continue;
        const double l = texels.emission[t].x + texels.reflected[2 * t].x; // the inner side is the front
        worst = std::max(worst, std::abs(l - 2.0));
        mean += l * texels.area[t];
        areaSum += texels.area[t];
        ++counted;
    }
    mean /= areaSum;
    std::printf("furnace: %zu texels, area-weighted mean %.5f, worst |L - 2| %.5f\n", counted, mean, worst);
    EXPECT_GT(counted, 100u);
    EXPECT_NEAR(mean, 2.0, 0.01);
    EXPECT_LT(worst, 0.02);
}
