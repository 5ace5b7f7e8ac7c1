#include "reference/ReferenceRenderer.h"

#include "base/Log.h"

#include <atomic>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace bl {

namespace {
// Bad samples kept with their coordinates for replay; beyond this only the count grows.
constexpr std::size_t kMaxRecordedBadSamples = 64;

Image linearTexture(const Texture& t) {
    Image img(t.image.width, t.image.height);
    for (std::size_t i = 0; i < img.pixelCount(); ++i) {
        for (int c = 0; c < 3; ++c) {
            img.pixels()[i][c] = srgbToLinear(t.image.texels[4 * i + c] / 255.0f);
        }
    }
    return img;
}
} // namespace

ReferenceRenderer::ReferenceRenderer(const Scene& scene, double time, const ReferenceSettings& settings)
    : mWidth(scene.camera.resolution.x), mHeight(scene.camera.resolution.y), mSettings(settings),
      mEnvironment(scene.environment, settings.environmentImportance) {
    for (const Texture& t : scene.textures) {
        mTextures.push_back(linearTexture(t));
    }
    mGeometry = std::make_unique<EmbreeScene>(scene, time);
    mLights = std::make_unique<LightSampler>(*mGeometry, mEnvironment, settings.emitterSampling);
    mTracer = std::make_unique<PathTracer>(*mGeometry, *mLights, mEnvironment, mTextures,
                                           makeGpuCamera(scene.camera, time, 1.0f), settings.path);
    const std::size_t n = static_cast<std::size_t>(mWidth) * mHeight;
    mCounts.assign(n, 0);
    for (int h = 0; h < 2; ++h) {
        mHalfSums[h].assign(n, glm::dvec3(0.0));
        mHalfCounts[h].assign(n, 0);
    }
    mLayerSums.assign(n, {});
}

ReferenceRenderer::~ReferenceRenderer() = default;

void ReferenceRenderer::renderPass(std::uint32_t sampleIndex, std::uint32_t seed) {
    std::atomic<std::uint64_t> rays{0}, bad{0};
    auto rows = [&](const tbb::blocked_range<int>& range) {
        std::uint64_t localRays = 0;
        for (int y = range.begin(); y != range.end(); ++y) {
            for (int x = 0; x < mWidth; ++x) {
                PathSample s = mTracer->trace(x, y, sampleIndex, seed);
                localRays += s.rays;
                const std::size_t i = static_cast<std::size_t>(y) * mWidth + x;
                if (!s.finite()) {
                    ++bad;
                    std::lock_guard lock(mBadMutex);
                    if (mBad.size() < kMaxRecordedBadSamples) {
                        mBad.push_back({x, y, sampleIndex});
                    }
                    continue;
                }
                mHalfSums[sampleIndex & 1u][i] += glm::dvec3(s.total());
                ++mHalfCounts[sampleIndex & 1u][i];
                for (int l = 0; l < kPathLayerCount; ++l) {
                    mLayerSums[i][l] += s.layers[l];
                }
                ++mCounts[i];
            }
        }
        rays += localRays;
    };
    if (mSettings.threads > 0) {
        tbb::task_arena arena(mSettings.threads);
        arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int>(0, mHeight, 1), rows); });
    } else {
        tbb::parallel_for(tbb::blocked_range<int>(0, mHeight, 1), rows);
    }
    mRays += rays;
    if (bad > 0) {
        mNonFinite += bad;
        std::string first;
        for (const BadSample& b : badSamples()) {
            if (b.sample == sampleIndex) {
                first = "; the first: pixel " + std::to_string(b.x) + " " + std::to_string(b.y) + " sample " +
                        std::to_string(b.sample) + ", replay with `bundlelab replay SCENE --pixel " + std::to_string(b.x) +
                        " " + std::to_string(b.y) + " --sample " + std::to_string(b.sample) + " --seed " +
                        std::to_string(seed) + "`";
                break;
            }
        }
        log::warn("reference: " + std::to_string(bad.load()) + " NaN/Inf samples in pass " + std::to_string(sampleIndex) +
                  " (not averaged in)" + first);
    }
    ++mSamples;
}

Image ReferenceRenderer::mean() const {
    Image img(mWidth, mHeight);
    for (std::size_t i = 0; i < img.pixelCount(); ++i) {
        img.pixels()[i] = mCounts[i] ? glm::vec3((mHalfSums[0][i] + mHalfSums[1][i]) / double(mCounts[i]))
                                     : glm::vec3(0.0f);
    }
    return img;
}

Image ReferenceRenderer::layer(int index) const {
    Image img(mWidth, mHeight);
    for (std::size_t i = 0; i < img.pixelCount(); ++i) {
        img.pixels()[i] = mCounts[i] ? mLayerSums[i][index] / float(mCounts[i]) : glm::vec3(0.0f);
    }
    return img;
}

Image ReferenceRenderer::varianceOfMean() const {
    Image img(mWidth, mHeight);
    for (std::size_t i = 0; i < img.pixelCount(); ++i) {
        if (mHalfCounts[0][i] == 0 || mHalfCounts[1][i] == 0) continue;
        glm::dvec3 d = mHalfSums[0][i] / double(mHalfCounts[0][i]) - mHalfSums[1][i] / double(mHalfCounts[1][i]);
        img.pixels()[i] = glm::vec3(0.25 * d * d);
    }
    return img;
}

Image ReferenceRenderer::halfMean(int half) const {
    Image img(mWidth, mHeight);
    for (std::size_t i = 0; i < img.pixelCount(); ++i) {
        if (mHalfCounts[half][i] > 0) img.pixels()[i] = glm::vec3(mHalfSums[half][i] / double(mHalfCounts[half][i]));
    }
    return img;
}

std::vector<BadSample> ReferenceRenderer::badSamples() const {
    std::lock_guard lock(mBadMutex);
    return mBad;
}

PathSample ReferenceRenderer::replay(int x, int y, std::uint32_t sampleIndex, std::uint32_t seed,
                                     std::vector<std::string>& log) const {
    return mTracer->trace(x, y, sampleIndex, seed, &log);
}

} // namespace bl
