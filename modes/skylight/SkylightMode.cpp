#include "modes/skylight/SkylightMode.h"

#include "base/Error.h"
#include "bundle/BundleFrame.h"
#include "bundle/BundlePool.h"
#include "bundle/DepthMapPass.h"
#include "modes/skylight/IrradianceTable.h"
#include "scene/Scene.h"
#include "vk/BoundSet.h"
#include "vk/Commands.h"
#include "vk/ComputePass.h"

#include <cstring>
#include <modes/skylight/SkylightShared.h>
#include <modes/skylight/visibility.comp.spv.h>
#include <optional>
#include <shared/Bindings.h>

namespace bl {

namespace {

glm::uvec2 split(VkDeviceAddress a) {
    return {static_cast<std::uint32_t>(a & 0xffffffffu), static_cast<std::uint32_t>(a >> 32)};
}
} // namespace

std::vector<ParamSpec> SkylightMode::parameters() {
    return {
        {kBundleResolution, std::int64_t{512}, "pixels", "side of each bundle ([TO12] used 256^2 to 1024^2)", 16, 8192, {}},
        {kDirections, std::string("halton"), "", "bundle direction sequence (Hermes et al.: Halton covers best)", 0, 0,
         {"halton", "random", "stratified", "importance"}},
        {kImportanceOffset, 0.1, "", "L_o of [TO12] Eq. 2, as a fraction of the mean environment luminance", 0.0, 1e6, {}},
        {kStrata, std::int64_t{1024}, "directions", "directions per pass of the stratified sequence", 1, 1 << 24, {}},
        {kFit, std::string("scene"), "", "bundle frame around the scene's bounding sphere or the visible points", 0, 0,
         {"scene", "visible"}},
        {kRotate, true, "", "rotate each bundle frame randomly about its direction (decorrelates aliasing)", 0, 1, {}},
        {kMemoryCap, std::int64_t{1024}, "MiB", "bundle node pool limit; beyond it bundles are built in tiles", 1,
         1 << 20, {}},
        {kVisibility, std::string("bundle"), "",
         "bundle: omega and -omega for every point; depth_map: a directional shadow map, omega only", 0, 0,
         {"bundle", "depth_map"}},
        {kBundleBackend, std::string("auto"), "",
         "who builds the bundles: the graphics pipeline, compute shaders, or auto (compute on a CPU device with "
         "shaderInt64: 2.2-2.9x faster builds than raster on lavapipe for Sponza and the bunny at 512^2-2048^2; "
         "raster on GPUs: on an H100 compute was 45-92x the floor on Sponza's large triangles, raster 2.1-4.2x)",
         0, 0, {"raster", "compute", "auto"}},
        {kControlVariate, std::string("off"), "",
         "on: add the tabulated unoccluded Lambert irradiance and let bundles estimate only what occluders remove",
         0, 0, {"off", "on"}},
        {kGlossyControl, std::string("on"), "",
         "on: glossy lobes' unoccluded light from one lobe-sampled environment lookup per pixel and direction, the "
         "bundles estimating only what occluders remove from it (a sharp lobe is met every direction, not once in "
         "e + 1); off: lobes met through the bundle directions alone",
         0, 0, {"on", "off"}},
        {kGBufferReuse, std::int64_t{1}, "directions",
         "directions that share one jittered G-buffer (the camera pass paid once per k; same mean, the pixel "
         "footprint integrated with k times fewer jitter samples)",
         1, 4096, {}},
    };
}

std::unique_ptr<Mode> SkylightMode::create(const Settings& settings) { return std::make_unique<SkylightMode>(settings); }

SkylightMode::SkylightMode(const Settings& settings) : mSettings(settings), mOptions(skylightOptions(settings)) {}

struct SkylightMode::Gpu {
    std::unique_ptr<gpu::GpuScene> scene;
    std::unique_ptr<gpu::CameraPass> camera;
    const gpu::GBufferPass* gbuffer = nullptr; // the camera pass's
    std::unique_ptr<BundleBuilder> builder;
    std::unique_ptr<DepthMapPass> depthMap; // visibility = depth_map
    vk::GpuImage placeholder;               // rgba32f 1x1 bound as the depth map otherwise
    std::unique_ptr<EnvironmentLight> environment;
    std::unique_ptr<DirectionSampler> directions;
    vk::Buffer irradiance; // control_variate = on: IrradianceTable entries
    vk::Buffer frame;
    vk::BoundSet bound;
    vk::ComputePass<shader::SkylightPush> visibility;
    vk::GpuTimer timer;
    std::vector<glm::vec3> visiblePoints; // for fit = visible: this iteration's
    std::optional<gpu::CameraSample> gbufferSample; // what the G-buffer holds now (gbuffer_reuse)
    Bounds bounds;                        // the scene's, over all keyframes: computed once
    PassTimes builds;                     // bundle build ms (from the builder's timer)
    BundleStats lastStats;
};

SkylightMode::~SkylightMode() = default;

PassPlan SkylightMode::plan(const Scene& scene) const {
    SceneFeatures f = scene.features();
    PassPlan p;
    p.add("gbuffer", "gbuffer", true, "always", std::to_string(f.triangles) + " triangles, jittered every iteration");
    const bool env = f.environment;
    // Without an environment every sample is zero; the bundles are still built (the visibility pass
    // accumulates the emitted light and the sample counts), and the plan says so.
    p.add("bundles", "bundle build", true, env ? "environment" : "no-environment",
          env ? std::to_string(mOptions.bundleResolution) + "^2 bundle of every triangle per direction"
              : std::to_string(mOptions.bundleResolution) + "^2 bundle per direction, though no environment lights "
                                                            "anything: the image is the emitted light alone");
    p.add("visibility", "visibility", true, env ? "environment" : "no-environment",
          env ? "one list walk per visible point per direction" : "no environment: every sample is zero");
    if (f.shadowCastingLights() || f.emissiveMeshes) {
        p.add("other-lights", "point/spot/area light", false, "not-skylights-job",
              "not skylight's job: use reference, raster or bidir", true);
    }
    return p;
}

void SkylightMode::setScene(const Scene& scene, vk::Context* ctx) {
    mContext = &requireDevice(ctx, "skylight");
    mScene = &scene;
    mIterations = 0;
    const auto width = static_cast<std::uint32_t>(scene.camera.resolution.x);
    const auto height = static_cast<std::uint32_t>(scene.camera.resolution.y);
    ctx->requireDeviceMemory(VkDeviceSize(width) * height * gpu::CameraPass::bytesPerPixel(shader::kSkylightAccumLayers),
                             "skylight at " + std::to_string(width) + "x" + std::to_string(height));
    auto g = std::make_unique<Gpu>();
    g->scene = std::make_unique<gpu::GpuScene>(*ctx, scene);
    g->camera = std::make_unique<gpu::CameraPass>(*ctx, *g->scene, width, height, shader::kSkylightAccumLayers);
    g->gbuffer = &g->camera->gbuffer();
    BundleBuilderOptions options;
    options.memoryCapBytes = mOptions.memoryCapBytes;
    options.backend = chooseBundleBackend(*ctx, mOptions.bundleBackend);
    // The walk places each fragment by its facet's plane (visibility.comp.glsl).
    options.payload = BundlePayload::Hit;
    g->builder = std::make_unique<BundleBuilder>(*ctx, *g->scene, options);
    const bool depthMapVisibility = mOptions.depthMapVisibility;
    if (depthMapVisibility) {
        ctx->requireDeviceMemory(DepthMapPass::bytesFor(mOptions.bundleResolution, 0),
                                 "skylight's depth map at " + std::to_string(mOptions.bundleResolution) + "^2");
        g->depthMap = std::make_unique<DepthMapPass>(*ctx, *g->scene, mOptions.bundleResolution);
    } else {
        g->placeholder = vk::GpuImage(*ctx, {1, 1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
    }
    g->environment = std::make_unique<EnvironmentLight>(scene.environment, true);
    if (mOptions.controlVariate) {
        const IrradianceTable table(scene.environment);
        g->irradiance = vk::makeBuffer(*ctx, std::span<const glm::vec4>(table.entries()),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
    }
    g->bounds = scene.bounds();
    const DirectionSequence sequence = mOptions.directions;
    if (sequence == DirectionSequence::Importance && !scene.environment.present) {
        throw Error("skylight: directions=importance needs an environment in the scene");
    }
    g->frame = vk::Buffer(*ctx, sizeof(shader::BundleFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUse::Upload);
    g->timer = vk::GpuTimer(*ctx);

    VkDevice device = ctx->device();
    g->bound = vk::BoundSet(
        device, {vk::Bound::uniformBuffer(shader::kSkylightBindingFrame, g->frame.get()),
                 vk::Bound::storageImage(shader::kSkylightBindingDepthMap,
                                         depthMapVisibility ? g->depthMap->map().view() : g->placeholder.view())});
    g->visibility = vk::ComputePass<shader::SkylightPush>(device, kSpv_modes_skylight_visibility_comp,
                                                          {g->camera->setLayout(), g->bound.layout()});

    if (g->placeholder.get()) {
        ctx->submitAndWait([&](VkCommandBuffer cmd) { vk::transitionImage(cmd, g->placeholder.get(), vk::ImageTransition{}); });
    }
    mGpu = std::move(g);

    // The seed only decorrelates runs; directions are reproducible from (settings, seed).
    mGpu->directions.reset();
}

void SkylightMode::iterate(const IterationInfo& info) {
    Gpu& g = sceneState(mGpu, name(), "iterate");
    if (!g.directions) {
        g.directions = std::make_unique<DirectionSampler>(mOptions.directions, static_cast<std::uint32_t>(info.seed),
                                                          mOptions.strata, g.environment.get(),
                                                          static_cast<float>(mOptions.importanceOffset));
    }
    const std::uint32_t width = g.camera->width(), height = g.camera->height();
    // A new jittered G-buffer every gbuffer_reuse directions, and whenever the scene's time moved.
    const std::uint32_t reuse = mOptions.gbufferReuse;
    const bool freshGBuffer = !g.gbufferSample || mIterations % reuse == 0 || g.gbufferSample->time != info.time;
    // The G-buffer in a submission of its own only where the host needs it before the bundle
    // (fit = visible reads its points) or a depth map follows; else it is recorded with the bundle's
    // build and visibility pass (one submit and wait per direction; a frame split into tiles renders
    // it again with each tile).
    const bool gbufferWithBundle = freshGBuffer && !mOptions.fitVisible && !g.depthMap;
    if (freshGBuffer) {
        g.gbufferSample = g.camera->sample(mIterations / reuse, true, info.time, info.seed);
    }
    if (freshGBuffer && !gbufferWithBundle) {
        mContext->submitAndWait([&](VkCommandBuffer cmd) {
            g.timer.begin(cmd);
            g.camera->record(cmd, *g.gbufferSample, &g.timer);
        });
        g.timer.collect();
    }
    const gpu::CameraSample& sample = *g.gbufferSample;

    const BundleDirection dir = g.directions->sample(mIterations);
    const float rotation = mOptions.rotate ? dir.rotation : 0.0f;
    const std::uint32_t resolution = mOptions.bundleResolution;
    const Bounds& bounds = g.bounds;
    if (mOptions.fitVisible && freshGBuffer) {
        // The visible points of this iteration's G-buffer: no margin covers jitter (at a silhouette
        // it moves a pixel's point onto another surface), so the frame is fitted to the points the
        // visibility pass will look up, every iteration.
        g.visiblePoints = g.gbuffer->visiblePoints(*mContext);
    }
    shader::BundleFrame frame =
        g.visiblePoints.empty()
            ? bundleFrameForSphere(dir.omega, rotation, bounds.center(), bounds.radius(), resolution)
            : bundleFrameForPoints(dir.omega, rotation, g.visiblePoints, bounds.center(), bounds.radius(), resolution);

    shader::SkylightPush push{};
    push.radianceForward = g.environment->radiance(dir.omega);
    push.radianceBackward = g.environment->radiance(-dir.omega);
    push.pdfForward = g.directions->hemispherePdf(dir.omega);
    push.pdfBackward = g.directions->hemispherePdf(-dir.omega);
    push.width = width;
    push.height = height;
    push.environmentRotation = g.scene->environmentRotation();
    push.samplePosition = sample.samplePosition;
    push.environmentPresent = g.scene->environmentPresent() ? 1u : 0u;
    push.glossyControl = mOptions.glossyControl ? 1u : 0u;
    push.seed = static_cast<std::uint32_t>(info.seed);
    push.iteration = mIterations;
    if (g.irradiance.get()) {
        push.controlVariate = 1u;
        push.irradianceAddress = split(deviceAddress(*mContext, g.irradiance));
    }
    auto dispatchVisibility = [&](VkCommandBuffer cmd) {
        std::uint32_t scope = g.timer.start(cmd, "visibility");
        const VkDescriptorSet sets[] = {g.camera->set(), g.bound.set()};
        g.visibility.dispatch(
            cmd, push, vk::groupCount(width, height, shader::kSkylightGroupSize),
            sets);
        g.timer.stop(cmd, scope);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT);
    };
    if (g.depthMap) {
        // A shadow map serves omega only: its density is q(omega) on the sphere, not p_r.
        push.visibility = shader::kSkylightVisibilityDepthMap;
        push.pdfForward = g.directions->pdf(dir.omega);
        push.addBase = 1u;
        std::memcpy(g.frame.data(), &frame, sizeof(frame));
        mContext->submitAndWait([&](VkCommandBuffer cmd) {
            g.timer.begin(cmd);
            g.depthMap->record(cmd, frame, info.time, &g.timer);
            dispatchVisibility(cmd);
        });
        g.timer.collect();
        ++mIterations;
        return;
    }
    push.visibility = shader::kSkylightVisibilityBundle;
    bool first = true;
    // Each part of the bundle (the frame, or its tiles) is recorded with its build: the frame's
    // uniform is written here, while recording, as each part is its own submission.
    g.lastStats = g.builder->build(
        frame, info.time,
        [&](const BuiltBundle&) {
            g.timer.collect(); // the part's passes, after its submission
            first = false;
        },
        [&](VkCommandBuffer cmd, const BuiltBundle& built) {
            std::memcpy(g.frame.data(), &built.frame, sizeof(built.frame));
            push.headAddress = split(built.heads);
            push.nodeAddress = split(built.nodes);
            push.counterAddress = split(built.counters);
            push.hitAddress = split(built.payload);
            push.addBase = first ? 1u : 0u;
            g.timer.begin(cmd);
            if (gbufferWithBundle) {
                g.camera->record(cmd, *g.gbufferSample, &g.timer);
            }
            dispatchVisibility(cmd);
        });
    if (g.builds.empty()) {
        g.builds.push_back({"bundle build", 0.0, 0});
    }
    g.builds[0].totalMs += g.lastStats.buildMs;
    g.builds[0].count += 1;
    ++mIterations;
}

ImageSet SkylightMode::resolve() {
    Gpu& g = sceneState(mGpu, name(), "resolve");
    ImageSet out;
    out.iterations = mIterations;
    // One sample per pixel and direction: emitted + direct, and their variance.
    gpu::AccumulatedImages estimate = g.camera->accumulator().resolve(*mContext, mIterations);
    out.layers = std::move(estimate.layers);
    addSampleLosses(out, estimate.nonFiniteSamples, estimate.droppedSamples, estimate.expectedSamples);
    out.counters.emplace_back("bundle_fragments_last", double(g.lastStats.fragments));
    out.counters.emplace_back("bundle_rebuilds_last", double(g.lastStats.rebuilds));
    out.counters.emplace_back("bundle_tiles_last", double(g.lastStats.tiles));
    return out;
}

PassTimes SkylightMode::timings() const {
    if (!mGpu) return {};
    PassTimes t = mGpu->timer.totals();
    t.insert(t.end(), mGpu->builds.begin(), mGpu->builds.end());
    return t;
}

TradeSettings SkylightMode::trades() const {
    TradeSettings t = tradeSettingsOf(mSettings, {}, kBundleResolution, kFit);
    t.lobesByBundleDirections = !mOptions.glossyControl; // else each pixel samples its lobe itself
    if (mOptions.depthMapVisibility) {
        t.bundleWhat = "depth maps";
        t.bundleRule = BundleRule::DepthMapNearestLight;
    }
    return t;
}

} // namespace bl
