// The CPU reference renderer: one pass adds one sample to every pixel (TBB over rows), keeping
// the running mean of each path-length layer and a per-pixel variance of the mean. NaN/Inf
// samples are never averaged in: they are counted and recorded with pixel and sample index, and
// any sample can be replayed alone with a log of its path.
#pragma once

#include "reference/EmbreeScene.h"
#include "sampling/EnvironmentLight.h"
#include "reference/LightSampler.h"
#include "reference/PathTracer.h"

#include <memory>
#include <mutex>

namespace bl {

struct BadSample {
    int x;
    int y;
    std::uint32_t sample;
};

struct ReferenceSettings {
    PathTracerSettings path;
    int threads = 0;                   // 0: all hardware threads
    bool environmentImportance = true; // sample the environment by luminance (else uniformly)
    EmitterSampling emitterSampling = EmitterSampling::Area;
};

class ReferenceRenderer {
public:
    ReferenceRenderer(const Scene& scene, double time, const ReferenceSettings& settings);
    ~ReferenceRenderer();

    // Adds sample `sampleIndex` to every pixel.
    void renderPass(std::uint32_t sampleIndex, std::uint32_t seed);

    int width() const { return mWidth; }
    int height() const { return mHeight; }
    std::uint32_t samples() const { return mSamples; }
    std::uint64_t rays() const { return mRays; }
    Image mean() const;                  // the radiance estimate
    Image layer(int index) const;        // kPathLayerNames[index]
    // Per pixel and channel, (mean of even samples - mean of odd samples)^2 / 4: even and odd
    // samples are independently scrambled, so this is an unbiased (one-degree-of-freedom) estimate
    // of the variance of the mean, valid for quasi-random samples where the sample variance is not.
    Image varianceOfMean() const;
    // The mean of the even (half 0) or odd (half 1) samples alone: two independent estimates, from
    // which the variance of any difference of two renders' means can be estimated the same way.
    Image halfMean(int half) const;
    std::uint64_t nonFiniteSamples() const { return mNonFinite; }
    std::vector<BadSample> badSamples() const;

    PathSample replay(int x, int y, std::uint32_t sampleIndex, std::uint32_t seed, std::vector<std::string>& log) const;
    // The scene and the tracer as this renderer set them up (reference/TexelBaker.h traces from surfaces).
    const EmbreeScene& geometry() const { return *mGeometry; }
    const PathTracer& tracer() const { return *mTracer; }

private:
    int mWidth;
    int mHeight;
    ReferenceSettings mSettings;
    std::vector<Image> mTextures; // linear
    EnvironmentLight mEnvironment;
    std::unique_ptr<EmbreeScene> mGeometry;
    std::unique_ptr<LightSampler> mLights;
    std::unique_ptr<PathTracer> mTracer;

    std::uint32_t mSamples = 0;
    std::vector<std::uint32_t> mCounts;     // accepted samples per pixel
    std::vector<glm::dvec3> mHalfSums[2];   // total radiance of even and odd samples
    std::vector<std::uint32_t> mHalfCounts[2];
    std::vector<std::array<glm::vec3, kPathLayerCount>> mLayerSums;
    std::uint64_t mRays = 0;
    std::uint64_t mNonFinite = 0;
    mutable std::mutex mBadMutex;
    std::vector<BadSample> mBad;
};

} // namespace bl
