// The compute bundle backend (`bundle_backend = compute`): the triangles of a scene rasterized
// into a BundlePool slot by compute shaders instead of the graphics pipeline, for devices whose
// fixed-function rasterization is small or slow (issue 14). Same contract as
// BundlePool::recordBuild: after recordReset, any number of builds into any slots; the nodes are
// those of the rasterized exact build (pixel centres inside the snapped triangle, exact plane
// depth and face: shaders/bundle/compute_triangles.comp.glsl); a pool that runs out counts what it
// could not store (status()), and the caller grows it and builds again.
//
// Scope: triangles, with or without the hit payload (the same hits as the rasterized exact build:
// shaders/bundle/PoolHit.glsl). Point splats stay with the rasterized build. Needs shaderInt64
// (exact edge functions).
// One invocation per triangle; a triangle whose box holds more than kBundleComputeBandPixels pixels
// is walked by one invocation per band of rows instead (an indirect dispatch).
#pragma once

#include "bundle/BundlePool.h"

#include <bundle/ComputeBuildShared.h>

namespace bl {

class ComputeBundleRasterizer {
public:
    ComputeBundleRasterizer(const vk::Context& ctx, const gpu::GpuScene& scene);

    // True when the device can run it (shaderInt64).
    static bool supported(const vk::Context& ctx);

    void record(VkCommandBuffer cmd, const BundlePool& pool, std::uint32_t slot, const shader::BundleFrame& frame,
                double time, vk::GpuTimer* timer = nullptr) const;

private:
    const vk::Context* mContext;
    const gpu::GpuScene* mScene;
    vk::BoundSet mTriangleSet;
    vk::Buffer mBig; // BundleComputeBigHeader + one uint per triangle of the largest draw
    vk::ComputePass<shader::BundleComputeClearPush> mClear;
    vk::ComputePass<shader::BundleComputePush> mTriangles;
};

} // namespace bl
