// Mode `raster`: the baseline every other mode adds to, and the test bed of core/vk and core/gpu.
//
// Implements, per pixel sample: L = L_e (front faces of emitters) + sum over point/spot lights of
//   f(x, wi, wo) I(-wi) (n.wi) / r^2 V(x),
// with V from omnidirectional shadow maps (cube faces, 4x4 PCF, receiver-plane depth test), and
// the environment's radiance for camera rays that escape. No indirect light, no light from the
// environment or emitters onto surfaces: those are the other modes' job.
//
// One iteration = one sample per pixel at a sub-pixel position (a Halton (2,3) sequence shifted by
// the seed: seed 0 starts at the pixel centre; core/sampling/PixelSamples.h), so iterating
// converges to the box-filtered pixel (CONVENTIONS.md).
//
// Parameters (`bundlelab modes`):
//   shadow_resolution  1024  texels   side of each shadow cube face
//   jitter             true           move the sample inside the pixel (false: pixel centres)
#pragma once

#include "gpu/CameraPass.h"
#include "gpu/ShadowCubePass.h"
#include "modes/Mode.h"

#include <memory>
#include <optional>

namespace bl {

class RasterMode final : public Mode {
public:
    static constexpr const char* kShadowResolution = "shadow_resolution";
    static constexpr const char* kJitter = "jitter";

    static std::vector<ParamSpec> parameters();
    static std::unique_ptr<Mode> create(const Settings& settings);

    explicit RasterMode(const Settings& settings);
    ~RasterMode() override;

    std::string_view name() const override { return "raster"; }
    void setScene(const Scene& scene, vk::Context* gpu) override;
    void iterate(const IterationInfo& info) override;
    ImageSet resolve() override;
    const Settings& settings() const override { return mSettings; }
    PassTimes timings() const override;
    std::vector<PlannedPass> plan(const Scene& scene) const override;
    TradeSettings trades() const override;

private:
    struct Gpu;
    Settings mSettings;
    const Scene* mScene = nullptr;
    vk::Context* mContext = nullptr;
    std::unique_ptr<Gpu> mGpu;
    std::uint32_t mIterations = 0;
};

} // namespace bl
