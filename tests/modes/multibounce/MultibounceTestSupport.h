// The fixture, bounds and checks the multibounce mode tests share (MultibounceTest.cpp,
// MultibounceTexturedTest.cpp). Statistics as in tests/support/Statistics.h: kSeeds seeds, the
// seeds' mean held to the reference (or a closed form) within a tolerance plus t(1 - alpha/2, n - 1)
// standard errors behind the noise gate; regions Holm-corrected. Tolerances are biases derived
// below (bundleMisassignment), never windows about a measured mean.
//
// The bundle-resolution bias, derived (MultibounceMode.h: the next vertex is found on the bundle
// pixel's centre ray, then placed on that fragment's plane along the exact ray). A segment goes
// wrong only where the exact ray and the pixel's centre ray lie on different sides of a geometric
// edge in the bundle's projection. The offset between them is uniform over a pixel of side p
// (p = 2 r / R: the bundle covers the bounding sphere, R pixels a side), so the measure of rays
// whose offset crosses a projected edge of length l is at most l * max_theta E|u . n| = l p / 4.
// Averaged over uniform directions a segment of length L projects to (pi / 4) L and a surface of
// area S to S / 4 (Cauchy), so for isotropic uniform lines (the chords from surface points with
// cosine-weighted directions) the share of segments that can go wrong is at most
//     f = (pi / 4) sum(L) (p / 4) / (S / 4) = pi p sum(L) / (4 S),
// the sum over the scene's geometric edges (creases and borders; coplanar diagonals excluded).
// The white furnace's box (side a, sum L = 12 a, S = 6 a^2, 2 r = sqrt(3) a): f = pi sqrt(3) / (2 R),
// 2.1% at the default R = 128 (measured loss: 0.75% per bounce, README).
#pragma once

#include "modes/Registry.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "support/AnalyticScenes.h"
#include "support/Statistics.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <cmath>
#include <cstdio>

namespace bl::test::multibounce {

namespace stats = bl::test::stats;

// The statistical tests: 32^2 pixels in 4 x 4 regions of 8 x 8 pixels, kSeeds seeds (1..8).
constexpr int kStatResolution = 32;
constexpr int kRegions = 4;
constexpr std::uint32_t kSeeds = 8;
// The textured-albedo tests: fewer seeds (their tolerances are wider than the untextured box's).
constexpr std::uint32_t kTextureSeeds = 4;
constexpr std::uint32_t kReferenceSpp = 1024;
constexpr double kPi = 3.14159265358979323846;
// The mode's default bundle side (MultibounceMode.h), which the statistical tests use.
constexpr int kBundleResolution = 128;
// Direct light from point lights (shadow cubes, 4x4 PCF, no bundle segment): the filter is
// symmetric about a shadow boundary, so it moves no light to first order; what is left is the
// depth bias's band beside contact shadows, two texels of a 512^2 face (0.35 degrees, under 2 mm
// at the box's distances, well below 1% of any region's light). Held to 1%.
constexpr double kShadowTolerance = 0.01;
// Direct light from the emitter points' cubes (256^2 by default, one tap each: EmitterPointLight.glsl):
// a receiver within half a texel of a concave contact may read the other surface. A texel is
// 2 / 256 rad, about 4 mm at the box's far corners: a band of ~2 mm along ~12 contact edges of
// ~550 mm is about 0.9 % of the ~1.5 m^2 of surface, which loses at most half its light there: a
// bias under 0.5 %, held to 1 %.
constexpr double kEmitterShadowTolerance = 0.01;
// A Cornell-box path of k >= 3 bundle segments (layer `rest`): its expected segment count with
// albedo at most 0.8 (a geometric tail: 3 + 0.8 / 0.2) bounds its share of misassigned segments.
constexpr double kRestSegments = 7.0;

// f = pi p sum(L) / (4 S): the share of bundle segments that can go wrong at bundle side R (above),
// L the scene's creases and borders, S its area (edgeStats).
inline double bundleMisassignment(const Scene& s, int resolution) {
    const bl::test::EdgeStats e = bl::test::edgeStats(s.meshes);
    const double pixel = 2.0 * double(s.bounds().radius()) / double(resolution);
    const double f = kPi * pixel * e.creaseLength / (4.0 * e.area);
    std::printf("edges %.1f, area %.1f, bundle pixel %.3f: misassigned share f = %.4f at %d^2\n", e.creaseLength, e.area,
                pixel, f, resolution);
    return f;
}

class Multibounce : public bl::test::VulkanTest {
protected:
    ImageSet render(const Scene& scene, std::uint32_t iterations, const std::vector<std::string>& settings,
                    std::uint64_t seed = 1) {
        std::unique_ptr<Mode> mode = createMode("multibounce", settings);
        mode->setScene(scene, &ctx());
        for (std::uint32_t i = 0; i < iterations; ++i) {
            mode->iterate({i, seed, 0.0});
        }
        ImageSet out = mode->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u);
        EXPECT_EQ(out.radiance().countNonFinite(), 0u);
        return out;
    }
    // One image set per seed 1..count.
    std::vector<ImageSet> renderSeeds(const Scene& scene, std::uint32_t iterations,
                                      const std::vector<std::string>& settings, std::uint32_t count = kSeeds) {
        std::vector<ImageSet> out;
        for (std::uint32_t seed : stats::seeds(count)) out.push_back(render(scene, iterations, settings, seed));
        return out;
    }
};

