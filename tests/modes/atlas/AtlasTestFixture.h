// The fixture and helpers the atlas mode tests share (AtlasModeTest.cpp, AtlasFurnaceTest.cpp).
// Statistics as in tests/support/Statistics.h; the biases the tests allow are derived in AtlasBias.h.
#pragma once

#include "modes/Registry.h"
#include "modes/atlas/AtlasBias.h"
#include "modes/atlas/AtlasMode.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "support/SeedMeans.h"
#include "support/Statistics.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace bl::test::atlasmode {

using bl::test::expectSeedsAgree;
using bl::test::lumaMean;
using bl::test::reflectedLight;

namespace stats = bl::test::stats;
namespace bias = bl::test::atlas;

inline constexpr std::uint32_t kSeeds = 8;
// The mode's default weighting k (direction j weighs j^k).
inline constexpr double kWeighting = 2.0;
// The statistical tests' images: 32^2 pixels.
inline constexpr int kStatResolution = 32;
inline constexpr std::uint32_t kReferenceSpp = 1024;

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

    // Per seed, the luma mean of the light reflected after `directions` (reflectedLight), and the
    // atlas's texel side into `side`.
    std::vector<double> reflectedMeans(const Scene& scene, std::uint32_t directions,
                                       const std::vector<std::string>& settings, std::uint32_t seeds, double& side);

    // Over `seeds` seeds, the reflected light (reflectedMeans) against the reference's less the
    // interleaved deficit (transport norm `norm`, `fromLights` as interleavedDeficit takes it) within
    // the texel bias of the reflected light; printed under `label`. Defined in AtlasModeTest.cpp.
    void expectReflectedLight(const Scene& scene, std::uint32_t directions, const std::vector<std::string>& settings,
                              std::uint32_t seeds, double norm, int fromLights, const std::string& label);

    // The direct atlas's two checks (point lights, or the first shot): over `seeds` seeds, layer
    // `direct` against the reference's within `other` + the texel bias of the direct light, and
    // `rest` against the reference's indirect1 + indirect2 + rest less the interleaved deficit
    // (transport norm `norm`) within `other` + the texel bias of the indirect light; printed under
    // `label`. `mapStrip` > 0: the environment shot's depth maps, whose pixels are mapStrip (half a
    // diagonal) wide: their visibility is the map pixel's centre, which can lose the light of contact
    // strips that wide on both sides (texelBias, bothSides), and the surface tolerance (a share of
    // the map's pixel) lets an occluder closer than it pass, which gains light there: the strips'
    // light either way, for the direct light and, which it feeds, the indirect light. Defined in
    // AtlasModeTest.cpp.
    void expectDirectAndIndirect(const Scene& scene, std::uint32_t directions, const std::vector<std::string>& settings,
                                 std::uint32_t seeds, double norm, double other, const std::string& label,
                                 double mapStrip = 0.0);

    // Layer `direct` of `both` against the sum of `one`'s and `other`'s (4 directions, the same
    // seed: the same points, directions and cubes), each of the two at least a tenth of the other;
    // printed under `label`. Defined in AtlasModeTest.cpp.
    void expectDirectLayersAdd(const Scene& one, const Scene& other, const Scene& both,
                               const std::vector<std::string>& settings, const char* label);

    // One seed's run at `directions`: its images (checked finite), and the atlas's texel side into
    // `side` on the first call (the atlas does not depend on the seed).
    ImageSet resolveSeed(const Scene& scene, std::uint32_t directions, const std::vector<std::string>& settings,
                         std::uint64_t seed, double& side) {
        std::unique_ptr<Mode> mode = run(scene, directions, settings, seed);
        if (side == 0.0) side = bias::texelSide(static_cast<const AtlasMode&>(*mode).readTexels().area);
        ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        return out;
    }
};

inline Scene loadSmall(const std::string& path, int resolution) {
    Scene s = loadScene(bl::test::sourcePath(path));
    s.camera.resolution = {resolution, resolution};
    return s;
}

inline std::vector<double> Atlas::reflectedMeans(const Scene& scene, std::uint32_t directions,
                                                 const std::vector<std::string>& settings, std::uint32_t seeds,
                                                 double& side) {
    std::vector<double> means;
    for (std::uint32_t seed : stats::seeds(seeds)) {
        means.push_back(lumaMean(reflectedLight(resolveSeed(scene, directions, settings, seed, side))));
    }
    return means;
}

} // namespace bl::test::atlasmode
