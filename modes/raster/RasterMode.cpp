#include "modes/raster/RasterMode.h"

#include "base/Error.h"
#include "modes/EmitterPointParameters.h"
#include "modes/EnvironmentShadowParameters.h"
#include "bundle/EnvironmentShadowPass.h"
#include "modes/LightShadowPass.h"
#include "sampling/PixelSamples.h"
#include "scene/Scene.h"
#include "vk/BoundSet.h"
#include "vk/Commands.h"
#include "vk/ComputePass.h"
#include "vk/Descriptors.h"

#include <cmath>
#include <cstring>
#include <modes/raster/RasterShared.h>
#include <modes/raster/shade.comp.spv.h>
#include <shared/Bindings.h>

namespace bl {

std::vector<ParamSpec> RasterMode::parameters() {
    std::vector<ParamSpec> params{
        {kShadowResolution, std::int64_t{1024}, "texels",
         "side of each shadow cube face ([TO12] used 1024^2 per face for direct light)", 16, 8192, {}},
        {kJitter, true, "", "move the sample inside the pixel (box filter; seed 0 starts at the centre, other seeds shift the sequence)", 0, 1, {}},
    };
    params = withEmitterPointParameters(std::move(params), "iteration",
                                        "direct light from area emitters (0: area lights left out)", 0);
    return withEnvironmentShadowParameters(std::move(params), "iteration",
                                           "direct light from the environment (0: the environment seen only, lighting "
                                           "nothing)");
}

std::unique_ptr<Mode> RasterMode::create(const Settings& settings) {
    return std::make_unique<RasterMode>(settings);
}

RasterMode::RasterMode(const Settings& settings) : mSettings(settings), mOptions(rasterOptions(settings)) {}

struct RasterMode::Gpu {
    std::unique_ptr<gpu::GpuScene> scene;
    std::unique_ptr<gpu::CameraPass> camera;
    std::unique_ptr<gpu::ShadowCubePass> shadows;
    std::unique_ptr<gpu::EmitterPointPass> emitterPoints;
    std::unique_ptr<EnvironmentShadowPass> environmentShadows; // off (placeholders) unless the plan runs it
    vk::BoundSet bound;
    vk::ComputePass<shader::RasterPush> shade;
    vk::GpuTimer timer;
};

RasterMode::~RasterMode() = default;

PassPlan RasterMode::plan(const Scene& scene) const {
    SceneFeatures f = scene.features();
    PassPlan p;
    const bool lights = f.shadowCastingLights() > 0;
    p.add(lightShadowCubesPass(f, "", "iteration"));
    p.add("gbuffer", "gbuffer", true, "always", std::to_string(f.triangles) + " triangles");
    const std::uint32_t points = mOptions.emitterPoints;
    const bool areaLight = f.emissiveMeshes && points > 0;
    if (f.emissiveMeshes && !areaLight) {
        // Raster is direct light from point and spot lights and (emitter points) area emitters.
        p.add(kPassEmitterPoints, "area light", false, "emitter-points-0", "emitter_points = 0 leaves the area emitters out",
              true);
    } else {
        p.add(kPassEmitterPoints, "emitter points", areaLight, areaLight ? "area-emitters" : "no-area-emitters",
              areaLight ? std::to_string(points) + " point(s) on the emitters per iteration, by power, x 6 faces of " +
                              std::to_string(mOptions.emitterShadowResolution) + "^2"
                        : "no emissive mesh");
    }
    std::string shading = lights ? "direct light" : "";
    auto add = [&shading](const std::string& s) { shading += (shading.empty() ? "" : ", ") + s; };
    if (f.emissiveMeshes) add("visible emitters");
    if (areaLight) add("direct light from the emitters");
    const std::uint32_t shots = mOptions.environmentShots;
    const bool environmentLight = f.environment && shots > 0;
    // Warned when left out: the image then lacks light the scene has.
    p.add(kPassEnvironmentShadows, "environment light", environmentLight,
          !f.environment ? "no-environment" : environmentLight ? "environment" : "environment-shots-0",
          !f.environment     ? "no environment"
          : environmentLight ? std::to_string(shots) + " direction(s) toward the environment per iteration, by its "
                                                       "importance, a " +
                                   std::to_string(mOptions.environmentShadowResolution) + "^2 depth map each"
                             : "environment_shots = 0: the environment is seen but lights nothing",
          f.environment && !environmentLight);
    if (environmentLight) add("direct light from the environment");
    if (f.environment) add("environment behind geometry");
    p.add("shade", "shade", true, shading.empty() ? "unlit" : "lit",
          shading.empty() ? "nothing lights the scene: black" : shading);
    return p;
}

void RasterMode::setScene(const Scene& scene, vk::Context* ctx) {
    mContext = &requireDevice(ctx, "raster");
    mScene = &scene;
    mIterations = 0;
    mPlan = plan(scene);
    VkDevice device = ctx->device();
    const auto width = static_cast<std::uint32_t>(scene.camera.resolution.x);
    const auto height = static_cast<std::uint32_t>(scene.camera.resolution.y);

    // G-buffer, accumulation, shadow cubes + their depth.
    const VkDeviceSize pixels = VkDeviceSize(width) * height;
    const VkDeviceSize lights = scene.lights.size();
    const std::uint32_t points = mOptions.emitterPoints;
    const std::uint32_t pointSide = mOptions.emitterShadowResolution;
    ctx->requireDeviceMemory(pixels * gpu::CameraPass::bytesPerPixel(shader::kRasterAccumLayers) +
                                 gpu::ShadowCubePass::bytesFor(mOptions.shadowResolution, lights) +
                                 (mPlan.runs(kPassEmitterPoints) ? gpu::EmitterPointPass::bytesFor(points, pointSide) : 0) +
                                 (mPlan.runs(kPassEnvironmentShadows)
                                      ? EnvironmentShadowPass::bytesFor(mOptions.environmentShots,
                                                                        mOptions.environmentShadowResolution)
                                      : 0),
                             "raster at " + std::to_string(width) + "x" + std::to_string(height));

    auto g = std::make_unique<Gpu>();
    g->scene = std::make_unique<gpu::GpuScene>(*ctx, scene);
    g->camera = std::make_unique<gpu::CameraPass>(*ctx, *g->scene, width, height, shader::kRasterAccumLayers);
    g->shadows = std::make_unique<gpu::ShadowCubePass>(*ctx, *g->scene, mOptions.shadowResolution);
    g->emitterPoints = std::make_unique<gpu::EmitterPointPass>(*ctx, *g->scene, scene,
                                                               mPlan.runs(kPassEmitterPoints) ? points : 0u, pointSide);
    g->environmentShadows = std::make_unique<EnvironmentShadowPass>(
        *ctx, *g->scene, scene, mPlan.runs(kPassEnvironmentShadows) ? mOptions.environmentShots : 0u,
        mOptions.environmentShadowResolution);
    g->timer = vk::GpuTimer(*ctx);

    g->bound = vk::BoundSet(
        device, {vk::Bound::storageBuffer(shader::kRasterBindingLights, g->scene->lightBuffer()),
                 vk::Bound::storageImage(shader::kRasterBindingShadowMaps, g->shadows->maps().view()),
                 vk::Bound::storageBuffer(shader::kRasterBindingEmitterPoints, g->emitterPoints->buffer()),
                 vk::Bound::storageImage(shader::kRasterBindingEmitterShadowMaps, g->emitterPoints->maps().view()),
                 vk::Bound::storageBuffer(shader::kRasterBindingEnvironmentShadows, g->environmentShadows->buffer()),
                 vk::Bound::storageImage(shader::kRasterBindingEnvironmentShadowMaps,
                                         g->environmentShadows->maps().view())});
    std::vector<std::uint32_t> specialization(shader::kRasterSpecCount);
    specialization[shader::kRasterSpecPointLights] = scene.lights.empty() ? 0u : 1u;
    specialization[shader::kRasterSpecEmitterPoints] = mPlan.runs(kPassEmitterPoints) ? 1u : 0u;
    specialization[shader::kRasterSpecEnvironment] = mPlan.runs(kPassEnvironmentShadows) ? 1u : 0u;
    g->shade = vk::ComputePass<shader::RasterPush>(device, kSpv_modes_raster_shade_comp,
                                                   {g->camera->setLayout(), g->bound.layout()}, specialization);
    mGpu = std::move(g);
}

void RasterMode::iterate(const IterationInfo& info) {
    Gpu& g = sceneState(mGpu, name(), "iterate");
    const std::uint32_t width = g.camera->width();
    const std::uint32_t height = g.camera->height();
    const gpu::CameraSample sample = g.camera->sample(mIterations, mOptions.jitter, info.time, info.seed);
    const bool renderShadows = mPlan.runs(kPassLightShadowCubes) && g.shadows->refreshFor(*mContext, *g.scene, info.time);
    g.emitterPoints->prepare(info.seed, mIterations, info.time);
    g.environmentShadows->prepare(info.seed, mIterations);

    mContext->submitAndWait([&](VkCommandBuffer cmd) {
        g.timer.begin(cmd);
        if (renderShadows) {
            g.shadows->record(cmd, info.time, &g.timer);
        }
        g.emitterPoints->record(cmd, info.time, &g.timer);
        g.environmentShadows->record(cmd, info.time, &g.timer);
        g.camera->record(cmd, sample, &g.timer);

        shader::RasterPush push{};
        push.lightCount = g.shadows->lightCount();
        push.shadowResolution = g.shadows->resolution();
        push.environmentPresent = g.scene->environmentPresent() ? 1u : 0u;
        push.environmentRotation = g.scene->environmentRotation();
        push.samplePosition = sample.samplePosition;
        push.width = width;
        push.height = height;
        const VkDescriptorSet sets[] = {g.camera->set(), g.bound.set()};
        g.timer.timed(cmd, "shade", [&] {
            g.shade.dispatch(cmd, push, vk::groupCount(width, height, shader::kRasterGroupSize), sets);
        });
        vk::computeToHost(cmd);
    });
    g.timer.collect();
    ++mIterations;
}

ImageSet RasterMode::resolve() {
    Gpu& g = sceneState(mGpu, name(), "resolve");
    const int width = static_cast<int>(g.camera->width());
    const int height = static_cast<int>(g.camera->height());
    ImageSet out;
    out.iterations = mIterations;
    // Every iteration adds one sample to every pixel: emitted + direct, and their variance.
    gpu::AccumulatedImages estimate = g.camera->accumulator().resolve(*mContext, mIterations);
    out.layers = std::move(estimate.layers);
    addSampleLosses(out, estimate.nonFiniteSamples, estimate.droppedSamples, estimate.expectedSamples);

    // AOVs of the last iteration's G-buffer, for inspection and later denoisers.
    auto aov = [&](std::uint32_t attachment, const char* name) {
        std::vector<std::byte> raw = g.camera->gbuffer().attachment(attachment).download(*mContext, VK_IMAGE_LAYOUT_GENERAL);
        const auto* texels = reinterpret_cast<const glm::vec4*>(raw.data());
        Image image(width, height);
        for (std::size_t i = 0; i < image.pixelCount(); ++i) {
            image.pixels()[i] = glm::vec3(texels[i]);
        }
        out.layers.emplace_back(name, std::move(image));
    };
    if (mIterations > 0) {
        aov(shader::kGBufferAlbedo, "albedo");
        aov(shader::kGBufferNormal, "normal");
    }
    return out;
}

PassTimes RasterMode::timings() const { return mGpu ? mGpu->timer.totals() : PassTimes{}; }

TradeSettings RasterMode::trades() const {
    // The environment directions' depth maps (over the scene's bounding sphere) are checked as
    // skylight's bundles are, at their resolution, with the depth maps' rule.
    const bool environmentMaps = mSettings.getInt(kEnvironmentShotsKey) > 0;
    TradeSettings t = tradeSettingsOf(mSettings, kShadowResolution, environmentMaps ? kEnvironmentShadowResolutionKey : "");
    t.bundlesOnlyForEnvironment = true;
    t.bundleWhat = "environment depth maps";
    t.bundleRule = BundleRule::DepthMapNearestLight;
    t.wholeSceneWhy = "raster frames its maps over the scene's bounding sphere and has no fit setting yet";
    return t;
}

} // namespace bl