inline Scene loadSmall(const std::string& path, int resolution) {
    Scene s = loadScene(bl::test::sourcePath(path));
    s.camera.resolution = {resolution, resolution};
    return s;
}

// A layer's image ("" = radiance).
inline const Image& layer(const ImageSet& set, const std::string& name) {
    return name.empty() ? set.radiance() : bl::test::layerOf(set, name);
}

inline double imageMean(const Image& image) {
    double sum = 0.0;
    for (double v : stats::blockMeans(image, kStatResolution / kRegions)) sum += v;
    return sum / double(kRegions * kRegions);
}

// The seeds' image means (luminance) of a layer within `tolerance` (relative) of the reference's.
inline void expectLayerMean(const std::vector<ImageSet>& runs, const ImageSet& reference, const std::string& name,
                     double tolerance, const std::string& what) {
    std::vector<double> means;
    for (const ImageSet& r : runs) means.push_back(imageMean(layer(r, name)));
    const stats::Summary s = stats::summarize(means);
    const double ref = imageMean(layer(reference, name));
    std::printf("%s %-9s: image mean %.5f +- %.5f (stderr; seeds' sd %.5f), reference %.5f: %+.2f%% (tolerance %.2f%%)\n",
                what.c_str(), name.empty() ? "radiance" : name.c_str(), s.mean, s.stderr_, s.stddev, ref,
                100.0 * (s.mean / ref - 1.0), 100.0 * tolerance);
    EXPECT_TRUE(stats::agrees(s, ref, tolerance * ref, what + " " + (name.empty() ? "radiance" : name)));
}

// One channel of an image as a grey image (its luminance is that channel).
inline Image channelOf(const Image& image, int channel) {
    Image out = image;
    for (glm::vec3& p : out.pixels()) p = glm::vec3(p[channel]);
    return out;
}

// Every region of a layer (luminance, or one channel: `channel` >= 0) within `tolerance`
// (relative, dim regions floored at `floor` of the mean region) of the reference's, Holm-corrected
// over the regions.
inline void expectLayerRegions(const std::vector<ImageSet>& runs, const ImageSet& reference, const std::string& name,
                        double tolerance, double floor, const std::string& what, int channel = -1) {
    const auto regions = [&](const Image& image) {
        return stats::blockMeans(channel < 0 ? image : channelOf(image, channel), kStatResolution / kRegions);
    };
    std::vector<std::vector<double>> perSeed;
    for (const ImageSet& r : runs) perSeed.push_back(regions(layer(r, name)));
    const std::vector<double> ref = regions(layer(reference, name));
    EXPECT_TRUE(stats::regionsAgree(perSeed, ref, {tolerance, floor, stats::kAlpha},
                                    what + " " + (name.empty() ? "radiance" : name) +
                                        (channel < 0 ? "" : " channel " + std::to_string(channel))));
}

// The image's tolerance from its layers': sum over layers of the reference's share times the
// layer's bound.
inline double imageTolerance(const ImageSet& reference, const std::vector<std::pair<std::string, double>>& layerBounds) {
    const double all = imageMean(reference.radiance());
    double t = 0.0;
    for (const auto& [name, bound] : layerBounds) t += bound * imageMean(bl::test::layerOf(reference, name)) / all;
    return t;
}

// Regions of the Cornell box: a region may hold an edge of the box, where its camera points lie
// within a bundle pixel of their own face's edge twice as often as on average (the edges at x's
// end are half of the union bound f counts), so regions are held to twice the image's bound.
constexpr double kRegionFactor = 2.0;
// Regions with under a quarter of the mean region's light are held to that quarter's tolerance.
constexpr double kDimRegion = 0.25;


} // namespace bl::test::multibounce
