// Mode `raster`: the baseline every other mode adds to, and the test bed of core/vk and core/gpu.
//
// Implements, per pixel sample: L = L_e (front faces of emitters) + sum over point/spot lights of
//   f(x, wi, wo) I(-wi) (n.wi) / r^2 V(x),
// with V from omnidirectional shadow maps (cube faces, 4x4 PCF, receiver-plane depth test),
// + direct light from area emitters by next-event estimation: `emitter_points` points y_k drawn on
// the emitters by power each iteration, each shadowed by its own cube (gpu/EmitterPointPass.h,
// shared/EmitterPoints.h: 1/M sum_k f L_e(y_k) cos_x cos_y V / (r^2 p_A(y_k))), so the average over
// iterations converges to the emitters' direct light,
// + direct light from the environment by next-event estimation: `environment_shots` directions
// drawn by its importance each iteration, each shadowed by an orthographic depth map
// (bundle/EnvironmentShadowPass.h, shared/EnvironmentShadows.h),
// + the environment's radiance for camera rays that escape. No indirect light: that is the other
// modes' job.
//
// One iteration = one sample per pixel at a sub-pixel position (a Halton (2,3) sequence shifted by
// the seed: seed 0 starts at the pixel centre; core/sampling/PixelSamples.h), so iterating
// converges to the box-filtered pixel (CONVENTIONS.md).
//
// Parameters (`bundlelab modes`):
//   shadow_resolution  1024  texels   side of each shadow cube face
//   emitter_points     4     points   on the area emitters per iteration (0: area lights left out)
//   emitter_shadow_resolution 256 texels side of each emitter point's shadow cube face
//   environment_shots  4     directions toward the environment per iteration (0: it lights nothing)
//   environment_shadow_resolution 512 texels side of each direction's depth map
//   jitter             true           move the sample inside the pixel (false: pixel centres)
#pragma once

#include "gpu/CameraPass.h"
#include "gpu/EmitterPointPass.h"
#include "gpu/ShadowCubePass.h"
#include "modes/Mode.h"
#include "modes/raster/RasterOptions.h"

#include <memory>
#include <optional>

namespace bl {

class RasterMode final : public Mode {
public:
    static constexpr const char* kShadowResolution = "shadow_resolution";
    static constexpr const char* kJitter = "jitter";
    static constexpr const char* kEmitterPoints = "emitter_points";
    static constexpr const char* kEmitterShadowResolution = "emitter_shadow_resolution";

    // The ids of the plan's passes that setScene() and iterate() execute.
    static constexpr const char* kPassEmitterPoints = "emitter-points";
    static constexpr const char* kPassEnvironmentShadows = "environment-light";

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
    PassPlan plan(const Scene& scene) const override;
    TradeSettings trades() const override;

private:
    struct Gpu;
    Settings mSettings;
    RasterOptions mOptions; // mSettings, typed, read once
    PassPlan mPlan;         // plan(scene) of the scene given to setScene: what iterate() runs
    const Scene* mScene = nullptr;
    vk::Context* mContext = nullptr;
    std::unique_ptr<Gpu> mGpu;
    std::uint32_t mIterations = 0;
};

} // namespace bl
