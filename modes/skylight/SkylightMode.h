// Mode `skylight`: direct light from the environment via global ray-bundles ([TO12] section 3 and
// Fig. 6; ambient occlusion is the special case of a constant white environment).
//
// One iteration = one bundle direction omega (Halton by default). Every camera-visible point x
// with normal n uses d = omega or -omega, whichever lies on n's side, and adds
//   V(x, d) L_e(d) f(x, d, w_o) (n.d) / p_r(d)
// where V comes from the bundle (a single rasterization answers it for all points, in both
// directions) and p_r(d) = q(d) + q(-d) (core/bundle/DirectionSampler.h). The estimate after N
// iterations is the mean; visible emitters and the environment behind the scene are added as in
// `raster`, so it converges to the reference's emitted + direct layers for environment-lit scenes.
//
// Parameters (`bundlelab modes`):
//   bundle_resolution  512       pixels per side of each bundle
//   directions         halton    halton, random, stratified, importance ([TO12] Eq. 2)
//   importance_offset  0.1       L_o as a fraction of the mean environment luminance
//   strata             1024      directions per stratified pass
//   fit                scene     bundle frame: the scene's bounding sphere or the visible points
//   rotate             true      random rotation of each frame about omega
//   memory_cap_mib     1024      bundle node pool limit (beyond: tiles)
//   visibility         bundle    bundle (omega and -omega for every point) or depth_map (a
//                                directional shadow map: omega only; the comparison of [TO12])
//   bundle_backend     auto      raster (graphics pipeline), compute (ComputeBundleRasterizer) or
//                                auto (compute on a CPU device with shaderInt64: on lavapipe its
//                                builds are 2.2-2.9x faster on Sponza and the bunny; experiments/
//                                bench/results/bundles-breakdown-lavapipe-2026-11-23.md; raster on
//                                GPUs: an H100 built Sponza 45-92x the floor with compute,
//                                experiments/gpu/README.md)
//   control_variate    off       on: each sample becomes (albedo/pi) E(n) + [V L_e f (n.d) -
//                                L_e (albedo/pi) (n.d)] / p(d) with E(n) the unoccluded irradiance
//                                tabulated once per map (IrradianceTable.h): same mean, and the
//                                bundles estimate only the light occluders remove
//   gbuffer_reuse      1         directions that share one jittered G-buffer (the camera pass
//                                is paid once per k directions; jitter and directions are
//                                independent, so the mean is unchanged, while the pixel
//                                footprint is integrated with k times fewer jitter samples)
#pragma once

#include "bundle/BundleBuilder.h"
#include "bundle/DirectionSampler.h"
#include "gpu/CameraPass.h"
#include "modes/Mode.h"
#include "modes/skylight/SkylightOptions.h"

#include <memory>

namespace bl {

class SkylightMode final : public Mode {
public:
    static constexpr const char* kBundleResolution = "bundle_resolution";
    static constexpr const char* kDirections = "directions";
    static constexpr const char* kImportanceOffset = "importance_offset";
    static constexpr const char* kStrata = "strata";
    static constexpr const char* kFit = "fit";
    static constexpr const char* kRotate = "rotate";
    static constexpr const char* kMemoryCap = "memory_cap_mib";
    static constexpr const char* kVisibility = "visibility";
    static constexpr const char* kControlVariate = "control_variate";
    static constexpr const char* kGlossyControl = "glossy_control_variate";
    static constexpr const char* kBundleBackend = "bundle_backend";
    static constexpr const char* kGBufferReuse = "gbuffer_reuse";

    static std::vector<ParamSpec> parameters();
    static std::unique_ptr<Mode> create(const Settings& settings);

    explicit SkylightMode(const Settings& settings);
    ~SkylightMode() override;

    std::string_view name() const override { return "skylight"; }
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
    SkylightOptions mOptions; // mSettings, typed, read once
    const Scene* mScene = nullptr;
    vk::Context* mContext = nullptr;
    std::unique_ptr<Gpu> mGpu;
    std::uint32_t mIterations = 0;
};

} // namespace bl
