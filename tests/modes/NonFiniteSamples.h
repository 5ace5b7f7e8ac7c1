// One check every GPU mode's tests run: a NaN/Inf sample is counted and never averaged in.
#pragma once

#include "modes/Registry.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>
#include <limits>

namespace bl::test {

// The furnace box with infinite emitters (the loader refuses them, so they are set in memory): every
// pixel's every sample is infinite. The mode must count each one and still resolve to a finite image.
inline void expectInfiniteSamplesCounted(const std::string& modeName, vk::Context* ctx,
                                         const std::vector<std::string>& settings = {}) {
    Scene s = loadScene(sourcePath("data/analytic/furnace.toml"));
    s.camera.resolution = {4, 4};
    for (Mesh& m : s.meshes) m.emission = glm::vec3(std::numeric_limits<float>::infinity());
    std::unique_ptr<Mode> mode = createMode(modeName, settings);
    mode->setScene(s, ctx);
    constexpr std::uint32_t kIterations = 3;
    for (std::uint32_t i = 0; i < kIterations; ++i) {
        mode->iterate({i, 0, 0.0});
    }
    ImageSet out = mode->resolve();
    EXPECT_EQ(out.nonFiniteSamples, 4u * 4u * kIterations) << modeName;
    EXPECT_EQ(out.radiance().countNonFinite(), 0u) << modeName;
}

} // namespace bl::test
