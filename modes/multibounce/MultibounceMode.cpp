#include "modes/multibounce/MultibounceMode.h"

#include "base/Error.h"
#include "bundle/BundleFrame.h"
#include "bundle/BundlePool.h"
#include "bundle/DirectionSampler.h"
#include "bundle/FittingBuild.h"
#include "gpu/CameraPass.h"
#include "bundle/EnvironmentShadowPass.h"
#include "gpu/EmitterPointPass.h"
#include "gpu/MaterialSpecialization.h"
#include "gpu/PackedTextures.h"
#include "gpu/ShadowCubePass.h"
#include "modes/EmitterPointParameters.h"
#include "modes/EnvironmentShadowParameters.h"
#include "modes/LightShadowPass.h"
#include "modes/multibounce/SurfacePoints.h"
#include "scene/Scene.h"
#include "vk/BoundSet.h"
#include "vk/Commands.h"
#include "vk/ComputePass.h"
#include "vk/Descriptors.h"

#include <modes/multibounce/MultibounceShared.h>
#include <modes/multibounce/paths.comp.spv.h>

#include <cstdio>

namespace bl {

namespace {
constexpr double kMiB = 1024.0 * 1024.0;
// First pool size, in nodes per bundle pixel: closed rooms seen from outside their bounding
// sphere's frame have depth complexity ~1-2 per pixel (the Cornell box: 1.05); the pool grows to
// what an iteration needs, so starting low keeps large K and R from asking for memory never used.
constexpr std::uint64_t kInitialNodesPerPixel = 2;

} // namespace

std::vector<ParamSpec> MultibounceMode::parameters() {
    // K = 32 with 8 paths a pixel: the builds are most of an iteration at K = 64 with 4, and an
    // iteration's variance goes about as 1/K + 1/paths; K = 16 with 16 paths is a little lower
    // still on diffuse scenes, 32 the middle with twice its directions (README, `bundle_count`).
    std::vector<ParamSpec> params{
        {kBundleCount, std::int64_t{32}, "bundles", "resident omnidirectional bundles per iteration (K); paths pick one per bounce",
         1, 4096, {}},
        {kPathsPerPixel, std::int64_t{8}, "paths",
         "camera paths per pixel through each iteration's bundles (they share its K directions)", 1, 1024, {}},
        {kBundleResolution, std::int64_t{128}, "pixels",
         "side of each bundle; the next vertex is found up to half a pixel diagonal off the exact ray", 8, 4096, {}},
        {kDirections, std::string("halton"), "", "bundle directions, uniform on the sphere", 0, 0, {"halton", "random"}},
        {kMaxSegments, std::int64_t{64}, "segments", "at most this many segments per path (1 emitters, 2 direct light)", 1,
         1024, {}},
        {kRrSegments, std::int64_t{5}, "segments", "Russian roulette from this path length on", 1, 1024, {}},
        {kShadowResolution, std::int64_t{512}, "texels", "side of each shadow cube face (point and spot lights)", 16, 8192,
         {}},
        {kMemoryCap, std::int64_t{0}, "MiB",
         "node storage limit of the bundle pool (0: half the largest device-local heap); an iteration that needs more is "
         "refused",
         0, 1 << 20, {}},
        {kBundles, std::string("perfect"), "",
         "perfect: bundles of the scene's triangles; imperfect: of point splats ([TO12p])", 0, 0, {"perfect", "imperfect"}},
        {kPoints, std::int64_t{16384}, "points",
         "imperfect bundles: points per direction, uniform by area, a different set per direction", 16, 1 << 22, {}},
        {kSplatScale, 2.0, "",
         "imperfect bundles: disc radius in units of sqrt(area / (pi points)); larger: fewer holes, more redundant nodes",
         0.05, 20.0, {}},
        {kSplatUv, std::string("corners"), "",
         "imperfect bundles: corners: texture coordinates interpolated over each splat from its corners ([TO12p]); "
         "centre: the splat's centre texel over the whole splat (for comparison)",
         0, 0, {"corners", "centre"}},
        {kEmitterSampling, std::string("mis"), "",
         "area emitters and the environment after a bounce: mis (bundle hits and escapes, and emitter points and "
         "environment directions, by the balance heuristic), bundles (bundle hits and escapes alone, as [TO12]), points "
         "(emitter points and environment directions alone)",
         0, 0, {"mis", "bundles", "points"}},
    };
    params = withEmitterPointParameters(std::move(params), "iteration",
                                        "next-event estimation at every path vertex (emitter_sampling mis, points)", 1);
    return withEnvironmentShadowParameters(std::move(params), "iteration",
                                           "next-event estimation at every path vertex (emitter_sampling mis, points); "
                                           "0: escaping paths alone");
}

std::unique_ptr<Mode> MultibounceMode::create(const Settings& settings) {
    return std::make_unique<MultibounceMode>(settings);
}

MultibounceMode::MultibounceMode(const Settings& settings) : mSettings(settings), mOptions(multibounceOptions(settings)) {}

// What lights each path vertex: the point/spot lights' shadow cubes, the emitter points
// (next-event estimation toward area emitters) and the emitters' table for bundle hits (MIS).
struct MultibounceLights {
    std::unique_ptr<gpu::ShadowCubePass> shadows;
    std::unique_ptr<gpu::EmitterPointPass> emitterPoints;
    std::unique_ptr<EnvironmentShadowPass> environmentShadows; // off (placeholders) unless the plan runs it
    vk::Buffer emitters;
    std::uint32_t emitterCount = 0;
};

// The K resident bundles a path steps through ([TO12] section 7): the pool, their directions, the
// point splats of imperfect bundles, the albedo textures read at hits, and what their builds cost.
struct MultibounceBundles {
    std::unique_ptr<BundlePool> pool;
    std::unique_ptr<DirectionSampler> directions;
    std::unique_ptr<SurfacePoints> points; // imperfect bundles only
    vk::Buffer noPoints;                   // perfect bundles: the points and splats bindings' placeholder
    std::unique_ptr<gpu::PackedTextures> textures;
    Bounds bounds;
    std::uint64_t nodesLast = 0; // nodes the last iteration's K bundles held
    std::uint64_t rebuilds = 0;  // iterations redone after the pool grew
    PrefetchedBuild prefetched;  // the next iteration's bundles, built with this one's paths
};

struct MultibounceMode::Gpu {
    std::unique_ptr<gpu::GpuScene> scene;
    std::unique_ptr<gpu::CameraPass> camera;
    MultibounceLights lights;
    MultibounceBundles bundles;
    // The paths pass: every camera path through the bundles, its vertices lit as above.
    vk::BoundSet bound;
    vk::ComputePass<shader::MultibouncePush> paths;
    vk::GpuTimer timer;
};

MultibounceMode::~MultibounceMode() = default;

PassPlan MultibounceMode::plan(const Scene& scene) const {
    const SceneFeatures f = scene.features();
    const MultibounceOptions& o = mOptions;
    const auto k = std::to_string(o.bundleCount);
    const auto r = std::to_string(o.bundleResolution);
    PassPlan p;
    const auto n = std::to_string(o.points);
    p.add(kPassSurfacePoints, "surface points", o.imperfect, o.imperfect ? "imperfect-bundles" : "perfect-bundles",
          o.imperfect ? k + " x " + n + " points uniform by area over " + std::to_string(f.triangles) +
                            " triangles (a different set per direction), every iteration" +
                            (f.textured ? "; UVs and their gradients over each splat's plane (texture coordinates at the corners)"
                                        : "; no textures: UVs not interpolated")
                      : "bundles = perfect: bundles of the triangles themselves");
    p.add("bundles", "bundle build", true, o.imperfect ? "point-splats" : "triangles",
          o.imperfect ? k + " bundles of " + r + "^2 pixels from " + n + " point splats each (splat_scale " +
                            formatValue(o.splatScale) + "), with hit payload, every iteration"
                      : k + " bundles of " + r + "^2 pixels over " + std::to_string(f.triangles) +
                            " triangles, with hit payload, every iteration");
    p.add("bundle-sort", "bundle sort", true, "always",
          "depth order per pixel: the next vertex is one step from the point's depth");
    p.add(lightShadowCubesPass(f, " at every path vertex", "iteration"));
    p.add("gbuffer", "gbuffer", true, "always", "the camera's first vertex, jittered every iteration");
    const std::string& sampling = o.emitterSampling;
    const bool points = f.emissiveMeshes && o.emitterPointCount() > 0;
    p.add(kPassEmitterPoints, "emitter points", points,
          !f.emissiveMeshes ? "no-area-emitters" : points ? "emitter-sampling-" + sampling : "emitter-sampling-bundles",
          points ? std::to_string(o.emitterPoints) + " point(s) on the emitters per iteration, by power, x 6 faces of " +
                       std::to_string(o.emitterShadowResolution) + "^2, at every path vertex"
          : !f.emissiveMeshes ? "no emissive mesh"
                              : "emitter_sampling = bundles: emitters only where bundles hit them");
    p.add("paths", "paths", true, f.emissiveMeshes ? "emitter-sampling-" + sampling : "no-area-emitters",
          std::string("bounces through the bundles") +
              (!f.emissiveMeshes    ? "; no emitters to hit"
               : sampling == "mis"  ? "; emitters hit (front faces), weighed against the emitter points (MIS)"
               : sampling == "points" ? "; emitters seen from the camera only, the emitter points light the rest"
                                      : "; emitters hit (front faces)"));
    const bool shadows = f.environment && o.environmentShotCount() > 0;
    p.add(kPassEnvironmentShadows, "environment shadows", shadows,
          !f.environment ? "no-environment" : shadows ? "emitter-sampling-" + sampling
          : o.environmentShots == 0 ? "environment-shots-0" : "emitter-sampling-bundles",
          shadows ? std::to_string(o.environmentShots) + " direction(s) toward the environment per iteration, by its "
                        "importance, a " + std::to_string(o.environmentShadowResolution) +
                        "^2 depth map each, at every path vertex"
          : !f.environment ? "no environment"
          : o.environmentShots == 0 ? "environment_shots = 0: the environment only where paths escape"
                                    : "emitter_sampling = bundles: the environment only where paths escape");
    p.add(kPassEnvironment, "environment", f.environment, f.environment ? "escaping-paths" : "no-environment",
          !f.environment ? "no environment: escaping paths end"
          : !shadows    ? "escaping paths take the environment's radiance"
          : sampling == "points" ? "escaping paths end: the environment's directions light every vertex"
                                 : "escaping paths take the environment's radiance, weighed against its directions (MIS)");
    std::string textures = "no textures: no UV, gradient or texture work (the packed texture buffer holds the decode "
                           "table only)";
    if (f.textured) {
        char mib[32];
        std::snprintf(mib, sizeof(mib), "%.1f", double(gpu::PackedTextures::words(scene)) * 4.0 / kMiB);
        textures = "albedo at every vertex from " + std::to_string(scene.textures.size()) +
                   " textures packed in one buffer (" + mib + " MiB), bilinear at " +
                   (!o.imperfect      ? std::string("the bundle payload's UV")
                    : o.splatUvCentre ? std::string("each splat's centre UV")
                                      : std::string("the UV over each splat (from its corners)"));
    }
    p.add(kPassTextures, "textures", f.textured,
          !f.textured ? "no-textures" : !o.imperfect ? "payload-uv" : o.splatUvCentre ? "splat-centre-uv" : "splat-corner-uvs",
          textures);
    return p;
}

void MultibounceMode::setScene(const Scene& scene, vk::Context* ctx) {
    mContext = &requireDevice(ctx, "multibounce");
    mScene = &scene;
    mIterations = 0;
    mPlan = plan(scene);
    const auto width = static_cast<std::uint32_t>(scene.camera.resolution.x);
    const auto height = static_cast<std::uint32_t>(scene.camera.resolution.y);
    ctx->requireDeviceMemory(VkDeviceSize(width) * height * gpu::CameraPass::bytesPerPixel(shader::kMultibounceAccumLayers) +
                                 gpu::ShadowCubePass::bytesFor(mOptions.shadowResolution, scene.lights.size()) +
                                 (mPlan.runs(kPassEmitterPoints)
                                      ? gpu::EmitterPointPass::bytesFor(mOptions.emitterPointCount(), mOptions.emitterShadowResolution)
                                      : 0) +
                                 (mPlan.runs(kPassEnvironmentShadows)
                                      ? EnvironmentShadowPass::bytesFor(mOptions.environmentShots,
                                                                        mOptions.environmentShadowResolution)
                                      : 0),
                             "multibounce at " + std::to_string(width) + "x" + std::to_string(height));
    auto g = std::make_unique<Gpu>();
    g->scene = std::make_unique<gpu::GpuScene>(*ctx, scene);
    g->camera = std::make_unique<gpu::CameraPass>(*ctx, *g->scene, width, height, shader::kMultibounceAccumLayers);
    g->lights.shadows = std::make_unique<gpu::ShadowCubePass>(*ctx, *g->scene, mOptions.shadowResolution);
    g->lights.emitterPoints = std::make_unique<gpu::EmitterPointPass>(
        *ctx, *g->scene, scene, mPlan.runs(kPassEmitterPoints) ? mOptions.emitterPointCount() : 0u,
        mOptions.emitterShadowResolution);
    g->lights.environmentShadows = std::make_unique<EnvironmentShadowPass>(
        *ctx, *g->scene, scene, mPlan.runs(kPassEnvironmentShadows) ? mOptions.environmentShots : 0u,
        mOptions.environmentShadowResolution);
    g->bundles.bounds = scene.bounds();

    const std::uint32_t slots = mOptions.bundleCount;
    const std::uint32_t resolution = mOptions.bundleResolution;
    BundlePoolOptions options;
    options.slots = slots;
    options.slotPixels = resolution * resolution;
    options.payload = BundlePayload::Hit;
    options.sortable = true;
    options.initialNodes = kInitialNodesPerPixel * slots * options.slotPixels;
    options.memoryCapBytes = mOptions.memoryCapBytes;
    try {
        g->bundles.pool = std::make_unique<BundlePool>(*ctx, *g->scene, options);
    } catch (const Error& e) {
        throw Error("multibounce: " + std::to_string(slots) + " bundles of " + std::to_string(resolution) + "^2: " +
                    e.what() + " (lower bundle_count or bundle_resolution, or raise memory_cap_mib where the device allows)");
    }
    // A scope per build and per sort (the next iteration's, recorded with this one's passes), plus
    // the points, shadow, emitter-point, camera and path passes.
    constexpr std::uint32_t kOtherScopes = 12;
    g->timer = vk::GpuTimer(*ctx, 2 * slots + kOtherScopes);

    if (mPlan.runs(kPassSurfacePoints)) {
        g->bundles.points = std::make_unique<SurfacePoints>(*ctx, *g->scene, slots, mOptions.points, mOptions.splatScale);
    } else {
        g->bundles.noPoints = vk::Buffer(*ctx, sizeof(shader::MultibouncePoint), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                 vk::MemoryUse::Device);
    }

    g->bundles.textures = std::make_unique<gpu::PackedTextures>(*ctx, scene);

    std::vector<shader::MultibounceEmitter> emitters;
    for (const gpu::GpuDraw& d : g->scene->draws()) {
        emitters.push_back({scene.meshes[d.mesh].emission, d.firstIndex / 3});
    }
    g->lights.emitterCount = static_cast<std::uint32_t>(emitters.size());
    g->lights.emitters = vk::makeBuffer(*ctx, std::span<const shader::MultibounceEmitter>(emitters),
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

    VkDevice device = ctx->device();
    const VkBuffer points = g->bundles.points ? g->bundles.points->pointBuffer() : g->bundles.noPoints.get();
    const VkBuffer splats = g->bundles.points ? g->bundles.points->splatBuffer() : g->bundles.noPoints.get();
    g->bound = vk::BoundSet(
        device, {vk::Bound::storageBuffer(shader::kMultibounceBindingLights, g->scene->lightBuffer()),
                 vk::Bound::storageImage(shader::kMultibounceBindingShadowMaps, g->lights.shadows->maps().view()),
                 vk::Bound::storageBuffer(shader::kMultibounceBindingEmitters, g->lights.emitters.get()),
                 vk::Bound::storageBuffer(shader::kMultibounceBindingPoints, points),
                 vk::Bound::storageBuffer(shader::kMultibounceBindingSplats, splats),
                 vk::Bound::storageBuffer(shader::kMultibounceBindingTextures, g->bundles.textures->buffer()),
                 vk::Bound::storageBuffer(shader::kMultibounceBindingEmitterPoints, g->lights.emitterPoints->buffer()),
                 vk::Bound::storageImage(shader::kMultibounceBindingEmitterShadowMaps, g->lights.emitterPoints->maps().view()),
                 vk::Bound::storageBuffer(shader::kMultibounceBindingEnvironmentShadows,
                                          g->lights.environmentShadows->buffer()),
                 vk::Bound::storageImage(shader::kMultibounceBindingEnvironmentShadowMaps,
                                         g->lights.environmentShadows->maps().view())});
    std::vector<std::uint32_t> specialization(shader::kMultibounceSpecCount);
    specialization[shader::kMultibounceSpecPointLights] = scene.lights.empty() ? 0u : 1u;
    specialization[shader::kMultibounceSpecEmitterPoints] = mPlan.runs(kPassEmitterPoints) ? 1u : 0u;
    specialization[shader::kMultibounceSpecEnvironment] = mPlan.runs(kPassEnvironmentShadows) ? 1u : 0u;
    gpu::appendMaterialSpecialization(specialization, scene.features());
    g->paths = vk::ComputePass<shader::MultibouncePush>(device, kSpv_modes_multibounce_paths_comp,
                                                        {g->camera->setLayout(), g->bound.layout()}, specialization);
    mGpu = std::move(g);
}

// Records the reset, the points (imperfect bundles), the builds and the sorts of iteration
// `iteration`'s K bundles: their directions and points depend on the iteration and seed only.
void MultibounceMode::recordBundles(VkCommandBuffer cmd, std::uint32_t iteration, const IterationInfo& info) {
    Gpu& g = *mGpu;
    const std::uint32_t slots = g.bundles.pool->slots();
    const std::uint32_t resolution = mOptions.bundleResolution;
    g.bundles.pool->recordReset(cmd);
    if (g.bundles.points) {
        g.bundles.points->record(cmd, static_cast<std::uint32_t>(info.seed), iteration, info.time, &g.timer);
    }
    std::vector<BundlePool::SlotBuild> builds(slots);
    for (std::uint32_t k = 0; k < slots; ++k) {
        const BundleDirection dir = g.bundles.directions->sample(iteration * slots + k);
        builds[k].slot = k;
        builds[k].frame =
            bundleFrameForSphere(dir.omega, dir.rotation, g.bundles.bounds.center(), g.bundles.bounds.radius(), resolution);
        builds[k].geometry = g.bundles.points ? BundleGeometry::pointSplats(g.bundles.points->splats(k), g.bundles.points->perDirection())
                                              : BundleGeometry::triangles(info.time);
    }
    g.bundles.pool->recordBuilds(cmd, builds, &g.timer);
    g.bundles.pool->recordSorts(cmd, 0, slots, &g.timer);
}

// Makes this iteration's K bundles: built at the end of the previous iteration's submission, or
// here in a submission of their own (the first iteration, after an overflow); grows the pool and
// builds again when they did not fit, and refuses what the limits cannot hold.
void MultibounceMode::buildBundles(const IterationInfo& info) {
    Gpu& g = *mGpu;
    if (g.bundles.prefetched.take(*g.bundles.pool, {mIterations, info.seed, info.time}, g.bundles.nodesLast,
                                  g.bundles.rebuilds)) {
        return;
    }
    g.bundles.nodesLast = buildFitting(*g.bundles.pool, {"multibounce", g.bundles.pool->slots(), mOptions.bundleResolution}, [&] {
        mContext->submitAndWait([&](VkCommandBuffer cmd) {
            g.timer.begin(cmd);
            recordBundles(cmd, mIterations, info);
        });
        g.timer.collect();
    }, g.bundles.rebuilds);
}

void MultibounceMode::iterate(const IterationInfo& info) {
    Gpu& g = sceneState(mGpu, name(), "iterate");
    if (!g.bundles.directions) {
        // The seed decorrelates runs; directions are reproducible from (settings, seed).
        g.bundles.directions = std::make_unique<DirectionSampler>(mOptions.directions, static_cast<std::uint32_t>(info.seed));
    }
    buildBundles(info);

    const std::uint32_t width = g.camera->width(), height = g.camera->height();
    const gpu::CameraSample sample = g.camera->sample(mIterations, true, info.time, info.seed);
    const bool renderShadows = mPlan.runs(kPassLightShadowCubes) && g.lights.shadows->refreshFor(*mContext, *g.scene, info.time);
    g.lights.emitterPoints->prepare(info.seed, mIterations, info.time);
    g.lights.environmentShadows->prepare(info.seed, mIterations);
    shader::MultibouncePush push{};
    push.pool = g.bundles.pool->view();
    push.width = width;
    push.height = height;
    push.seed = static_cast<std::uint32_t>(info.seed);
    push.iteration = mIterations;
    push.lightCount = g.lights.shadows->lightCount();
    push.shadowResolution = g.lights.shadows->resolution();
    push.emitterCount = g.lights.emitterCount;
    push.flags = (mPlan.runs(kPassEnvironment) ? shader::kMultibounceEnvironment : 0u) |
                 (mPlan.runs(kPassTextures) ? shader::kMultibounceTextured : 0u) |
                 (mOptions.splatUvCentre ? shader::kMultibounceSplatCentreUv : 0u) |
                 (distinctBundles() ? shader::kMultibounceDistinctBundles : 0u) |
                 (mOptions.emitterPointsOnly() ? shader::kMultibounceEmitterPointsOnly : 0u);
    push.environmentRotation = g.scene->environmentRotation();
    push.maxSegments = mOptions.maxSegments;
    push.rrSegments = mOptions.rrSegments;
    // Uniform directions: every direction of a hemisphere has the same density (the axis is arbitrary).
    push.hemispherePdf = g.bundles.directions->hemispherePdf(glm::vec3(0.0f, 0.0f, 1.0f));
    push.samplePosition = sample.samplePosition;
    push.pathsPerPixel = mOptions.pathsPerPixel;
    push.pointsPerDirection = g.bundles.points ? g.bundles.points->perDirection() : 0u;
    mContext->submitAndWait([&](VkCommandBuffer cmd) {
        g.timer.begin(cmd);
        if (renderShadows) {
            g.lights.shadows->record(cmd, info.time, &g.timer);
        }
        g.lights.emitterPoints->record(cmd, info.time, &g.timer);
        g.lights.environmentShadows->record(cmd, info.time, &g.timer);
        g.camera->record(cmd, sample, &g.timer);
        const VkDescriptorSet sets[] = {g.camera->set(), g.bound.set()};
        g.timer.timed(cmd, "paths", [&] {
            g.paths.dispatch(cmd, push, vk::groupCount(width, height, shader::kMultibounceGroupSize), sets);
        });
        vk::computeToHost(cmd);
        // The next iteration's bundles, once the paths have read these (and their splats).
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                              VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        recordBundles(cmd, mIterations + 1, info);
    });
    g.timer.collect();
    g.bundles.prefetched.check(*g.bundles.pool, {mIterations + 1, info.seed, info.time});
    ++mIterations;
}

ImageSet MultibounceMode::resolve() {
    Gpu& g = sceneState(mGpu, name(), "resolve");
    ImageSet out;
    out.iterations = mIterations; // each added paths_per_pixel samples per pixel
    gpu::AccumulatedImages estimate = g.camera->accumulator().resolve(*mContext, mIterations * mOptions.pathsPerPixel);
    out.layers = std::move(estimate.layers);
    addSampleLosses(out, estimate.nonFiniteSamples, estimate.droppedSamples, estimate.expectedSamples);
    out.counters.emplace_back("bundle_nodes_last", double(g.bundles.nodesLast));
    out.counters.emplace_back("bundle_pool_capacity", double(g.bundles.pool->capacity()));
    out.counters.emplace_back("bundle_pool_max_nodes", double(g.bundles.pool->maxNodes()));
    out.counters.emplace_back("bundle_rebuilds", double(g.bundles.rebuilds));
    return out;
}

PassTimes MultibounceMode::timings() const { return mGpu ? mGpu->timer.totals() : PassTimes{}; }

// Frames over the scene's sphere, with no fit setting: a path's later vertices lie anywhere in the
// scene, so a frame fitted to the camera's points would miss them.
TradeSettings MultibounceMode::trades() const {
    TradeSettings t = tradeSettingsOf(mSettings, kShadowResolution, kBundleResolution);
    t.bundleRule = BundleRule::ListAlongFacetPlanes; // hit payloads (splats: their discs' planes)
    // A path draws each of K <= 8 bundles once: it ends after K bundle segments and the direct
    // light at their last vertex, K + 2 segments in all, emitters too where emitter points light
    // that vertex; without them (emitter_sampling = bundles) emitters, and the sky always, are met
    // only at the end of a bundle segment, K + 1 at most (shaders/modes/multibounce/paths.comp.glsl).
    const std::uint32_t k = mOptions.bundleCount;
    const std::uint32_t longest = mOptions.maxSegments;
    if (distinctBundles() && k <= shader::kMultibounceRecentBundles && k + 2u < longest) {
        t.pathKey = kBundleCount;
        t.pathValue = k;
        t.pathSegments = k + 2u;
        t.pathSegmentsToEmitters = mOptions.emitterPointCount() > 0 ? k + 2u : k + 1u;
        t.pathSegmentsToSky = k + 1u;
        t.pathUncut = longest;
        t.pathUncutFrom = shader::kMultibounceRecentBundles + 1u;
        // K = 9..15 cut nothing but leave a path K - 8 bundles to draw from after 8 segments (K = 9:
        // one, a fixed cycle; rare after Russian roulette): 16 is the value to suggest.
        t.pathSuggested = 2u * shader::kMultibounceRecentBundles;
        if (mOptions.directions != DirectionSequence::Random) {
            t.pathNote = "with directions=halton a path that skips the bundles it used also skips their strata: "
                         "a further -2 to -4 % on the point-lit Cornell box (K = 2..8); directions=random has none";
        }
    }
    return t;
}

// Independent random directions: a path's bundles are drawn without replacement (exact). Halton
// directions are stratified within an iteration and drawn with replacement (the retro point mass,
// small at K >= 16: MultibounceShared.h), except for K <= 8, where that point mass outweighs the
// stratum a path would leave out (point-lit Cornell box, 32^2, 2048 directions, green image mean
// against 16384 spp: with replacement +2.4 / +6.8 / +11 % / x77 at K = 8 / 4 / 3 / 2; without
// -2.8 / -6.2 / -8.8 / -12 %, all of it the paths cut at K + 2 segments that SettingTrades states).
bool MultibounceMode::distinctBundles() const {
    return mOptions.directions == DirectionSequence::Random || mOptions.bundleCount <= shader::kMultibounceRecentBundles;
}

} // namespace bl
