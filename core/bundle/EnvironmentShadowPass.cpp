#include "bundle/EnvironmentShadowPass.h"

#include "base/Error.h"
#include "bundle/BundleFrame.h"

#include <shared/Sampling.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace bl {

namespace {
// The directions' own sequence: its seed key (another than the modes' bundle directions), and L_o
// of the importance density as a fraction of the mean luminance (DirectionSampler): a small uniform
// share keeps a density wherever the bilinear map lights a direction its piecewise-constant
// luminance sampler would miss.
constexpr std::uint32_t kSeedKey = 0x1b873593u;
constexpr float kUniformOffset = 0.1f;
} // namespace

VkDeviceSize EnvironmentShadowPass::bytesFor(std::uint32_t count, std::uint32_t resolution) {
    return DepthMapPass::bytesFor(resolution, count) + sizeof(shader::GpuEnvironmentShadowHeader) +
           VkDeviceSize(count) * sizeof(shader::GpuEnvironmentShadow);
}

EnvironmentShadowPass::EnvironmentShadowPass(const vk::Context& ctx, const gpu::GpuScene& gpuScene, const Scene& scene,
                                             std::uint32_t count, std::uint32_t resolution)
    : mRequested(scene.environment.present ? count : 0u), mResolution(mRequested > 0 ? resolution : 1u),
      mBounds(scene.bounds()), mRadiance(scene.environment, false), mImportance(scene.environment, true),
      mMaps(ctx, gpuScene, mResolution, std::max(mRequested, 1u)),
      mBuffer(ctx, sizeof(shader::GpuEnvironmentShadowHeader) + sizeof(shader::GpuEnvironmentShadow) * std::max(mRequested, 1u),
              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload) {
    if (mRequested > 0) {
        // q~'s normalization: the integral of lum(L_e) over the sphere by the midpoint rule on a
        // latitude-longitude grid (any positive constant keeps the MIS weights a partition of
        // unity; this one makes q~ close to q).
        constexpr int kRows = 256, kColumns = 512;
        constexpr double kPi = 3.14159265358979323846;
        double integral = 0.0;
        for (int r = 0; r < kRows; ++r) {
            const double theta = kPi * (r + 0.5) / kRows;
            const double cell = (kPi / kRows) * (2.0 * kPi / kColumns) * std::sin(theta);
            for (int c = 0; c < kColumns; ++c) {
                const double phi = 2.0 * kPi * (c + 0.5) / kColumns;
                const glm::vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                                  float(std::sin(theta) * std::sin(phi)));
                integral += double(shader::blLuminance(mRadiance.radiance(d))) * cell;
            }
        }
        const double p = 1.0 / (1.0 + double(kUniformOffset));
        mLuminanceScale = integral > 0.0 ? float(p / integral) : 0.0f;
        mUniformDensity = float((integral > 0.0 ? 1.0 - p : 1.0) / (4.0 * kPi));
    }
    upload(); // a valid header (no directions) until the first prepare()
}

void EnvironmentShadowPass::prepare(std::uint64_t seed, std::uint32_t iteration) {
    if (off()) {
        return;
    }
    const auto folded = static_cast<std::uint32_t>(seed ^ (seed >> 32)) ^ kSeedKey;
    if (!mDirections || folded != mSeed) {
        mSeed = folded;
        mDirections = std::make_unique<DirectionSampler>(DirectionSequence::Importance, folded, 256, &mImportance,
                                                         kUniformOffset);
    }
    mShadows.clear();
    for (std::uint32_t k = 0; k < mRequested; ++k) {
        const BundleDirection dir = mDirections->sample(iteration * mRequested + k);
        const float pdf = mDirections->pdf(dir.omega);
        const glm::vec3 radiance = mRadiance.radiance(dir.omega);
        if (!(pdf > 0.0f) || radiance == glm::vec3(0.0f)) {
            continue; // adds nothing: neither its map nor its entry is needed
        }
        shader::GpuEnvironmentShadow s{};
        s.frame = bundleFrameForSphere(dir.omega, dir.rotation, mBounds.center(), mBounds.radius(), mResolution);
        s.weight = radiance / (pdf * float(mRequested));
        s.pdf = pdf;
        mShadows.push_back(s);
    }
    upload();
}

void EnvironmentShadowPass::upload() {
    shader::GpuEnvironmentShadowHeader header{};
    header.count = count();
    header.requested = mRequested;
    header.luminanceScale = mLuminanceScale;
    header.uniformDensity = mUniformDensity;
    auto* bytes = static_cast<std::byte*>(mBuffer.data());
    std::memcpy(bytes, &header, sizeof(header));
    if (!mShadows.empty()) {
        std::memcpy(bytes + sizeof(header), mShadows.data(), mShadows.size() * sizeof(shader::GpuEnvironmentShadow));
    }
}

void EnvironmentShadowPass::record(VkCommandBuffer cmd, double time, vk::GpuTimer* timer) {
    if (mShadows.empty()) {
        return;
    }
    const std::uint32_t scope = timer ? timer->start(cmd, "environment maps") : 0;
    for (std::uint32_t k = 0; k < count(); ++k) {
        mMaps.record(cmd, mShadows[k].frame, time, nullptr, k);
    }
    if (timer) {
        timer->stop(cmd, scope);
    }
}

} // namespace bl
