#include "modes/bidir/BidirMode.h"

#include "base/Error.h"
#include "base/WallSpan.h"
#include "bundle/BundleFrame.h"
#include "bundle/FittingBuild.h"
#include "gpu/CameraPass.h"
#include "gpu/EmitterPointPass.h"
#include "gpu/ShadowCubePass.h"
#include "gpu/PackedTextures.h"
#include "modes/LightShadowPass.h"
#include "modes/bidir/EnvironmentBundles.h"
#include "modes/bidir/ReflectiveShadowMap.h"
#include "modes/bidir/VplSampler.h"
#include "scene/Scene.h"
#include "vk/BoundSet.h"
#include "vk/Commands.h"
#include "vk/ComputePass.h"
#include "vk/Descriptors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <modes/bidir/BidirEnvironment.h>
#include <modes/bidir/BidirShared.h>
#include <modes/bidir/BidirTextures.h>
#include <modes/bidir/EvaluateSpecialization.h>
#include <modes/bidir/Rsm.h>
#include <modes/bidir/Suppression.h>
#include <modes/bidir/evaluate.comp.spv.h>

namespace bl {

namespace {

// How far a VPL's shadow cube centre sits off its surface, as a fraction of the scene's bounding
// radius: the cube must not sit exactly in the VPL's own plane (that plane, seen edge-on, would
// shadow grazing receivers), and 1e-3 of the scene is far below any feature the cube resolves at
// its 256^2 default (a texel spans ~4e-3 of the scene at unit distance).
constexpr float kVplLiftFraction = 1e-3f;

bool finiteVec(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Every field the evaluation reads of a VPL is finite (a light ray's hit at float's limits can
// produce an infinite area density or a NaN position; such a VPL is lost, not a sample of zero).
bool finiteVpl(const shader::BidirVpl& v) {
    return finiteVec(v.position) && finiteVec(v.normal) && finiteVec(v.albedo) && finiteVec(v.intensity) &&
           finiteVec(v.toLight) && finiteVec(v.cubeCentre) && std::isfinite(v.pdfLight) && std::isfinite(v.areaPdf);
}
} // namespace

std::unique_ptr<Mode> BidirMode::create(const Settings& settings) { return std::make_unique<BidirMode>(settings); }

BidirMode::BidirMode(const Settings& settings) : mSettings(settings), mOptions(bidirOptions(settings)) {}

// Light sub-paths ([TO12 §4.1]): the lights' shadow cubes, the VPLs (traced or from reflective
// shadow maps) with their cubes, the area emitters' points, and what was lost of them.
struct BidirLightPaths {
    std::unique_ptr<gpu::ShadowCubePass> shadows;    // cube l = light l
    std::unique_ptr<gpu::ShadowCubePass> vplShadows; // cube k = VPL k
    std::unique_ptr<gpu::EmitterPointPass> emitterPoints; // area emitters: direct and one-bounce light
    std::unique_ptr<VplSampler> vpls;
    std::unique_ptr<ReflectiveShadowMap> rsm; // vpl_source = rsm
    vk::Buffer noRsm;                         // vpl_source = traced: the CDF block's header, N = 0
    vk::Buffer vplBuffer;
    std::uint64_t invalidVpls = 0; // over all frames: VPLs that add nothing (escaped, black, back-lit or lost)
    std::uint64_t lostVpls = 0;    // over all frames: VPLs whose record was not finite (never used)
    std::uint64_t sampledVpls = 0; // over all frames: what invalidVpls and lostVpls are parts of
};

// Camera paths by bundles (the bundle strategy, [TO12 Eq. 5]): a bundle per VPL/bundle pair and
// the environment's bundles in one pool, their directions and frames, and what their builds cost.
struct BidirCameraBundles {
    bool pairBundles = false;                        // a bundle per VPL/bundle pair
    std::unique_ptr<BundlePool> pool;                // null for strategy = vpl
    std::unique_ptr<DirectionSampler> directions;
    std::unique_ptr<EnvironmentBundles> environment; // pool slots after the pairs'
    std::unique_ptr<gpu::PackedTextures> textures;   // albedo at bundle hits
    Bounds bounds;
    std::vector<glm::vec3> visiblePoints; // fit = visible: this frame's G-buffer points
    std::uint64_t nodesLast = 0;
    std::uint64_t rebuilds = 0;
    double pixelGainSum = 0.0;            // sum over bundles of (sphere frame's pixel / this frame's pixel)
    std::uint64_t bundlesBuilt = 0;
};

struct BidirMode::Gpu {
    std::unique_ptr<gpu::GpuScene> scene;
    std::unique_ptr<gpu::CameraPass> camera;
    BidirLightPaths light;
    BidirCameraBundles bundles;
    // The evaluation ([TO12 Eq. 3], [TO12 Eq. 7]): both strategies' contributions with their MIS weights.
    vk::BoundSet bound;
    vk::ComputePass<shader::BidirPush> evaluate;
    vk::GpuTimer timer;
    // Host wall clock of each phase of a frame (submission, wait, read-back), beside the timestamps.
    PassTime wallGbuffer{"gbuffer (wall)"}, wallBundles{"bundles (wall)"}, wallVpls{"VPLs (wall)"},
        wallEvaluate{"shadow cubes + evaluate (wall)"};
};

BidirMode::~BidirMode() = default;

void BidirMode::setScene(const Scene& scene, vk::Context* ctx) {
    mContext = &requireDevice(ctx, "bidir");
    mScene = &scene;
    mIterations = 0;
    mPlan = plan(scene);
    const auto width = static_cast<std::uint32_t>(scene.camera.resolution.x);
    const auto height = static_cast<std::uint32_t>(scene.camera.resolution.y);
    const BidirOptions& o = mOptions;
    const std::uint32_t pairs = o.pairs;
    const std::uint32_t strategy = o.strategy;
    const std::uint32_t points = o.emitterPoints;
    const std::uint32_t pointSide = o.emitterShadowResolution;
    const bool areaLit = mPlan.runs(kBidirPassEmitterPoints);
    ctx->requireDeviceMemory(VkDeviceSize(width) * height * gpu::CameraPass::bytesPerPixel(shader::kBidirAccumLayers) +
                                 gpu::ShadowCubePass::bytesFor(o.shadowResolution, scene.lights.size()) +
                                 gpu::ShadowCubePass::bytesFor(o.vplShadowResolution, pairs) +
                                 (areaLit ? gpu::EmitterPointPass::bytesFor(points, pointSide) : 0),
                             "bidir at " + std::to_string(width) + "x" + std::to_string(height));
    auto g = std::make_unique<Gpu>();
    g->scene = std::make_unique<gpu::GpuScene>(*ctx, scene);
    g->camera = std::make_unique<gpu::CameraPass>(*ctx, *g->scene, width, height, shader::kBidirAccumLayers);
    g->light.shadows = std::make_unique<gpu::ShadowCubePass>(*ctx, *g->scene, o.shadowResolution);
    // The constructor wants room for the lights' cubes too; VPL cubes use slots 0 .. K-1 only.
    const auto vplCubes = std::max<std::uint32_t>(pairs, g->light.shadows->lightCount());
    g->light.vplShadows = std::make_unique<gpu::ShadowCubePass>(*ctx, *g->scene, o.vplShadowResolution, vplCubes);
    g->light.vpls = std::make_unique<VplSampler>(scene, mPlan.runs(kBidirPassAreaVpls));
    g->light.emitterPoints = std::make_unique<gpu::EmitterPointPass>(*ctx, *g->scene, scene, areaLit ? points : 0u, pointSide);
    if (o.rsmVpls && g->light.shadows->lightCount() > 0) {
        g->light.rsm = std::make_unique<ReflectiveShadowMap>(*ctx, *g->scene, o.rsmResolution);
    } else {
        g->light.noRsm = vk::Buffer(*ctx, 4 * shader::kBidirRsmHeaderWords, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              vk::MemoryUse::Upload);
        std::memset(g->light.noRsm.data(), 0, 4 * shader::kBidirRsmHeaderWords);
    }
    g->light.vplBuffer = vk::Buffer(*ctx, sizeof(shader::BidirVpl) * pairs, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              vk::MemoryUse::Upload);
    g->bundles.bounds = scene.bounds();
    setUpInterleaving(scene, width, height);
    g->bundles.environment = std::make_unique<EnvironmentBundles>(
        *ctx, scene, mPlan.runs(kBidirPassEnvironment) ? o.environmentBundles : 0u, 0.1f);
    g->bundles.textures = std::make_unique<gpu::PackedTextures>(*ctx, scene);
    const bool pairBundles = mPlan.runs(kBidirPassBundles);
    g->bundles.pairBundles = pairBundles;

    if (pairBundles || g->bundles.environment->count() > 0) {
        if (!ctx->geometryShader()) {
            throw Error("bidir: strategy " + o.strategyName + " with bounces = " + std::to_string(o.bounces) +
                        " needs bundle hit payloads (gl_PrimitiveID: geometry shaders); use strategy=vpl bounces=1");
        }
        const std::uint32_t resolution = o.bundleResolution;
        BundlePoolOptions options;
        options.slots = (pairBundles ? pairs : 0u) + g->bundles.environment->count();
        options.slotPixels = resolution * resolution;
        options.payload = BundlePayload::Hit;
        options.memoryCapBytes = o.memoryCapBytes;
        try {
            g->bundles.pool = std::make_unique<BundlePool>(*ctx, *g->scene, options);
        } catch (const Error& e) {
            throw Error("bidir: " + std::to_string(pairs) + " bundles of " + std::to_string(resolution) + "^2: " +
                        e.what() + " (lower pairs_per_frame or bundle_resolution, or raise memory_cap_mib)");
        }
    }
    // A scope per bundle build and per VPL cube, plus the camera, light and evaluation passes.
    constexpr std::uint32_t kOtherScopes = 9;
    g->timer = vk::GpuTimer(*ctx, 2 * pairs + g->bundles.environment->count() + kOtherScopes);

    VkDevice device = ctx->device();
    g->bound = vk::BoundSet(
        device, {vk::Bound::storageBuffer(shader::kBidirBindingLights, g->scene->lightBuffer()),
                 vk::Bound::storageImage(shader::kBidirBindingShadowMaps, g->light.shadows->maps().view()),
                 vk::Bound::storageImage(shader::kBidirBindingVplMaps, g->light.vplShadows->maps().view()),
                 vk::Bound::storageBuffer(shader::kBidirBindingVpls, g->light.vplBuffer.get()),
                 vk::Bound::storageBuffer(shader::kBidirBindingEmitterPoints, g->light.emitterPoints->buffer()),
                 vk::Bound::storageImage(shader::kBidirBindingEmitterShadowMaps, g->light.emitterPoints->maps().view()),
                 vk::Bound::storageBuffer(shader::kBidirBindingRsmCdf, g->light.rsm ? g->light.rsm->cdf() : g->light.noRsm.get()),
                 vk::Bound::storageBuffer(shader::kBidirBindingEnvironment, g->bundles.environment->buffer()),
                 vk::Bound::storageBuffer(shader::kBidirBindingTextures, g->bundles.textures->buffer()),
                 vk::Bound::storageImage(shader::kBidirBindingFrame, mInterleave->frameView()),
                 vk::Bound::storageBuffer(shader::kBidirBindingInterleave, mInterleave->evaluateBuffer())});
    // EvaluateSpecialization.h, in its order: what the evaluation's paths depend on for the scene's life.
    const SceneFeatures features = scene.features();
    std::vector<std::uint32_t> specialization(shader::kBidirSpecCount);
    specialization[shader::kBidirSpecStrategy] = strategy;
    specialization[shader::kBidirSpecBounces] = o.bounces;
    specialization[shader::kBidirSpecSuppression] =
        mPlan.runs(kBidirPassSuppression) ? o.suppression : shader::kBidirSuppressionNone;
    specialization[shader::kBidirSpecGlossy] = features.glossy ? 1u : 0u;
    specialization[shader::kBidirSpecTextured] = features.textured ? 1u : 0u;
    specialization[shader::kBidirSpecEnvironment] = g->bundles.environment->count() > 0 ? 1u : 0u;
    specialization[shader::kBidirSpecRsm] = g->light.rsm ? 1u : 0u;
    specialization[shader::kBidirSpecVplTaps] = o.vplShadowTaps;
    specialization[shader::kBidirSpecAreaVpls] = g->light.vpls->areaSource() ? 1u : 0u;
    g->evaluate = vk::ComputePass<shader::BidirPush>(device, kSpv_modes_bidir_evaluate_comp,
                                                     {g->camera->setLayout(), g->bound.layout()}, specialization);
    mInterleave->preparePipeline(g->camera->setLayout());
    mGpu = std::move(g);
}

// Interleaving's options from the settings; its temporal caches are kept across setScene (the
// frames of an animation) for the same scene, image size and options.
void BidirMode::setUpInterleaving(const Scene& scene, std::uint32_t width, std::uint32_t height) {
    InterleaveOptions o;
    o.n = mOptions.interleave;
    o.filter = mOptions.interleaveFilter;
    o.temporal = mOptions.temporal;
    o.reproject = mPlan.runs(kBidirPassReprojection);
    o.twoSigma2 = static_cast<float>(mOptions.temporalDepthVariance);
    const std::uint32_t pairs = mOptions.pairs;
    if (o.n * o.n > pairs) {
        throw Error("bidir: interleave = " + std::to_string(o.n) + " needs pairs_per_frame >= " +
                    std::to_string(o.n * o.n) + " (one pair per sub-image at least), got " + std::to_string(pairs));
    }
    if (!mInterleave || !mInterleave->matches(width, height, o) || mInterleaveScene != &scene) {
        mInterleave = std::make_unique<Interleaving>(*mContext, width, height, o);
    }
    mInterleave->setReproject(o.reproject);
    mInterleaveScene = &scene;
}

// Builds the K bundles of this frame into the pool; grows the pool and builds again when they did
// not fit (nothing partial is kept), and refuses what the limits cannot hold.
void BidirMode::buildBundles(const IterationInfo& info) {
    Gpu& g = *mGpu;
    const std::uint32_t slots = g.bundles.pool->slots();
    const std::uint32_t pairSlots = slots - g.bundles.environment->count(); // then the environment's
    const std::uint32_t resolution = mOptions.bundleResolution;
    std::vector<shader::BundleFrame> frames(pairSlots);
    for (std::uint32_t k = 0; k < pairSlots; ++k) {
        const BundleDirection dir =
            g.bundles.directions->sample(static_cast<std::uint32_t>(mInterleave->sequenceBase(mIterations, pairSlots) + k));
        frames[k] = g.bundles.visiblePoints.empty() ? bundleFrameForSphere(dir.omega, dir.rotation, g.bundles.bounds.center(),
                                                                   g.bundles.bounds.radius(), resolution)
                                            : bundleFrameForPoints(dir.omega, dir.rotation, g.bundles.visiblePoints,
                                                                   g.bundles.bounds.center(), g.bundles.bounds.radius(), resolution);
        g.bundles.pixelGainSum += 2.0 * g.bundles.bounds.radius() / (double(resolution) * frames[k].pixelSize);
    }
    g.bundles.bundlesBuilt += pairSlots;
    const std::vector<shader::BundleFrame> environment = g.bundles.environment->frames(
        mIterations, static_cast<std::uint32_t>(info.seed), pairSlots, g.bundles.visiblePoints, g.bundles.bounds, resolution);
    frames.insert(frames.end(), environment.begin(), environment.end());
    g.bundles.nodesLast = buildFitting(*g.bundles.pool, {"bidir", slots, resolution}, [&] {
        mContext->submitAndWait([&](VkCommandBuffer cmd) {
            g.timer.begin(cmd);
            g.bundles.pool->recordReset(cmd);
            std::vector<BundlePool::SlotBuild> builds(slots);
            for (std::uint32_t k = 0; k < slots; ++k) {
                builds[k] = {k, frames[k], BundleGeometry::triangles(info.time)};
            }
            g.bundles.pool->recordBuilds(cmd, builds, &g.timer);
        });
        g.timer.collect();
    }, g.bundles.rebuilds);
}

void BidirMode::iterate(const IterationInfo& info) {
    Gpu& g = sceneState(mGpu, name(), "iterate");
    const BidirOptions& o = mOptions;
    const std::uint32_t pairs = o.pairs;
    const std::uint32_t strategy = o.strategy;
    const std::uint32_t lightCount = g.light.shadows->lightCount();
    if (!g.bundles.directions) {
        // The seed decorrelates runs; directions are reproducible from (settings, seed).
        g.bundles.directions = std::make_unique<DirectionSampler>(
            o.directions, static_cast<std::uint32_t>(info.seed));
    }
    // The G-buffer first: fit = visible fits this frame's bundles to the points it sees.
    const gpu::CameraSample sample = mInterleave->cameraSample(g.camera->sample(mIterations, true, info.time, info.seed),
                                                               g.camera->width(), g.camera->height());
    {
        const WallSpan wall(g.wallGbuffer);
        mContext->submitAndWait([&](VkCommandBuffer cmd) {
            g.timer.begin(cmd);
            g.camera->record(cmd, sample, &g.timer);
        });
        g.timer.collect();
    }
    if (g.bundles.pool) {
        const WallSpan wall(g.wallBundles);
        if (o.fitVisible) g.bundles.visiblePoints = g.camera->gbuffer().visiblePoints(*mContext);
        buildBundles(info);
    }
    const bool useVpls = mPlan.runs(kBidirPassVpls);
    std::vector<shader::BidirVpl> vpls(pairs);
    if (useVpls) {
        const WallSpan wall(g.wallVpls);
        const std::uint64_t first = mInterleave->sequenceBase(mIterations, pairs);
        const auto seed = static_cast<std::uint32_t>(info.seed);
        const float lift = kVplLiftFraction * g.bundles.bounds.radius();
        if (g.light.rsm) {
            // The area source's pairs are traced on the host, the lights' from the cubes.
            const bool area = g.light.vpls->areaSource();
            std::vector<std::uint32_t> areaPairs;
            vpls = g.light.rsm->sample(first, pairs, seed, info.time, lift, &g.timer, area, areaPairs);
            for (std::uint32_t k : areaPairs) vpls[k] = g.light.vpls->areaVpl(first + k, seed, info.time, lift);
        } else {
            vpls = g.light.vpls->sample(first, pairs, seed, info.time, lift);
        }
        for (shader::BidirVpl& v : vpls) {
            if (v.valid && !finiteVpl(v)) {
                v.valid = 0u; // lost work, not a zero sample: counted apart and refused if it is all
                ++g.light.lostVpls;
            }
            g.light.invalidVpls += v.valid ? 0u : 1u;
        }
        g.light.sampledVpls += vpls.size();
    }
    std::memcpy(g.light.vplBuffer.data(), vpls.data(), sizeof(shader::BidirVpl) * pairs);

    const std::uint32_t width = g.camera->width(), height = g.camera->height();
    const bool renderShadows = mPlan.runs(kPassLightShadowCubes) && g.light.shadows->refreshFor(*mContext, *g.scene, info.time);
    g.light.emitterPoints->prepare(info.seed, mIterations, info.time);
    shader::BidirPush push{};
    if (g.bundles.pool) {
        push.pool = g.bundles.pool->view();
    }
    push.width = width;
    push.height = height;
    push.pairs = lightCount > 0 || g.bundles.pairBundles || useVpls ? pairs : 0u;
    push.lightCount = lightCount;
    push.shadowResolution = g.light.shadows->resolution();
    push.vplResolution = g.light.vplShadows->resolution();
    push.strategy = strategy;
    // Uniform directions: every direction of a hemisphere has the same density (the axis is arbitrary).
    push.hemispherePdf = g.bundles.directions->hemispherePdf(glm::vec3(0.0f, 0.0f, 1.0f));
    push.suppression = mPlan.runs(kBidirPassSuppression) ? o.suppression : shader::kBidirSuppressionNone;
    push.suppressionNeighbours = static_cast<float>(o.suppressionNeighbours);
    push.environmentPresent = g.scene->environmentPresent() ? 1u : 0u;
    push.environmentRotation = g.scene->environmentRotation();
    push.samplePosition = sample.samplePosition;
    push.bounces = o.bounces;
    const float minDistance = static_cast<float>(o.twoBounceClamp) * g.bundles.bounds.radius();
    push.twoBounceMinDistance2 = minDistance * minDistance;
    std::optional<WallSpan> wall(std::in_place, g.wallEvaluate);
    mContext->submitAndWait([&](VkCommandBuffer cmd) {
        g.timer.begin(cmd);
        if (renderShadows) {
            g.light.shadows->record(cmd, info.time, &g.timer);
        }
        g.light.emitterPoints->record(cmd, info.time, &g.timer);
        for (std::uint32_t k = 0; useVpls && k < pairs; ++k) {
            if (vpls[k].valid) {
                g.light.vplShadows->record(cmd, vpls[k].cubeCentre, k, info.time, &g.timer);
            }
        }
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        const std::uint32_t scope = g.timer.start(cmd, "evaluate");
        if (mInterleave->active()) mInterleave->recordClear(cmd);
        const VkDescriptorSet sets[] = {g.camera->set(), g.bound.set()};
        g.evaluate.dispatch(cmd, push,
                            vk::groupCount(mInterleave->dispatchWidth(), mInterleave->dispatchHeight(),
                                           shader::kBidirGroupSize),
                            sets);
        g.timer.stop(cmd, scope);
        if (mInterleave->active()) mInterleave->recordResolve(cmd, g.camera->set(), sample.camera, &g.timer);
        vk::computeToHost(cmd);
    });
    g.timer.collect();
    wall.reset();
    if (mInterleave->active()) mInterleave->advance();
    ++mIterations;
}

ImageSet BidirMode::resolve() {
    Gpu& g = sceneState(mGpu, name(), "resolve");
    ImageSet out;
    out.iterations = mIterations; // one sample per pixel per frame (the mean over its K pairs)
    gpu::AccumulatedImages estimate = g.camera->accumulator().resolve(*mContext, mIterations);
    out.layers = std::move(estimate.layers);
    addSampleLosses(out, estimate.nonFiniteSamples, estimate.droppedSamples, estimate.expectedSamples);
    if (mInterleave->options().temporal && mIterations > 0) {
        // The last frame's share of accepted reprojected caches ([TO12s] Fig. 1 b, 4 c).
        out.layers.emplace_back("cache_hits", mInterleave->cacheHits());
    }
    // A VPL whose light ray escaped or met a black surface (or the back of one) is a sample of
    // zero, a valid estimate (a point light outside a closed box lights nothing inside it); only
    // VPLs whose record is not finite are lost work. That every VPL is zero is still worth saying.
    out.counters.emplace_back("invalid_vpls", double(g.light.invalidVpls));
    out.lost.push_back({"non_finite_vpls", g.light.lostVpls, g.light.sampledVpls, "VPLs", "were not finite and left out"});
    if (g.light.invalidVpls == g.light.sampledVpls && g.light.lostVpls < g.light.sampledVpls) { // all lost: refused instead
        out.notes.push_back("all " + std::to_string(g.light.sampledVpls - g.light.lostVpls) +
                            " VPLs carry no light (their light rays escaped or met black surfaces or the backs of "
                            "them), so the image has no light reflected from a VPL; if the scene should, raise "
                            "pairs_per_frame or iterations (invalid_vpls)");
    }
    if (g.light.rsm) {
        out.counters.emplace_back("rsm_texel_mismatches", double(g.light.rsm->texelMismatches()));
    }
    if (g.bundles.pool) {
        out.counters.emplace_back("bundle_nodes_last", double(g.bundles.nodesLast));
        out.counters.emplace_back("bundle_pool_rebuilds", double(g.bundles.rebuilds));
        // bundle_resolution x the mean ratio of the sphere frame's pixel to the one used: the side of a
        // sphere-fitted bundle with the same pixels (fit = scene: bundle_resolution).
        out.counters.emplace_back("bundle_effective_resolution",
                                  g.bundles.bundlesBuilt ? double(mOptions.bundleResolution) * g.bundles.pixelGainSum /
                                                       double(g.bundles.bundlesBuilt)
                                                 : 0.0);
    }
    return out;
}

PassTimes BidirMode::timings() const {
    if (!mGpu) return {};
    PassTimes t = mGpu->timer.totals();
    for (const PassTime* w : {&mGpu->wallGbuffer, &mGpu->wallBundles, &mGpu->wallVpls, &mGpu->wallEvaluate}) {
        if (w->count > 0) t.push_back(*w);
    }
    return t;
}

TradeSettings BidirMode::trades() const {
    TradeSettings t = tradeSettingsOf(mSettings, kShadowResolution, kBundleResolution, kFit);
    // strategy = vpl with one bounce pairs its VPLs with no bundle (setScene: pairBundles); only an
    // environment's bundles are left to judge.
    t.bundlesOnlyForEnvironment = mOptions.strategy == shader::kBidirStrategyVpl && !mOptions.twoBounce();
    t.bundleRule = BundleRule::ListAlongFacetPlanes; // its pools carry hit payloads
    return t;
}

} // namespace bl
