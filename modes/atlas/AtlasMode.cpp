#include "modes/atlas/AtlasGpu.h"

#include "atlas/Atlas.h"
#include "atlas/AtlasLink.h"
#include "base/Error.h"
#include "base/Log.h"
#include "base/WallSpan.h"
#include "bundle/BundleFrame.h"
#include "bundle/FittingBuild.h"
#include "bundle/BundlePool.h"
#include "bundle/DirectionSampler.h"
#include "gpu/CameraPass.h"
#include "gpu/ShadowCubePass.h"
#include "modes/atlas/AtlasTables.h"
#include "modes/atlas/AtlasViewPass.h"
#include "modes/atlas/TexelSamples.h"
#include "sampling/EnvironmentLight.h"
#include "scene/Scene.h"
#include "scene/ShaderConversions.h"
#include "vk/Commands.h"
#include "vk/Descriptors.h"

#include <modes/atlas/AtlasShared.h>
#include <modes/atlas/direct.comp.spv.h>
#include <modes/atlas/exchange.comp.spv.h>
#include <modes/atlas/gather.comp.spv.h>
#include <modes/atlas/highlight.comp.spv.h>
#include <modes/atlas/shade.comp.spv.h>
#include <modes/atlas/update.comp.spv.h>
#include <shared/Random.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>

