// Rendering helpers shared by the raster mode's tests.
#pragma once

#include "modes/Registry.h"
#include "scene/Scene.h"
#include "support/VulkanTest.h"

namespace bl::test {

class RasterTest : public VulkanTest {
protected:
    ImageSet render(const Scene& scene, std::uint32_t iterations = 1, const std::vector<std::string>& settings = {},
                    std::uint64_t seed = 0) {
        std::unique_ptr<Mode> mode = createMode("raster", settings);
        mode->setScene(scene, &ctx());
        for (std::uint32_t i = 0; i < iterations; ++i) {
            mode->iterate({i, seed, 0.0});
        }
        ImageSet out = mode->resolve();
        EXPECT_EQ(out.radiance().countNonFinite(), 0u);
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        return out;
    }
};

} // namespace bl::test
