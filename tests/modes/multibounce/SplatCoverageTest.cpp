// Imperfect bundles ([TO12p]): the trade-off the poster names, measured against perfect bundles of
// the same frames. For each splat_scale s, a perfect bundle (the triangles) and an imperfect one
// (SurfacePoints' splats) are built along the same directions; per bundle pixel whose ray meets a
// surface:
//   holes     the imperfect bundle has no fragment up to the perfect bundle's first hit (+ a pixel
//             of slope): the ray passes through the surface, light leaks;
//   redundant imperfect nodes minus perfect nodes, per pixel with a hit, and the node ratio.
// Independent uniform points predict holes exp(-s^2) and a node ratio of s^2; the sampler's
// stratified points leave fewer holes.
//
// Also a tool: BL_SPLAT_CURVE_SCENE=path/to/scene.toml BL_SPLAT_CURVE_DIRECTIONS=64
// test_multibounce --gtest_filter='SplatCoverage.*' prints the curve for any scene (the bounds of
// the test apply to the Cornell box only).
#include "bundle/BundleFrame.h"
#include "bundle/BundlePool.h"
#include "bundle/DirectionSampler.h"
#include "modes/multibounce/SurfacePoints.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"
#include "support/VulkanTest.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace bl;

namespace {

struct CurvePoint {
    double scale = 0.0;
    double holes = 0.0;          // fraction of perfect first hits the imperfect bundle misses
    double redundantPerPixel = 0.0;
    double nodeRatio = 0.0;      // imperfect nodes / perfect nodes
};

// Nearest depth of a pixel's list, or +inf when empty.
float firstDepth(const std::vector<shader::BundleNode>& nodes, std::uint32_t head) {
    float best = INFINITY;
    for (std::uint32_t i = head & shader::kBundleIndexMask; i != shader::kBundleNil;
         i = nodes[i].next & shader::kBundleIndexMask) {
        best = std::min(best, nodes[i].depth);
    }
    return best;
}

class SplatCoverage : public bl::test::VulkanTest {
protected:
    std::vector<CurvePoint> measure(const Scene& scene, const std::vector<double>& scales, std::uint32_t directions,
                                    std::uint32_t points, std::uint32_t resolution) {
        gpu::GpuScene gpuScene(ctx(), scene);
        const Bounds bounds = scene.bounds();
        BundlePoolOptions options;
        options.slots = 2; // 0: perfect, 1: imperfect, same frame
        options.slotPixels = resolution * resolution;
        BundlePool pool(ctx(), gpuScene, options);
        DirectionSampler sampler(DirectionSequence::Halton, 7);
        std::vector<CurvePoint> curve;
        for (double scale : scales) {
            SurfacePoints splats(ctx(), gpuScene, directions, points, scale);
            double hits = 0, holes = 0, perfectNodes = 0, imperfectNodes = 0;
            for (std::uint32_t k = 0; k < directions; ++k) {
                const BundleDirection d = sampler.sample(k);
                const shader::BundleFrame frame =
                    bundleFrameForSphere(d.omega, d.rotation, bounds.center(), bounds.radius(), resolution);
                BundlePoolStatus status;
                for (;;) {
                    ctx().submitAndWait([&](VkCommandBuffer cmd) {
                        pool.recordReset(cmd);
                        if (k == 0) splats.record(cmd, 1, 0, 0.0);
                        pool.recordBuild(cmd, 0, frame, BundleGeometry::triangles(0.0));
                        pool.recordBuild(cmd, 1, frame, BundleGeometry::pointSplats(splats.splats(k), points));
                    });
                    status = pool.status();
                    if (!status.overflowed()) break;
                    EXPECT_TRUE(pool.grow(status)) << "pool limits";
                }
                const std::vector<shader::BundleNode> nodes = pool.readNodes(status.requested);
                const std::vector<std::uint32_t> perfect = pool.readHeads(0), imperfect = pool.readHeads(1);
                // A pixel of slope beyond the exact plane depth: splats of curved surfaces lie on
                // tangent planes, not on the triangles.
                const float tolerance = frame.depthEpsilon + 2.0f * frame.pixelSize;
                for (std::size_t p = 0; p < perfect.size(); ++p) {
                    const float dp = firstDepth(nodes, perfect[p]);
                    if (!std::isfinite(dp)) continue;
                    hits += 1;
                    holes += firstDepth(nodes, imperfect[p]) > dp + tolerance ? 1 : 0;
                }
                for (std::uint32_t s = 0; s < 2; ++s) {
                    double count = 0;
                    for (std::uint32_t h : s == 0 ? perfect : imperfect) {
                        for (std::uint32_t i = h & shader::kBundleIndexMask; i != shader::kBundleNil;
                             i = nodes[i].next & shader::kBundleIndexMask) {
                            count += 1;
                        }
                    }
                    (s == 0 ? perfectNodes : imperfectNodes) += count;
                }
            }
            CurvePoint c;
            c.scale = scale;
            c.holes = holes / hits;
            c.redundantPerPixel = (imperfectNodes - perfectNodes) / hits;
            c.nodeRatio = imperfectNodes / perfectNodes;
            std::printf("splat_scale %.2f  holes %.5f (independent points: %.5f)  redundant nodes/pixel %.3f  node "
                        "ratio %.3f (s^2 = %.3f)\n",
                        scale, c.holes, std::exp(-scale * scale), c.redundantPerPixel, c.nodeRatio, scale * scale);
            curve.push_back(c);
        }
        return curve;
    }
};

} // namespace

// Cornell box, 16 directions of 128^2, 16384 points per direction (the poster's density).
TEST_F(SplatCoverage, HolesFallAndRedundantNodesGrowWithTheSplatScale) {
    const char* sceneEnv = std::getenv("BL_SPLAT_CURVE_SCENE");
    const char* directionsEnv = std::getenv("BL_SPLAT_CURVE_DIRECTIONS");
    const bool cornell = sceneEnv == nullptr;
    const Scene scene = loadScene(cornell ? bl::test::sourcePath("data/cornell-box/cornell.toml") : std::string(sceneEnv));
    const std::uint32_t directions = directionsEnv ? static_cast<std::uint32_t>(std::atoi(directionsEnv)) : 16;
    const std::vector<double> scales{0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0};
    const std::vector<CurvePoint> curve = measure(scene, scales, directions, 16384, 128);
    if (!cornell) return;
    for (std::size_t i = 1; i < curve.size(); ++i) {
        EXPECT_LE(curve[i].holes, curve[i - 1].holes) << "scale " << curve[i].scale;
        EXPECT_GT(curve[i].redundantPerPixel, curve[i - 1].redundantPerPixel) << "scale " << curve[i].scale;
    }
    for (const CurvePoint& c : curve) {
        // The discs of a direction cover s^2 times the surface: nodes follow, within the pixel
        // sampling of small discs and the splats reaching past the box's edges.
        EXPECT_NEAR(c.nodeRatio, c.scale * c.scale, 0.03 * c.scale * c.scale + 0.02) << "scale " << c.scale;
        // Stratified points never leave more holes than independent ones (plus noise).
        EXPECT_LT(c.holes, std::exp(-c.scale * c.scale) + 0.01) << "scale " << c.scale;
    }
}
