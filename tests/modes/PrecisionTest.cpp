// Issue 19, geometric precision: the point-lit Cornell box 1e6 mm from the origin, and scaled by
// 1e-6 .. 1e6 (intensity by s^2), renders the image of the box as it is; a point light lying on
// the floor (or 1e-4 above it) lights the ceiling in the reference as in the GPU modes.
//
// Every comparison renders both sides with the same seed (common random numbers), so they differ
// only where the geometry's float rounding differs: far less than two independent estimates would.
#include "modes/Registry.h"
#include "modes/reference/ReferenceTestSupport.h"
#include "scene/SceneLoader.h"
#include "support/MovedScenes.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <cstdio>

using namespace bl;

namespace {

const char* kBox = "data/cornell-box/cornell-point.toml";

class Precision : public bl::test::VulkanTest {
protected:
    ImageSet render(const Scene& scene, const std::string& mode, std::uint32_t iterations,
                    const std::vector<std::string>& settings = {}) {
        std::unique_ptr<Mode> m = createMode(mode, settings);
        m->setScene(scene, mode == "reference" ? nullptr : &ctx());
        for (std::uint32_t i = 0; i < iterations; ++i) {
            m->iterate({i, 7, 0.0});
        }
        ImageSet out = m->resolve();
        EXPECT_EQ(out.nonFiniteSamples, 0u) << mode;
        return out;
    }

    static Scene small(Scene s) {
        s.camera.resolution = {32, 32};
        return s;
    }

    // Mean of each image and the largest per-pixel difference relative to the brighter pixel
    // (pixels below 1% of the image mean left out: relative noise there means nothing).
    struct Difference {
        double ratio = 0.0;        // mean(moved) / mean(base), luminance-weighted equally over rgb
        double worst = 0.0;        // largest |a - b| / max(a, b) over pixels
        std::size_t differing = 0; // pixels differing by more than 1%
    };
    static Difference compare(const Image& base, const Image& moved) {
        Difference d;
        const double mb = glm::dot(base.mean(), glm::dvec3(1.0)),
                     mm = glm::dot(moved.mean(), glm::dvec3(1.0));
        d.ratio = mm / mb;
        for (std::size_t i = 0; i < base.pixelCount(); ++i) {
            const double a = glm::dot(glm::dvec3(base.pixels()[i]), glm::dvec3(1.0));
            const double b = glm::dot(glm::dvec3(moved.pixels()[i]), glm::dvec3(1.0));
            if (std::max(a, b) < 0.01 * mb)
                continue;
            const double rel = std::abs(a - b) / std::max(a, b);
            d.worst = std::max(d.worst, rel);
            d.differing += rel > 0.01;
        }
        return d;
    }
};

struct ModeCase {
    const char* mode;
    std::uint32_t iterations;
    std::vector<std::string> settings;
    double ratio;     // |mean ratio - 1| allowed
    double differing; // fraction of pixels allowed to differ by more than 1% (< 0: not checked)
};

// Raster is deterministic given the seed: moved or scaled, its image may differ only in edge
// pixels the float rounding moves (measured: none by more than 0.14%); 1e-3 on the mean, 0.5% of
// the pixels. The estimators run on common random numbers, so their two images differ only where
// rounding changes a path (measured: mean ratio 0.99995 and 1.00078 at 1e6): the bound is one
// standard deviation of the image mean over seeds (1..4, this box at 32^2: reference 16 spp 1.17%,
// multibounce 8 directions 1.5%), a change as large as drawing a new seed. Before the fix the box
// at 1e6 gave raster 0.73x, multibounce 0.84x.
const ModeCase kModes[] = {
    {"raster", 4, {}, 1e-3, 0.005},
    {"reference", 16, {}, 0.0117, -1.0},
    {"multibounce", 8, {"bundle_resolution=64"}, 0.015, -1.0},
};

} // namespace

TEST_F(Precision, BoxAMillionMillimetresOutRendersLikeTheBox) {
    const Scene base = small(loadScene(bl::test::sourcePath(kBox)));
    const Scene moved = small(loadScene(bl::test::writeMovedScene(kBox, glm::dvec3(1e6))));
    for (const ModeCase& c : kModes) {
        const Difference d = compare(render(base, c.mode, c.iterations, c.settings).radiance(),
                                     render(moved, c.mode, c.iterations, c.settings).radiance());
        std::printf(
            "%-12s offset 1e6: mean ratio %.5f, %zu of %zu pixels differ by > 1%% (worst %.4f)\n",
            c.mode, d.ratio, d.differing,
            base.camera.resolution.x * std::size_t(base.camera.resolution.y), d.worst);
        EXPECT_NEAR(d.ratio, 1.0, c.ratio) << c.mode;
        if (c.differing >= 0.0) {
            EXPECT_LE(double(d.differing), c.differing * 32 * 32) << c.mode;
        }
    }
}

