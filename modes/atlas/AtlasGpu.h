// Mode atlas's device state in parts, one per idea, each worked on by its file (AtlasMode.cpp: scene set-up, one
// direction's build, exchange and update; AtlasResolve.cpp: the camera view; AtlasDirect.cpp:
// point/spot lights into the direct atlas; AtlasGlossy.cpp: the glossy passes).
#pragma once

#include "atlas/Atlas.h"
#include "atlas/AtlasLink.h"
#include "bundle/BundlePool.h"
#include "bundle/EnvironmentShadowPass.h"
#include "bundle/DirectionSampler.h"
#include "bundle/FittingBuild.h"
#include "gpu/CameraPass.h"
#include "gpu/EmitterPointPass.h"
#include "gpu/ShadowCubePass.h"
#include "modes/atlas/AtlasMode.h"
#include "modes/atlas/AtlasTables.h"
#include "modes/atlas/AtlasViewPass.h"
#include "modes/atlas/DirectionOrder.h"
#include "sampling/EnvironmentLight.h"
#include "vk/ComputePass.h"
#include "vk/BoundSet.h"

namespace bl {

namespace atlasmode {
inline glm::uvec2 addressOf(const vk::Context& ctx, const vk::Buffer& b) { return splitAddress(deviceAddress(ctx, b)); }
// Storage buffers of the mode: read and written by address, filled and read back by transfers.
inline constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                              VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                              VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
} // namespace atlasmode

// The parts of the state, one per idea of the method; each file of the mode works on its part
// (and reads the link and the shared pieces).

// The atlas and its link to the scene ([HHGM10] §4): texels, charts, the triangle -> texel tables.
struct AtlasLinkState {
    atlas::Atlas atlas;
    atlasmode::AtlasTables tables;
    atlas::AtlasLink link;
    std::uint32_t texelCount = 0;
    vk::Buffer texels, triangles, charts;
};

// The radiance exchange (AtlasMode.cpp): one direction's bundle, the exchange along its lists and
// the update of the received sums ([HHGM10] Eq. 3, §5.1-5.2).
struct AtlasExchangeState {
    std::unique_ptr<BundlePool> pool;
    std::unique_ptr<DirectionSampler> directions;
    std::unique_ptr<DirectionOrder> order; // the shuffled order (glossy transfer), with `directions`
    EnvironmentLight environment;
    std::unique_ptr<EnvironmentLight> importance; // luminance-sampled, for directions=importance
    vk::Buffer sender, received, sums, settled;
    vk::Buffer direction; // AtlasDirection, host-written before each direction's submission
    // The sides each direction touched (AtlasTouched, the update's indirect dispatch) and the
    // interleaved transfer's sender records (AtlasSenderRecord; `sender` is bounce's).
    vk::Buffer touched, senders;
    // delay_indirect > 0: the multi-bounce channel's received words and sums.
    bool split = false;
    vk::Buffer receivedIndirect, sumsIndirect;
    vk::ComputePass<shader::AtlasExchangePush> exchangePass;
    vk::ComputePass<shader::AtlasUpdatePush> updatePass;
    // One submission and wait per direction: its exchange and update, then the next direction's
    // bundle (its frame is known ahead: direction and jitter depend on the index and seed only).
    PrefetchedBuild prefetched;
    // Host wall clock beside the GPU timestamps (the bench's ms per direction include host
    // submission and waits): a bundle built on its own, and each direction's submission.
    PassTime wallBuild{"build + sort (wall)"}, wallExchange{"direction (wall)"};
    std::uint64_t nodesLast = 0;
    std::uint64_t rebuilds = 0;
};

// The direct atlas (AtlasDirect.cpp: point/spot lights, [HHGM10] §6.5) and the first shot
// (AtlasFirstShot.cpp: area emitters by emitter points, the exchange then carrying reflected light).
struct AtlasDirectState {
    std::unique_ptr<gpu::ShadowCubePass> shadows; // only with point or spot lights
    vk::Buffer samples, firstSample;               // TexelSamples of the direct pass (with lights only)
    vk::Buffer directRadiance;
    vk::ComputePass<shader::AtlasDirectPush> directPass;
    vk::BoundSet directSet;
    // first_shot: the emitter points, the point/spot lights' part of the direct atlas kept apart
    // and the running sum of the shots (vec4 per texel side each).
    bool firstShot = false;
    std::unique_ptr<gpu::EmitterPointPass> emitterPoints; // no points where only the environment is shot
    vk::Buffer pointDirect, shotSum;
    vk::BoundSet firstShotSet;
    vk::ComputePass<shader::AtlasFirstShotPush> firstShotPass;
    // The environment's part: its directions and their depth maps (off without the environment's shot).
    std::unique_ptr<EnvironmentShadowPass> environmentShadows;
};

// The glossy passes (AtlasGlossy.cpp, [HHGM10] §5.3-5.4): the transfer atlas rides in the
// exchange's `received`; the final gather's per-pixel sums and the view sample's point-light
// highlight per pixel; interleaved transfer only.
struct AtlasGlossyState {
    bool gather = false, transfer = false, shuffleDirections = false;
    // Glossy transfer with point/spot lights: (texel, first record) per glossy texel and the lights'
    // cached light at their samples (AtlasLightRecord).
    vk::Buffer texels, lightCache;
    std::uint32_t texelCount = 0;
    vk::Buffer materials, gathered, gatheredIndirect, highlight;
    vk::ComputePass<shader::AtlasGatherPush> gatherPass;
    vk::ComputePass<shader::AtlasHighlightPush> highlightPass;
};

// The camera view (AtlasResolve.cpp): per view sample the G-buffer and the atlas lookup raster, then
// the shade pass.
struct AtlasViewState {
    std::unique_ptr<gpu::CameraPass> camera;
    std::unique_ptr<atlasmode::AtlasViewPass> lookup;
    vk::ComputePass<shader::AtlasShadePush> shadePass;
    vk::BoundSet bound;
};

struct AtlasMode::Gpu {
    std::unique_ptr<gpu::GpuScene> scene;
    AtlasLinkState link;
    AtlasExchangeState exchange;
    AtlasDirectState direct;
    AtlasGlossyState glossy;
    AtlasViewState view;
    vk::GpuTimer timer;
    Bounds bounds;
};

} // namespace bl
