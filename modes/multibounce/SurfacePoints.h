// Imperfect bundles ([TO12p], papers/EQUATIONS.md): per iteration, a different set of N points
// per direction, uniform by area over all surfaces, turned into tangent-plane splats for
// BundlePool::recordBuild (BundleGeometry::pointSplats) plus what a path vertex found on a splat
// needs (MultibouncePoint: shading normal, triangle, and the UV as a linear function of position in
// the splat's plane: the poster's texture coordinates at each splat corner, so the path pass looks a
// textured albedo up where the path meets the splat, not at its centre).
//
// Sampling runs on the GPU (points.comp.glsl): a binary search of an area CDF over the scene's
// triangles (built on the host once, in double: rigid animation keeps areas), then square-root
// barycentrics; cost O(K N log T) per iteration, independent of the rasterization of T triangles.
//
// Splat radius from the point density: r = splat_scale * sqrt(A / (pi N)) for total area A, so
// the discs of one direction cover splat_scale^2 times the surface. For independent uniform points
// a surface point lies in no disc with probability exp(-splat_scale^2) (the holes, light leaking)
// and in splat_scale^2 discs on average (the redundant nodes); the points' stratification lowers
// the holes below that (measured: README, mode multibounce).
#pragma once

#include "gpu/GpuScene.h"
#include "vk/Buffer.h"
#include "vk/BoundSet.h"
#include "vk/GpuTimer.h"
#include "vk/ComputePass.h"

#include <modes/multibounce/MultibounceShared.h>
#include <vector>

namespace bl {

class SurfacePoints {
public:
    // Room for `directions` sets of `perDirection` points; `splatScale` > 0.
    SurfacePoints(const vk::Context& ctx, const gpu::GpuScene& scene, std::uint32_t directions,
                  std::uint32_t perDirection, double splatScale);

    // Samples every direction's points for (seed, iteration) at scene time `time`. The draw table is
    // a host write: call between submissions.
    void record(VkCommandBuffer cmd, std::uint32_t seed, std::uint32_t iteration, double time,
                vk::GpuTimer* timer = nullptr);

    std::uint32_t perDirection() const { return mPerDirection; }
    std::uint32_t directions() const { return mDirections; }
    double totalArea() const { return mArea; }
    float radius() const { return mRadius; }
    // Device address of direction k's BundleSplat array (perDirection() splats).
    VkDeviceAddress splats(std::uint32_t direction) const;
    VkBuffer pointBuffer() const { return mPoints.get(); }
    VkBuffer splatBuffer() const { return mSplats.get(); }

private:
    const vk::Context* mContext;
    const gpu::GpuScene* mScene;
    std::uint32_t mDirections;
    std::uint32_t mPerDirection;
    std::uint32_t mTriangles = 0;
    double mArea = 0.0;
    float mRadius = 0.0f;
    vk::Buffer mCdf;
    vk::Buffer mDraws;
    vk::Buffer mSplats;
    vk::Buffer mPoints;
    vk::BoundSet mBound;
    vk::ComputePass<shader::MultibouncePointsPush> mSample;
};

} // namespace bl
