#include "gpu/EmitterPointPass.h"

#include <cstring>

namespace bl::gpu {

namespace {
// How far a point's shadow cube centre sits in front of its emitter, as a fraction of the scene's
// radius: ten times the cubes' near plane (lightClearance), so the emitter's own plane, edge-on
// from y itself, lies clearly behind the centre. The shaders light only receivers in front of the
// centre's plane (EmitterPointLight.glsl), which the cube's front parts hold (frontTexels).
constexpr float kLiftFraction = 1e-4f;
} // namespace

VkDeviceSize EmitterPointPass::bytesFor(std::uint32_t count, std::uint32_t resolution) {
    return ShadowCubePass::bytesFor(resolution, count) + sizeof(shader::GpuEmitterPointHeader) +
           count * sizeof(shader::GpuEmitterPoint);
}

EmitterPointPass::EmitterPointPass(const vk::Context& ctx, const GpuScene& gpuScene, const Scene& scene,
                                   std::uint32_t count, std::uint32_t resolution)
    : mSampler(scene), mRequested(mSampler.empty() ? 0u : count), mLift(kLiftFraction * gpuScene.radius()),
      // One tap per point (EmitterPointLight.glsl): no crease rule, so no normals.
      mCubes(ShadowCubePass::forPositions(ctx, gpuScene, resolution, mRequested, false)),
      mBuffer(ctx, sizeof(shader::GpuEmitterPointHeader) + sizeof(shader::GpuEmitterPoint) * std::max(mRequested, 1u),
              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload) {
    upload(); // a valid header (no points) until the first prepare()
}

void EmitterPointPass::prepare(std::uint64_t seed, std::uint32_t iteration, double time) {
    // Both halves of the run seed count: runs whose seeds differ only above bit 31 draw other points.
    const auto folded = static_cast<std::uint32_t>(seed ^ (seed >> 32));
    mPoints = mSampler.sample(mRequested, folded, iteration, time, mLift);
    upload();
}

void EmitterPointPass::upload() {
    shader::GpuEmitterPointHeader header{};
    header.count = count();
    header.resolution = resolution();
    header.inversePower = inversePower();
    auto* bytes = static_cast<std::byte*>(mBuffer.data());
    std::memcpy(bytes, &header, sizeof(header));
    if (!mPoints.empty()) {
        std::memcpy(bytes + sizeof(header), mPoints.data(), sizeof(shader::GpuEmitterPoint) * mPoints.size());
    }
}

void EmitterPointPass::record(VkCommandBuffer cmd, double time, vk::GpuTimer* timer) {
    if (mPoints.empty()) {
        return;
    }
    std::uint32_t scope = timer ? timer->start(cmd, "emitter points") : 0;
    for (std::uint32_t k = 0; k < mPoints.size(); ++k) {
        // A point lights only the side its emitter faces: each cube's faces behind it are cleared.
        mCubes.record(cmd, mPoints[k].cubeCentre, k, time, nullptr, mPoints[k].normal);
    }
    if (timer) {
        timer->stop(cmd, scope);
    }
}

} // namespace bl::gpu
