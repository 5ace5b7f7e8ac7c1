// Unidirectional path tracing with next-event estimation and multiple importance sampling (power
// heuristic) for emissive triangles and the environment; point and spot lights by NEE only (delta
// lights); Russian roulette after `rrDepth` segments; at most `maxSegments` path segments
// (1 = emitters seen directly, 2 = direct light: the convention of ../shared/references).
//
// One sample of pixel (x, y) is a pure function of (seed, pixel, sample index): the same on any
// thread count, and replayable alone with a log of its path.
#pragma once

#include "image/Image.h"
#include "reference/EmbreeScene.h"
#include "reference/LightSampler.h"

#include <array>
#include <shared/GpuTypes.h>
#include <shared/Random.h>
#include <string>
#include <vector>

namespace bl {

struct PathTracerSettings {
    int maxSegments = 64;
    int rrDepth = 5;
};

// Radiance split by path length: emitted (1 segment), direct (2), indirect1 (3), indirect2 (4),
// rest (5 and more). Their sum is the pixel's radiance.
inline constexpr int kPathLayerCount = 5;
inline constexpr const char* kPathLayerNames[kPathLayerCount] = {"emitted", "direct", "indirect1", "indirect2",
                                                                 "rest"};

struct PathSample {
    std::array<glm::vec3, kPathLayerCount> layers{};
    std::uint32_t rays = 0; // closest-hit and shadow rays traced
    glm::vec3 total() const;
    bool finite() const;
};

class PathTracer {
public:
    PathTracer(const EmbreeScene& geometry, const LightSampler& lights, const EnvironmentLight& environment,
               const std::vector<Image>& linearTextures, const shader::GpuCamera& camera, PathTracerSettings settings);

    // `log`, when given, receives one line per event of the path (for replaying a bad sample).
    PathSample trace(int x, int y, std::uint32_t sampleIndex, std::uint32_t seed,
                     std::vector<std::string>* log = nullptr) const;
    // One sample of the radiance leaving surface point `at` on its front (`back` false) or back side
    // along that side's geometric normal: a path whose first vertex is `at`, as if a camera ray had
    // arrived there along the normal (layer 0 holds what the side emits, the rest what it reflects;
    // for a diffuse surface the direction does not matter). `index` plays the pixel's part in the
    // random stream (reference/TexelBaker.h: the texel).
    PathSample traceLeaving(const SurfaceHit& at, bool back, std::uint32_t index, std::uint32_t sampleIndex,
                            std::uint32_t seed) const;

private:
    // The path from `origin` along `direction` (a camera ray), its first hit `first` when given.
    PathSample tracePath(glm::vec3 origin, glm::vec3 direction, shader::RandomStream& rng, const SurfaceHit* first,
                         std::vector<std::string>* log) const;
    glm::vec3 albedoAt(const Material& m, glm::vec2 uv) const;

    const EmbreeScene* mGeometry;
    const LightSampler* mLights;
    const EnvironmentLight* mEnvironment;
    const std::vector<Image>* mTextures;
    shader::GpuCamera mCamera;
    PathTracerSettings mSettings;
    std::vector<shader::GpuMaterial> mMaterials;
    std::vector<shader::GpuLight> mDeltaLights;
};

} // namespace bl
