// The fixture and helpers the atlas mode tests share (AtlasModeTest.cpp, AtlasFurnaceTest.cpp).
// Statistics as in tests/support/Statistics.h; the biases the tests allow are derived in AtlasBias.h.
#pragma once

#include "modes/Registry.h"
#include "modes/atlas/AtlasBias.h"
#include "modes/atlas/AtlasMode.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "support/Statistics.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace bl::test::atlasmode {

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

// The light an image set shows reflected: radiance less the emitted layer (emitters and the
// background seen directly, which the view samples rather than the exchange).
inline Image reflectedLight(const ImageSet& set) {
    Image light = set.radiance();
    const Image& emitted = bl::test::layerOf(set, "emitted");
    for (std::size_t p = 0; p < light.pixelCount(); ++p) light.pixels()[p] -= emitted.pixels()[p];
    return light;
}

inline Scene loadSmall(const std::string& path, int resolution) {
    Scene s = loadScene(bl::test::sourcePath(path));
    s.camera.resolution = {resolution, resolution};
    return s;
}

// The luminance image mean of an image.
inline double lumaMean(const Image& image) {
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels()) sum += stats::luminance(p);
    return sum / double(image.pixelCount());
}

// The seeds' means against `expected` within `tolerance` (absolute), printed.
inline void expectSeedsAgree(const std::vector<double>& perSeed, double expected, double tolerance, const std::string& what) {
    const stats::Summary s = stats::summarize(perSeed);
    std::printf("%s: %.6g +- %.3g (stderr; seeds' sd %.3g, %zu seeds), expected %.6g (%+.3f%%), tolerance %.3g "
                "(%.3f%%)\n",
                what.c_str(), s.mean, s.stderr_, s.stddev, s.n, expected, 100.0 * (s.mean / expected - 1.0), tolerance,
                100.0 * tolerance / expected);
    EXPECT_TRUE(stats::agrees(s, expected, tolerance, what));
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
