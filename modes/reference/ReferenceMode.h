// Mode `reference`: the ground truth. CPU unidirectional path tracing on Embree 3 + TBB with
// next-event estimation and MIS (core/reference/PathTracer.h), the same BRDF code as the GPU modes
// (shaders/shared/Brdf.h), a box pixel filter. No Vulkan.
//
// One iteration = one sample per pixel. Outputs: the radiance, layers by path length (emitted,
// direct, indirect1, indirect2, rest) and the per-pixel variance of the mean ("variance").
//
// Parameters (`bundlelab modes`):
//   max_segments  64         at most this many path segments (1 emitters, 2 direct light, ...)
//   rr_depth      5          segments before Russian roulette
//   threads       0          worker threads (0: all hardware threads)
//   env_sampling  luminance  "luminance" or "uniform"
//   emitter_sampling area    "area" or "solid_angle" (Arvo's spherical triangles)
#pragma once

#include "modes/Mode.h"
#include "reference/ReferenceRenderer.h"

#include <chrono>
#include <memory>
#include <optional>

namespace bl {

class ReferenceMode final : public Mode {
public:
    static constexpr const char* kMaxSegments = "max_segments";
    static constexpr const char* kRrDepth = "rr_depth";
    static constexpr const char* kThreads = "threads";
    static constexpr const char* kEnvSampling = "env_sampling";
    static constexpr const char* kEmitterSampling = "emitter_sampling";

    static std::vector<ParamSpec> parameters();
    static std::unique_ptr<Mode> create(const Settings& settings);

    explicit ReferenceMode(const Settings& settings);
    ~ReferenceMode() override;

    std::string_view name() const override { return "reference"; }
    void setScene(const Scene& scene, vk::Context* gpu) override;
    void iterate(const IterationInfo& info) override;
    ImageSet resolve() override;
    const Settings& settings() const override { return mSettings; }
    PassTimes timings() const override { return mTimes; }
    PassPlan plan(const Scene& scene) const override;

    // Traces one sample alone, returning its radiance and a log of its path.
    PathSample replay(int x, int y, std::uint32_t sampleIndex, std::uint32_t seed, std::vector<std::string>& log);
    std::uint64_t rays() const { return mRenderer ? mRenderer->rays() : 0; }

private:
    ReferenceSettings rendererSettings() const;

    Settings mSettings;
    const Scene* mScene = nullptr;
    std::unique_ptr<ReferenceRenderer> mRenderer;
    std::optional<double> mTime;
    PassTimes mTimes;
};

} // namespace bl