namespace bl {

using atlasmode::addressOf;
using atlasmode::kStorage;

namespace {
// First pool size in nodes per bundle pixel: closed rooms seen along a direction cross ~2-4
// surfaces per pixel inside the frame's disc; the pool grows to what a direction needs.
// Keys of the sub-pixel offset of each direction's grid: decorrelated from the direction's own
// numbers (DirectionSampler) by distinct hash keys.
constexpr std::uint32_t kGridKeyX = 0x68e31da4u;
constexpr std::uint32_t kGridKeyY = 0xb5297a4du;
// Device bytes per texel: texel table (32), received and glossy transfer (2 x 32), sums (2 x 32),
// direct (2 x 16), settled (2 x 16), chart (4), touched list (2 x 4), and either the sender
// records (interleaved, 2 x 48) or the sender (bounce, 2 x 16); split channels (delay_indirect)
// add received (2 x 16) and sums (2 x 32).
constexpr VkDeviceSize kBytesPerTexel = 32 + 64 + 64 + 32 + 32 + 4 + 8 + 96;
constexpr VkDeviceSize kSplitBytesPerTexel = 32 + 64;

// Whether any mesh or light is keyframed (a camera path alone leaves the atlas's solution valid).
bool movesOverTime(const Scene& scene) {
    for (const Mesh& m : scene.meshes) {
        if (m.animation.animated()) return true;
    }
    for (const Light& l : scene.lights) {
        if (l.animated()) return true;
    }
    return false;
}
} // namespace

std::unique_ptr<Mode> AtlasMode::create(const Settings& settings) { return std::make_unique<AtlasMode>(settings); }

AtlasMode::AtlasMode(const Settings& settings) : mSettings(settings), mOptions(atlasModeOptions(settings)) {}

AtlasMode::~AtlasMode() = default;

void AtlasMode::setScene(const Scene& scene, vk::Context* ctx) {
    mContext = &requireDevice(ctx, "atlas");
    mScene = &scene;
    mIterations = 0;
    mTotalWeight = 0.0;
    mPass = 1;
    mTime = 0.0;
    mPlan = plan(scene);
    if (!mOptions.bounce && mOptions.maxSegments != 0) {
        throw Error("atlas: max_segments needs transfer=bounce (interleaved transfer mixes path lengths in every "
                    "direction's sender)");
    }
    if (mOptions.bounce && mOptions.delayIndirect != 0) {
        throw Error("atlas: delay_indirect = " + std::to_string(mOptions.delayIndirect) +
                    " needs transfer=interleaved (bounce-by-bounce transfer sends direct light alone in its first "
                    "pass already)");
    }
    if (const FirstShotChoice shot = firstShotChoice(scene);
        mOptions.firstShot == "on" && !shot.conflict.empty()) {
        throw Error("atlas: first_shot = on needs transfer=interleaved, delay_indirect=0 and no glossy transport "
                    "(glossy=off or no glossy materials), here " + shot.conflict +
                    ": the shot's light does not yet enter a fixed pass sender, the one-bounce channel or the glossy "
                    "transfer atlas (first_shot = auto leaves the shot out there)");
    }
    mIndirectDirections = 0;
    mIndirectWeight = 0.0;
    mSolutionTime.reset();
    const auto width = static_cast<std::uint32_t>(scene.camera.resolution.x);
    const auto height = static_cast<std::uint32_t>(scene.camera.resolution.y);
    auto g = std::make_unique<Gpu>();

    atlas::AtlasOptions atlasOptions;
    atlasOptions.size = static_cast<int>(mOptions.atlasResolution);
    g->link.atlas = atlas::buildAtlas(scene, atlasOptions);
    // The generator leaves out triangles that found no texel and no room for a chart of their own
    // (sub-texel triangles of large scenes); the mode needs every triangle in the atlas.
    std::size_t inAtlas = 0;
    for (const std::vector<std::uint32_t>& sources : g->link.atlas.triangleSources) inAtlas += sources.size();
    if (inAtlas != scene.triangleCount()) {
        throw Error("atlas: " + std::to_string(scene.triangleCount() - inAtlas) + " of " +
                    std::to_string(scene.triangleCount()) + " triangles found no room in a " +
                    std::to_string(atlasOptions.size) + "^2 atlas (" + std::to_string(g->link.atlas.stats.charts) +
                    " charts, texels too coarse for them); raise atlas_resolution");
    }
    g->link.link = atlas::linkAtlas(scene, g->link.atlas);
    const atlas::AtlasLink& link = g->link.link;
    g->link.tables = atlasmode::buildAtlasTables(g->link.atlas, link);
    g->link.texelCount = static_cast<std::uint32_t>(g->link.tables.texels.size());
    log::info("atlas: " + std::to_string(g->link.atlas.maps.width) + "x" + std::to_string(g->link.atlas.maps.height) + " x " +
              std::to_string(g->link.atlas.maps.pages) + " page(s), " + std::to_string(g->link.atlas.stats.charts) +
              " charts, utilization " + std::to_string(g->link.atlas.stats.utilization));
    if (g->link.atlas.stats.isolatedTriangles > 0) {
        log::warn("atlas: " + std::to_string(g->link.atlas.stats.isolatedTriangles) +
                  " triangles are too thin for a texel of their own at atlas_resolution " +
                  std::to_string(atlasOptions.size) + " (slivers, or triangles crowded within a texel) and got " +
                  "charts of their own: " + std::to_string(g->link.atlas.maps.pages) +
                  " page(s); their texels see few hits each (noisy, not biased). Raise atlas_resolution or remesh");
    }
    if (g->link.tables.degenerateTriangles > 0) {
        log::warn("atlas: " + std::to_string(g->link.tables.degenerateTriangles) +
                  " triangles have no atlas area; their hits exchange nothing");
    }
    const auto lightSamples = static_cast<VkDeviceSize>(mOptions.lightSamples);
    const VkDeviceSize lightBytes = scene.lights.empty()
                                        ? 0
                                        : gpu::ShadowCubePass::bytesFor(mOptions.shadowResolution, scene.lights.size()) +
                                              VkDeviceSize(g->link.texelCount) * (lightSamples * lightSamples * 32 + 4);
    g->exchange.split = mPlan.runs(kPassDelayedIndirect);
    ctx->requireDeviceMemory(VkDeviceSize(g->link.texelCount) * (kBytesPerTexel + (g->exchange.split ? kSplitBytesPerTexel : 0)) +
                                 lightBytes +
                                 VkDeviceSize(width) * height *
                                     (gpu::CameraPass::bytesPerPixel(shader::kAtlasAccumLayers) + 16 + 4 +
                                      (scene.features().glossy ? 32 : 0)), // glossy gather + highlight
                             "atlas with " + std::to_string(g->link.texelCount) + " texels");

    g->scene = std::make_unique<gpu::GpuScene>(*ctx, scene, &link);
    g->view.camera = std::make_unique<gpu::CameraPass>(*ctx, *g->scene, width, height, shader::kAtlasAccumLayers);
    g->view.lookup = std::make_unique<atlasmode::AtlasViewPass>(*ctx, *g->scene, width, height);
    g->bounds = scene.bounds();
    g->exchange.environment = EnvironmentLight(scene.environment, false);
    if (mOptions.directions == DirectionSequence::Importance) {
        if (!scene.environment.present) {
            throw Error("atlas: directions=importance needs an environment in the scene");
        }
        g->exchange.importance = std::make_unique<EnvironmentLight>(scene.environment, true);
    }

    // One grid of R + 1 pixels a side: each direction's grid is shifted by a random sub-pixel
    // offset (below), and the extra pixel keeps the bounding sphere covered.
    const std::uint32_t resolution = mOptions.bundleResolution + 1;
    BundlePoolOptions options;
    options.slots = 1;
    options.slotPixels = resolution * resolution;
    options.payload = BundlePayload::Hit;
    options.sortable = true;
    options.initialNodes = std::uint64_t(mOptions.poolNodesPerPixel) * options.slotPixels;
    options.memoryCapBytes = mOptions.memoryCapBytes;
    g->exchange.pool = std::make_unique<BundlePool>(*ctx, *g->scene, options);
    // Per direction: first shot, exchange, glossy passes, update, the next bundle's build and sort;
    // per resolve submission kViewSamplesPerSubmission x (G-buffer, view raster, highlight, shade).
    constexpr std::uint32_t kScopes = 48;
    g->timer = vk::GpuTimer(*ctx, kScopes);

    const std::size_t texels = g->link.texelCount;
    g->link.texels = vk::makeBuffer(*ctx, std::span<const shader::AtlasTexel>(g->link.tables.texels), kStorage);
    g->link.triangles = vk::makeBuffer(*ctx, std::span<const shader::AtlasTriangle>(g->link.tables.triangles), kStorage);
    g->link.charts = vk::makeBuffer(*ctx, std::span<const std::int32_t>(g->link.tables.charts), kStorage);
    // Bounce: the sender starts as the emission (front sides); interleaved transfer keeps sender
    // records instead (written before the first direction). Sums and received start at zero.
    std::vector<glm::vec4> sender(mOptions.bounce ? shader::kAtlasSides * texels : 0, glm::vec4(0.0f));
    for (std::size_t t = 0; t < sender.size() / shader::kAtlasSides; ++t) {
        sender[shader::kAtlasSides * t + shader::kAtlasFront] = glm::vec4(g->link.tables.texels[t].emission, 0.0f);
    }
    g->exchange.sender = vk::makeBuffer(*ctx, std::span<const glm::vec4>(sender), kStorage);
    g->exchange.senders = vk::Buffer(*ctx, (mOptions.bounce ? 1 : shader::kAtlasSides * texels) * sizeof(shader::AtlasSenderRecord),
                            kStorage, vk::MemoryUse::Device);
    g->exchange.received = vk::makeBuffer(*ctx,
                                 std::span<const glm::vec4>(std::vector<glm::vec4>(
                                     shader::kAtlasSides * texels * shader::kAtlasReceivedWords / 4)),
                                 kStorage);
    g->direct.directRadiance = vk::makeBuffer(*ctx, std::span<const glm::vec4>(std::vector<glm::vec4>(shader::kAtlasSides * texels)),
                               kStorage);
    g->exchange.settled = vk::makeBuffer(*ctx, std::span<const glm::vec4>(std::vector<glm::vec4>(shader::kAtlasSides * texels)),
                                kStorage);
    g->exchange.sums = vk::makeBuffer(*ctx, std::span<const glm::vec4>(std::vector<glm::vec4>(2 * shader::kAtlasSides * texels)),
                             kStorage);
    const std::vector<glm::vec4> zeroSlots(shader::kAtlasSides * texels);
    std::vector<std::uint32_t> touched(shader::kAtlasTouchedHeader + shader::kAtlasSides * texels, 0u);
    touched[2] = touched[3] = 1u; // the update's indirect dispatch is (groups, 1, 1)
    g->exchange.touched = vk::makeBuffer(*ctx, std::span<const std::uint32_t>(touched), kStorage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
    if (g->exchange.split) {
        g->exchange.receivedIndirect = vk::makeBuffer(*ctx, std::span<const glm::vec4>(zeroSlots), kStorage);
        g->exchange.sumsIndirect =
            vk::makeBuffer(*ctx, std::span<const glm::vec4>(std::vector<glm::vec4>(2 * zeroSlots.size())), kStorage);
    }
    g->exchange.direction = vk::Buffer(*ctx, sizeof(shader::AtlasDirection),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                              vk::MemoryUse::Upload);

    VkDevice device = ctx->device();
    g->glossy.transfer = mPlan.runs(kPassGlossyTransfer);
    // The exchange's constants: the same fields directionParams and iterate() fill the direction's
    // split, glossy and transfer words from; the shader narrows those words by these (AtlasShared.h).
    std::array<std::uint32_t, shader::kAtlasSpecCount> exchangeSpec{};
    exchangeSpec[shader::kAtlasSpecSplit] = g->exchange.split ? 1u : 0u;
    exchangeSpec[shader::kAtlasSpecGlossy] = g->glossy.transfer ? 1u : 0u;
    exchangeSpec[shader::kAtlasSpecBounce] = mOptions.bounce ? 1u : 0u;
    g->exchange.exchangePass =
        vk::ComputePass<shader::AtlasExchangePush>(device, kSpv_modes_atlas_exchange_comp, {}, exchangeSpec);
    g->exchange.updatePass = vk::ComputePass<shader::AtlasUpdatePush>(device, kSpv_modes_atlas_update_comp);
    if (!scene.lights.empty()) {
        g->direct.shadows = std::make_unique<gpu::ShadowCubePass>(*ctx, *g->scene, mOptions.shadowResolution);
        g->direct.directSet = vk::BoundSet(
            device, {vk::Bound::storageBuffer(shader::kAtlasDirectBindingLights, g->scene->lightBuffer()),
                     vk::Bound::storageImage(shader::kAtlasDirectBindingShadowMaps, g->direct.shadows->maps().view())});
        g->direct.directPass =
            vk::ComputePass<shader::AtlasDirectPush>(device, kSpv_modes_atlas_direct_comp, {g->direct.directSet.layout()});
    }
    std::vector<shader::GpuMaterial> materials;
    for (const Material& m : scene.materials) materials.push_back(toGpuMaterial(m));
    if (materials.empty()) materials.emplace_back();
    g->glossy.materials = vk::makeBuffer(*ctx, std::span<const shader::GpuMaterial>(materials), kStorage);
    g->glossy.gather = mPlan.runs(kPassGlossyGather);
    // The shuffled direction order only where a mesh carries a glossy lobe: with none hit, the
    // transfer adds nothing and the directions stay those of the diffuse mode.
    const auto glossyMesh = [&](const Mesh& m) {
        return m.material < scene.materials.size() && scene.materials[m.material].glossy();
    };
    g->glossy.shuffleDirections =
        g->glossy.transfer && std::any_of(scene.meshes.begin(), scene.meshes.end(), glossyMesh);
    if (g->glossy.gather) {
        const std::vector<glm::vec4> pixels(std::size_t(width) * height);
        g->glossy.gathered = vk::makeBuffer(*ctx, std::span<const glm::vec4>(pixels), kStorage);
        if (g->exchange.split) {
            g->glossy.gatheredIndirect = vk::makeBuffer(*ctx, std::span<const glm::vec4>(pixels), kStorage);
        }
        g->glossy.gatherPass =
            vk::ComputePass<shader::AtlasGatherPush>(device, kSpv_modes_atlas_gather_comp, {g->view.camera->setLayout()});
        if (g->direct.shadows) {
            g->glossy.highlight = vk::makeBuffer(*ctx, std::span<const glm::vec4>(pixels), kStorage);
            g->glossy.highlightPass = vk::ComputePass<shader::AtlasHighlightPush>(
                device, kSpv_modes_atlas_highlight_comp, {g->view.camera->setLayout(), g->direct.directSet.layout()});
        }
    }
    g->view.bound = vk::BoundSet(device, {vk::Bound::storageImage(shader::kAtlasViewBinding, g->view.lookup->image().view())});
    g->view.shadePass = vk::ComputePass<shader::AtlasShadePush>(device, kSpv_modes_atlas_shade_comp,
                                                                {g->view.camera->setLayout(), g->view.bound.layout()});
    mGpu = std::move(g);
    setUpFirstShot(scene);
}

shader::BundleFrame AtlasMode::bundleFrame(std::uint32_t i, std::uint64_t seed) const {
    const Gpu& g = *mGpu;
    const std::uint32_t resolution = mOptions.bundleResolution;
    const BundleDirection dir = g.exchange.directions->sample(directionIndex(i));
    // A frame of R + 1 pixels of the R-pixel frame's size (radius scaled by (R + 1) / R), shifted
    // by a random sub-pixel offset in [-1/2, 1/2) pixel each way: it still covers the bounding
    // sphere, and every surface point's ray is uniformly placed within its pixel over directions
    // (the rotation alone leaves points near the frame's axis at a fixed phase), which the
    // per-texel pixel counts rely on.
    const float radius = g.bounds.radius() * float(resolution + 1) / float(resolution);
    shader::BundleFrame frame = bundleFrameForSphere(dir.omega, dir.rotation, g.bounds.center(), radius, resolution + 1);
    const auto key = static_cast<std::uint32_t>(seed);
    const float jx = shader::blHashRandom(key ^ kGridKeyX, i) - 0.5f;
    const float jy = shader::blHashRandom(key ^ kGridKeyY, i) - 0.5f;
    frame.origin -= (jx * frame.axisX + jy * frame.axisY) * frame.pixelSize;
    return frame;
}

void AtlasMode::recordBundle(VkCommandBuffer cmd, const shader::BundleFrame& frame, double time) {
    Gpu& g = *mGpu;
    g.exchange.pool->recordReset(cmd);
    g.exchange.pool->recordBuild(cmd, 0, frame, BundleGeometry::triangles(time), &g.timer);
    g.exchange.pool->recordSort(cmd, 0, &g.timer);
}

// Grows the pool and builds again when the bundle did not fit, and refuses what the limits cannot hold.
void AtlasMode::ensureBundle(const IterationInfo& info, const shader::BundleFrame& frame) {
    Gpu& g = *mGpu;
    if (g.exchange.prefetched.take(*g.exchange.pool, {mIterations, info.seed, info.time}, g.exchange.nodesLast,
                                   g.exchange.rebuilds)) {
        return;
    }
    g.exchange.nodesLast = buildFitting(*g.exchange.pool, {"atlas", 1, frame.width}, [&] {
        const WallSpan wall(g.exchange.wallBuild);
        mContext->submitAndWait([&](VkCommandBuffer cmd) {
            g.timer.begin(cmd);
            recordBundle(cmd, frame, info.time);
        });
        g.timer.collect();
    }, g.exchange.rebuilds);
}

shader::AtlasDirection AtlasMode::directionParams(const shader::BundleFrame& frame) const {
    const Gpu& g = *mGpu;
    shader::AtlasDirection params{};
    // Radiance arriving from +omega at the last hit of a list, from -omega at the first.
    // Bounce-by-bounce: the environment is a source, sent in pass 1 only (later passes send reflected light).
    // The environment's first shot has lit every texel directly: its list ends receive nothing.
    const bool environment =
        g.exchange.environment.present() && (!mOptions.bounce || mPass == 1) &&
        !(g.direct.environmentShadows && !g.direct.environmentShadows->off());
    params.environmentForward = environment ? g.exchange.environment.radiance(frame.direction) : glm::vec3(0.0f);
    params.environmentBackward = environment ? g.exchange.environment.radiance(-frame.direction) : glm::vec3(0.0f);
    const float density = g.exchange.directions->hemispherePdf(frame.direction);
    params.weight = frame.pixelSize * frame.pixelSize / (shader::kPi * density);
    params.inverseDensity = 1.0f / density;
    params.glossy = g.glossy.transfer ? 1u : 0u;  // as the exchange's kAtlasSpecGlossy (setScene)
    params.next = g.exchange.directions->sample(directionIndex(mIterations + 1)).omega;
    return params;
}

void AtlasMode::iterate(const IterationInfo& info) {
    Gpu& g = sceneState(mGpu, name(), "iterate");
    // The atlas holds one static solution: geometry and lights must stay where the first direction
    // saw them (a moving camera is fine: the view is rendered at the last direction's time).
    if (!mSolutionTime) {
        mSolutionTime = info.time;
        lightDirect(info.time);
    } else if (info.time != *mSolutionTime && movesOverTime(*mScene)) {
        throw Error("atlas: the scene's meshes or lights move (keyframes) and the scene time changed from " +
                    std::to_string(*mSolutionTime) + " to " + std::to_string(info.time) +
                    " s; the atlas holds one static solution: render a single scene time (--scene-time), not frames");
    }
    if (!g.exchange.directions) {
        // The seed decorrelates runs; directions are reproducible from (settings, seed).
        g.exchange.directions = std::make_unique<DirectionSampler>(mOptions.directions, static_cast<std::uint32_t>(info.seed),
                                                          mOptions.strata, g.exchange.importance.get(),
                                                          static_cast<float>(mOptions.importanceOffset));
        g.exchange.order = std::make_unique<DirectionOrder>(mOptions.directions, mOptions.strata,
                                                   static_cast<std::uint32_t>(info.seed));
    }
    mTime = info.time;
    mSeed = info.seed;
    if (mOptions.bounce && mOptions.maxSegments == 1) {
        ++mIterations; // emitters only: nothing is reflected
        return;
    }
    const shader::BundleFrame frame = bundleFrame(mIterations, info.seed);
    ensureBundle(info, frame);
    shader::AtlasDirection params = directionParams(frame);

    const std::uint32_t bundlePixels = g.exchange.pool->slotPixels();
    shader::AtlasExchangePush exchange{};
    exchange.pool = g.exchange.pool->view();
    exchange.texels = addressOf(*mContext, g.link.texels);
    exchange.triangles = addressOf(*mContext, g.link.triangles);
    exchange.received = addressOf(*mContext, g.exchange.received);
    exchange.direction = addressOf(*mContext, g.exchange.direction);
    exchange.materials = addressOf(*mContext, g.glossy.materials);
    exchange.width = static_cast<std::uint32_t>(g.link.atlas.maps.width);
    exchange.height = static_cast<std::uint32_t>(g.link.atlas.maps.height);
    exchange.pages = static_cast<std::uint32_t>(g.link.atlas.maps.pages);
    // Interleaved: direction j weighs j^k. Bounce: the sender is fixed within a pass, so its
    // directions weigh the same, and the pass's last direction settles it (the last pass allowed
    // by max_segments never settles: it keeps refining). Split: the one-bounce channel's sender
    // (emitters, environment) is fixed too, so it is the plain mean (j^k would only lose samples:
    // relMSE 2x higher at equal directions, measured); the multi-bounce channel weighs j^k, j
    // counted from its first direction.
    const double k = mOptions.weighting;
    const std::uint32_t passDirections = mOptions.bounceDirections;
    const double weight = mOptions.bounce || g.exchange.split ? 1.0 : std::pow(double(mIterations + 1), k);
    const bool indirect = g.exchange.split && mIterations >= mOptions.delayIndirect;
    const double weightIndirect = indirect ? std::pow(double(mIndirectDirections + 1), k) : 0.0;

    // How this direction's sender is formed: the estimate of the directions before it.
    params.texels = exchange.texels;
    params.senders = addressOf(*mContext, g.exchange.senders);
    params.fixedSender = addressOf(*mContext, g.exchange.sender);
    params.touched = addressOf(*mContext, g.exchange.touched);
    params.scale = mTotalWeight > 0.0 ? float(1.0 / mTotalWeight) : 0.0f;
    params.previous = mIterations - 1u; // the first direction: ~0u is the init pass's tag, whose stored glossy transfer is zero
    // transfer and split as the exchange's kAtlasSpecBounce and kAtlasSpecSplit (setScene)
    params.transfer = mOptions.bounce ? shader::kAtlasTransferBounce : shader::kAtlasTransferInterleaved;
    if (g.exchange.split) {
        params.split = 1u;
        params.sumsIndirect = addressOf(*mContext, g.exchange.sumsIndirect);
        params.receivedIndirect = addressOf(*mContext, g.exchange.receivedIndirect);
        params.indirectScale = mIndirectWeight > 0.0 ? float(1.0 / mIndirectWeight) : 0.0f;
        params.indirect = indirect ? 1u : 0u;
        params.weightIndirect = float(weightIndirect);
        params.clearIndirect = indirect && mIndirectWeight == 0.0 ? 1u : 0u;
    }
    std::memcpy(g.exchange.direction.data(), &params, sizeof(params));

    shader::AtlasUpdatePush update{};
    update.texels = exchange.texels;
    update.sender = params.fixedSender;
    update.received = exchange.received;
    update.sums = addressOf(*mContext, g.exchange.sums);
    update.texelCount = g.link.texelCount;
    update.weight = float(weight);
    update.inverseTotalWeight = float(1.0 / (mTotalWeight + weight));
    update.clearSums = mTotalWeight == 0.0 ? 1u : 0u;
    update.direct = addressOf(*mContext, g.direct.directRadiance);
    update.settled = addressOf(*mContext, g.exchange.settled);
    update.transfer = params.transfer;
    const bool lastPass = mOptions.maxSegments != 0 && mPass + 1 >= mOptions.maxSegments;
    update.settle = mOptions.bounce && !lastPass && std::uint32_t(mTotalWeight + weight) >= passDirections ? 1u : 0u;
    update.directIntoSender = mPass == 1 ? 1u : 0u;
    // A settling pass rewrites every side's sender; otherwise only the touched sides change.
    update.mode = update.settle != 0u ? shader::kAtlasUpdateAll : shader::kAtlasUpdateListed;
    update.touched = params.touched;
    update.senders = params.senders;
    update.receivedIndirect = params.receivedIndirect;
    update.sumsIndirect = params.sumsIndirect;
    update.weightIndirect = float(weightIndirect);
    update.iteration = mIterations;
    if (g.direct.firstShot) {
        g.direct.emitterPoints->prepare(info.seed, mIterations, info.time);
        g.direct.environmentShadows->prepare(info.seed, mIterations);
    }
    std::optional<WallSpan> wall(std::in_place, g.exchange.wallExchange);
    mContext->submitAndWait([&](VkCommandBuffer cmd) {
        g.timer.begin(cmd);
        const std::uint32_t slots = shader::kAtlasSides * g.link.texelCount;
        if (mIterations == 0 && !mOptions.bounce) { // the sender records' constant part, once
            shader::AtlasUpdatePush init = update;
            init.mode = shader::kAtlasUpdateInit;
            g.exchange.updatePass.dispatch(cmd, init, vk::groupCount(slots, shader::kAtlasGroupSize));
        }
        if (g.direct.firstShot) { // after the init: the shot rewrites the records' constant part
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
            recordFirstShot(cmd, info.time);
        }
        vkCmdFillBuffer(cmd, g.exchange.touched.get(), 0, 2 * sizeof(std::uint32_t), 0u); // count, groups
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        std::uint32_t scope = g.timer.start(cmd, "exchange");
        g.exchange.exchangePass.dispatch(cmd, exchange, vk::groupCount(bundlePixels, shader::kAtlasGroupSize));
        g.timer.stop(cmd, scope);
        if (g.glossy.transfer && g.direct.shadows && g.glossy.texelCount > 0) {
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
            recordGlossyLights(cmd);
        }
        if (g.glossy.gather) {
            recordGather(cmd, weight);
        }
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT);
        scope = g.timer.start(cmd, "update");
        if (update.mode == shader::kAtlasUpdateListed) {
            g.exchange.updatePass.dispatchIndirect(cmd, update, g.exchange.touched.get(), shader::kAtlasTouchedDispatchOffset);
        } else {
            g.exchange.updatePass.dispatch(cmd, update, vk::groupCount(slots, shader::kAtlasGroupSize));
        }
        g.timer.stop(cmd, scope);
        vk::computeToHost(cmd);
        // The next direction's bundle, once this one's exchange and gather have read its lists.
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                              VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        recordBundle(cmd, bundleFrame(mIterations + 1, info.seed), info.time);
    });
    g.timer.collect();
    wall.reset();
    // Whether the next direction's bundle fit: if not, the pool grows now and that direction
    // builds on its own (ensureBundle; where the pool cannot grow, that build says why).
    g.exchange.prefetched.check(*g.exchange.pool, {mIterations + 1, info.seed, info.time});
    mTotalWeight += weight;
    if (indirect) {
        mIndirectWeight += weightIndirect;
        ++mIndirectDirections;
    }
    if (update.settle != 0u) {
        ++mPass;
        mTotalWeight = 0.0;
    }
    ++mIterations;
}

AtlasMode::TexelReadback AtlasMode::readTexels() const {
    const Gpu& g = sceneState(mGpu, name(), "readTexels");
    const std::size_t slots = shader::kAtlasSides * g.link.texelCount;
    std::vector<glm::vec4> sums(2 * slots), settled(slots), direct(slots);
    g.exchange.sums.download(*mContext, sums.data(), sums.size() * sizeof(glm::vec4));
    g.exchange.settled.download(*mContext, settled.data(), settled.size() * sizeof(glm::vec4));
    g.direct.directRadiance.download(*mContext, direct.data(), direct.size() * sizeof(glm::vec4));
    const float scale = mTotalWeight > 0.0 ? float(1.0 / mTotalWeight) : 0.0f;
    TexelReadback out;
    out.reflected.resize(slots);
    for (std::size_t s = 0; s < slots; ++s) {
        out.reflected[s] = glm::vec3(sums[2 * s] + sums[2 * s + 1]) * scale + glm::vec3(settled[s]) +
                           mOptions.directScale() * glm::vec3(direct[s]);
    }
    if (g.exchange.split) { // the multi-bounce channel
        g.exchange.sumsIndirect.download(*mContext, sums.data(), sums.size() * sizeof(glm::vec4));
        const float indirectScale = mIndirectWeight > 0.0 ? float(1.0 / mIndirectWeight) : 0.0f;
        for (std::size_t s = 0; s < slots; ++s) {
            out.reflected[s] += glm::vec3(sums[2 * s] + sums[2 * s + 1]) * indirectScale;
        }
    }
    for (const shader::AtlasTexel& t : g.link.tables.texels) {
        out.emission.push_back(t.emission);
        out.area.push_back(t.inverseArea > 0.0f ? 1.0f / t.inverseArea : 0.0f);
    }
    return out;
}

const atlas::Atlas& AtlasMode::atlas() const { return sceneState(mGpu, name(), "atlas").link.atlas; }

atlas::TexelRadiance AtlasMode::texelRadiance() const {
    const TexelReadback texels = readTexels();
    atlas::TexelRadiance out = atlas::TexelRadiance::like(texelMaps());
    for (std::size_t t = 0; t < out.texels(); ++t) {
        for (std::uint32_t side = 0; side < shader::kAtlasSides; ++side) {
            out.side[side][t] = texels.reflected[shader::kAtlasSides * t + side];
        }
    }
    return out;
}

glm::vec3 AtlasMode::direction(std::uint32_t i) const {
    if (!mGpu || !mGpu->exchange.directions) {
        throw Error("atlas: direction() before the first iterate()");
    }
    return mGpu->exchange.directions->sample(directionIndex(i)).omega;
}

std::uint32_t AtlasMode::directionIndex(std::uint32_t i) const {
    const Gpu& g = *mGpu;
    return g.glossy.shuffleDirections ? (*g.exchange.order)(i) : i;
}


PassTimes AtlasMode::timings() const {
    if (!mGpu) return {};
    PassTimes t = mGpu->timer.totals();
    t.push_back(mGpu->exchange.wallBuild);
    t.push_back(mGpu->exchange.wallExchange);
    return t;
}

TradeSettings AtlasMode::trades() const {
    TradeSettings t = tradeSettingsOf(mSettings, kShadowResolution, kBundleResolution);
    t.bundleRule = BundleRule::DepthMapNearestLight;
    return t;
}

} // namespace bl