TEST_F(Precision, ScaledBoxRendersLikeTheBox) {
    const Scene base = small(loadScene(bl::test::sourcePath(kBox)));
    std::vector<Image> baseImages;
    for (const ModeCase& c : kModes) {
        baseImages.push_back(render(base, c.mode, c.iterations, c.settings).radiance());
    }
    for (const double scale : {1e-6, 1e-3, 1e3, 1e6}) {
        const Scene scaled =
            small(loadScene(bl::test::writeMovedScene(kBox, glm::dvec3(0.0), scale)));
        for (std::size_t m = 0; m < std::size(kModes); ++m) {
            const ModeCase& c = kModes[m];
            const Difference d =
                compare(baseImages[m], render(scaled, c.mode, c.iterations, c.settings).radiance());
            std::printf(
                "%-12s scale %g: mean ratio %.5f, %zu pixels differ by > 1%% (worst %.4f)\n",
                c.mode, scale, d.ratio, d.differing, d.worst);
            EXPECT_NEAR(d.ratio, 1.0, c.ratio) << c.mode << " scale " << scale;
            if (c.differing >= 0.0) {
                EXPECT_LE(double(d.differing), c.differing * 32 * 32)
                    << c.mode << " scale " << scale;
            }
        }
    }
}

// bidir's VPLs come from reflective shadow maps rendered from the light; their face cameras looked
// at position + f (f a unit axis), which float's spacing swallowed beyond 2^24: scaled by 1e6 the
// RSM came back empty, every VPL was lost and indirect1 read 0.43 of the box's, indirect2 0. Same
// seed on both sides: the scaled box is the same scene to float precision (measured 1.000000).
TEST_F(Precision, ScaledBoxKeepsBidirsVpls) {
    const std::vector<std::string> settings = {"pairs_per_frame=4"};
    const ImageSet base = render(small(loadScene(bl::test::sourcePath(kBox))), "bidir", 2, settings);
    const ImageSet scaled =
        render(small(loadScene(bl::test::writeMovedScene(kBox, glm::dvec3(0.0), 1e6))), "bidir", 2, settings);
    for (const char* layer : {"indirect1", "indirect2"}) {
        const Difference d = compare(bl::test::layerOf(base, layer), bl::test::layerOf(scaled, layer));
        std::printf("bidir scale 1e6 %s: mean ratio %.6f\n", layer, d.ratio);
        EXPECT_NEAR(d.ratio, 1.0, 1e-3) << layer;
    }
}

TEST_F(Precision, LightOnTheFloorLightsTheCeilingInTheReferenceAsInRaster) {
    for (const float height : {0.0f, 1e-4f}) {
        Scene s = small(loadScene(bl::test::sourcePath(kBox)));
        s.lights.at(0).position = glm::vec3(278.0f, height, 279.5f); // the floor is y = 0
        const Image raster = render(s, "raster", 4).radiance();
        const Image direct = bl::test::layerOf(render(s, "reference", 16), "direct");
        // The ceiling: the top rows, which see nothing else at 32^2 (y = 548.8 from z = 0 to 559).
        auto ceiling = [](const Image& img) {
            double sum = 0.0;
            for (int y = 1; y < 6; ++y)
                for (int x = 8; x < 24; ++x)
                    sum += img.at(x, y).y;
            return sum / (5 * 16);
        };
        const double r = ceiling(raster), p = ceiling(direct);
        std::printf("light %g above the floor: ceiling raster %.5f reference %.5f\n", height, r, p);
        // Before the fix the reference read 0.00079 with the light on the floor (0.02145 at 1e-4,
        // where the floor lies beyond the light). The same point light straight above a smooth
        // region: raster's shadow cube and the reference agree there to 0.4% (measured); 3% leaves
        // room for the reference's pixel jitter at 16 spp. The whole image is not compared: pixels
        // next to the light vary as 1/d^2 within a pixel, and their means move ~9% between seeds.
        EXPECT_GT(r, 0.01);
        EXPECT_NEAR(p / r, 1.0, 0.03) << "height " << height;
    }
}
