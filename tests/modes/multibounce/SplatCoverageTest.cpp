// Imperfect bundles ([TO12p]): the trade-off the poster names, measured against perfect bundles of
// the same frames. For each splat_scale s, a perfect bundle (the triangles) and an imperfect one
// (SurfacePoints' splats) are built along the same directions; per bundle pixel whose ray meets a
// surface:
//   holes     the imperfect bundle has no fragment up to the perfect bundle's first hit (+ a pixel
//             of slope): the ray passes through the surface, light leaks;
//   redundant imperfect nodes minus perfect nodes, per pixel with a hit, and the node ratio;
//   segments  the share of segments (from each perfect fragment, both ways) that end elsewhere.
// Independent uniform points predict holes exp(-s^2) and a node ratio of s^2; the sampler's
// stratified points leave fewer holes.
//
// Also a tool: BL_SPLAT_CURVE_SCENE=path/to/scene.toml BL_SPLAT_CURVE_DIRECTIONS=64
// test_multibounce --gtest_filter='SplatCoverage.*' prints the curve for any scene (the bounds of
// the test apply to the Cornell box only).
#include "modes/multibounce/SplatCoverage.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace bl;

// Cornell box, 16 directions of 128^2, 16384 points per direction (the poster's density).
class SplatCoverage : public bl::test::VulkanTest {};

TEST_F(SplatCoverage, HolesFallAndRedundantNodesGrowWithTheSplatScale) {
    const char* sceneEnv = std::getenv("BL_SPLAT_CURVE_SCENE");
    const char* directionsEnv = std::getenv("BL_SPLAT_CURVE_DIRECTIONS");
    const bool cornell = sceneEnv == nullptr;
    const Scene scene = loadScene(cornell ? bl::test::sourcePath("data/cornell-box/cornell.toml") : std::string(sceneEnv));
    const std::uint32_t directions = directionsEnv ? static_cast<std::uint32_t>(std::atoi(directionsEnv)) : 16;
    const std::vector<double> scales{0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0};
    const std::vector<bl::test::SplatCoveragePoint> curve =
        bl::test::measureSplatCoverage(ctx(), scene, scales, directions, 16384, 128);
    if (!cornell) return;
    for (std::size_t i = 1; i < curve.size(); ++i) {
        EXPECT_LE(curve[i].holes, curve[i - 1].holes) << "scale " << curve[i].scale;
        EXPECT_GT(curve[i].redundantPerPixel, curve[i - 1].redundantPerPixel) << "scale " << curve[i].scale;
    }
    // Segments moved fall with the holes, then rise with the splats reaching past edges: the
    // mode's default scale (2) sits at the trade-off's bottom (within 10% of the least).
    double least = 1.0, atDefault = 1.0;
    for (const bl::test::SplatCoveragePoint& c : curve) {
        least = std::min(least, c.segmentsChanged);
        if (c.scale == 2.0) atDefault = c.segmentsChanged;
    }
    EXPECT_LE(atDefault, 1.1 * least) << "segments moved at splat_scale 2";
    for (const bl::test::SplatCoveragePoint& c : curve) {
        // The discs of a direction cover s^2 times the surface: nodes follow, within the pixel
        // sampling of small discs and the splats reaching past the box's edges.
        EXPECT_NEAR(c.nodeRatio, c.scale * c.scale, 0.03 * c.scale * c.scale + 0.02) << "scale " << c.scale;
        // Stratified points never leave more holes than independent ones (plus noise).
        EXPECT_LT(c.holes, std::exp(-c.scale * c.scale) + 0.01) << "scale " << c.scale;
    }
}
