#include "modes/multibounce/SplatCoverage.h"

#include "bundle/BundleFrame.h"
#include "bundle/BundlePool.h"
#include "bundle/DirectionSampler.h"
#include "gpu/GpuScene.h"
#include "modes/multibounce/SurfacePoints.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bl::test {

namespace {

// A pixel's fragment depths, sorted.
std::vector<float> depthsOf(const std::vector<shader::BundleNode>& nodes, std::uint32_t head) {
    std::vector<float> depths;
    for (std::uint32_t i = head & shader::kBundleIndexMask; i != shader::kBundleNil;
         i = nodes[i].next & shader::kBundleIndexMask) {
        depths.push_back(nodes[i].depth);
    }
    std::sort(depths.begin(), depths.end());
    return depths;
}

// Whether two segment ends agree: both open (the ray leaves the scene) or within `tolerance`.
bool sameEnd(float a, float b, float tolerance) {
    return std::isinf(a) ? std::isinf(b) : !std::isinf(b) && std::abs(a - b) <= tolerance;
}

// Of the segments from each perfect fragment forward and backward, how many end elsewhere in the
// imperfect list (counted into `changed`; `segments` counts them all).
void compareSegments(const std::vector<float>& perfect, const std::vector<float>& imperfect, float tolerance,
                     double& changed, double& segments) {
    for (std::size_t i = 0; i < perfect.size(); ++i) {
        const float z = perfect[i];
        const float forward = i + 1 < perfect.size() ? perfect[i + 1] : INFINITY;
        const float backward = i > 0 ? perfect[i - 1] : -INFINITY;
        const auto after = std::upper_bound(imperfect.begin(), imperfect.end(), z + tolerance);
        const float imperfectForward = after == imperfect.end() ? INFINITY : *after;
        const auto before = std::lower_bound(imperfect.begin(), imperfect.end(), z - tolerance);
        const float imperfectBackward = before == imperfect.begin() ? -INFINITY : *(before - 1);
        changed += sameEnd(forward, imperfectForward, tolerance) ? 0 : 1;
        changed += sameEnd(backward, imperfectBackward, tolerance) ? 0 : 1;
        segments += 2;
    }
}

} // namespace

std::vector<SplatCoveragePoint> measureSplatCoverage(const vk::Context& ctx, const Scene& scene,
                                                     const std::vector<double>& scales, std::uint32_t directions,
                                                     std::uint32_t points, std::uint32_t resolution) {
    gpu::GpuScene gpuScene(ctx, scene);
    const Bounds bounds = scene.bounds();
    BundlePoolOptions options;
    options.slots = 2; // 0: perfect, 1: imperfect, same frame
    options.slotPixels = resolution * resolution;
    BundlePool pool(ctx, gpuScene, options);
    DirectionSampler sampler(DirectionSequence::Halton, 7);
    std::vector<SplatCoveragePoint> curve;
    for (double scale : scales) {
        SurfacePoints splats(ctx, gpuScene, directions, points, scale);
        double hits = 0, holes = 0, perfectNodes = 0, imperfectNodes = 0, changed = 0, segments = 0;
        for (std::uint32_t k = 0; k < directions; ++k) {
            const BundleDirection d = sampler.sample(k);
            const shader::BundleFrame frame =
                bundleFrameForSphere(d.omega, d.rotation, bounds.center(), bounds.radius(), resolution);
            BundlePoolStatus status;
            for (;;) {
                ctx.submitAndWait([&](VkCommandBuffer cmd) {
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
                const std::vector<float> dp = depthsOf(nodes, perfect[p]), di = depthsOf(nodes, imperfect[p]);
                perfectNodes += double(dp.size());
                imperfectNodes += double(di.size());
                if (dp.empty()) continue;
                hits += 1;
                holes += di.empty() || di.front() > dp.front() + tolerance ? 1 : 0;
                compareSegments(dp, di, tolerance, changed, segments);
            }
        }
        SplatCoveragePoint c;
        c.scale = scale;
        c.holes = holes / hits;
        c.redundantPerPixel = (imperfectNodes - perfectNodes) / hits;
        c.nodeRatio = imperfectNodes / perfectNodes;
        c.segmentsChanged = changed / segments;
        std::printf("splat_scale %.2f  holes %.5f (independent points: %.5f)  redundant nodes/pixel %.3f  node "
                    "ratio %.3f (s^2 = %.3f)  segments changed %.5f\n",
                    scale, c.holes, std::exp(-scale * scale), c.redundantPerPixel, c.nodeRatio, scale * scale,
                    c.segmentsChanged);
        curve.push_back(c);
    }
    return curve;
}

} // namespace bl::test
