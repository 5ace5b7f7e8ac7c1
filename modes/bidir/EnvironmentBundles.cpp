#include "modes/bidir/EnvironmentBundles.h"

#include <cstring>
#include <modes/bidir/BidirEnvironment.h>

namespace bl {

EnvironmentBundles::EnvironmentBundles(const vk::Context& ctx, const Scene& scene, std::uint32_t count, float offset)
    : mCount(scene.environment.present ? count : 0u), mOffset(offset) {
    mBuffer = vk::Buffer(ctx, sizeof(shader::BidirEnvironmentHeader) + sizeof(shader::BidirEnvironmentBundle) * std::max(mCount, 1u),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload);
    std::memset(mBuffer.data(), 0, sizeof(shader::BidirEnvironmentHeader));
    if (mCount > 0) {
        mEnvironment = std::make_unique<EnvironmentLight>(scene.environment, true);
    }
}

std::vector<shader::BundleFrame> EnvironmentBundles::frames(std::uint32_t frame, std::uint32_t seed, std::uint32_t firstSlot,
                                                            const std::vector<glm::vec3>& points, const Bounds& bounds,
                                                            std::uint32_t resolution) {
    std::vector<shader::BundleFrame> out(mCount);
    if (mCount > 0 && !mDirections) {
        // A stream of its own: the pairs' bundle directions use the run seed as is.
        mDirections = std::make_unique<DirectionSampler>(DirectionSequence::Importance, seed ^ 0x9e3779b9u, 256,
                                                         mEnvironment.get(), mOffset);
    }
    auto* header = static_cast<shader::BidirEnvironmentHeader*>(mBuffer.data());
    auto* bundles = reinterpret_cast<shader::BidirEnvironmentBundle*>(header + 1);
    header->firstSlot = firstSlot;
    header->count = mCount;
    for (std::uint32_t e = 0; e < mCount; ++e) {
        const BundleDirection dir = mDirections->sample(frame * mCount + e);
        out[e] = points.empty() ? bundleFrameForSphere(dir.omega, dir.rotation, bounds.center(), bounds.radius(), resolution)
                                : bundleFrameForPoints(dir.omega, dir.rotation, points, bounds.center(), bounds.radius(),
                                                       resolution);
        bundles[e].radianceForward = mEnvironment->radiance(dir.omega);
        bundles[e].radianceBackward = mEnvironment->radiance(-dir.omega);
        bundles[e].pdfForward = mDirections->hemispherePdf(dir.omega);
        bundles[e].pdfBackward = mDirections->hemispherePdf(-dir.omega);
    }
    return out;
}

} // namespace bl
