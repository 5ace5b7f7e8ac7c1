// Mode atlas's device state, shared by the files of the mode (AtlasMode.cpp: scene set-up, one
// direction's build, exchange and update; AtlasResolve.cpp: the camera view; AtlasDirect.cpp:
// point/spot lights into the direct atlas; AtlasGlossy.cpp: the glossy passes).
#pragma once

#include "atlas/Atlas.h"
#include "atlas/AtlasLink.h"
#include "bundle/BundlePool.h"
#include "bundle/DirectionSampler.h"
#include "gpu/CameraPass.h"
#include "gpu/EmitterPointPass.h"
#include "gpu/ShadowCubePass.h"
#include "modes/atlas/AtlasMode.h"
#include "modes/atlas/AtlasTables.h"
#include "modes/atlas/AtlasViewPass.h"
#include "modes/atlas/DirectionOrder.h"
#include "sampling/EnvironmentLight.h"
#include "vk/ComputePass.h"
#include "vk/Descriptors.h"

namespace bl {

namespace atlasmode {
inline glm::uvec2 addressOf(const vk::Context& ctx, const vk::Buffer& b) { return splitAddress(deviceAddress(ctx, b)); }
// Storage buffers of the mode: read and written by address, filled and read back by transfers.
inline constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                              VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                              VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
} // namespace atlasmode

struct AtlasMode::Gpu {
    atlas::Atlas atlas;
    atlasmode::AtlasTables tables;
    std::unique_ptr<gpu::GpuScene> scene;
    std::unique_ptr<gpu::CameraPass> camera;
    std::unique_ptr<atlasmode::AtlasViewPass> view;
    std::unique_ptr<BundlePool> pool;
    std::unique_ptr<DirectionSampler> directions;
    std::unique_ptr<DirectionOrder> order; // the shuffled order (glossy transfer), with `directions`
    EnvironmentLight environment;
    std::unique_ptr<EnvironmentLight> importance; // luminance-sampled, for directions=importance
    std::unique_ptr<gpu::ShadowCubePass> shadows; // only with point or spot lights
    vk::Buffer texels, triangles, charts, sender, received, sums, directRadiance, settled;
    vk::Buffer samples, firstSample; // TexelSamples of the direct pass (with lights only)
    vk::Buffer direction; // AtlasDirection, host-written before each direction's submission
    // The sides each direction touched (AtlasTouched, the update's indirect dispatch) and the
    // interleaved transfer's sender records (AtlasSenderRecord; `sender` is bounce's).
    vk::Buffer touched, senders;
    // delay_indirect > 0: the multi-bounce channel's received words, sums and gather sums.
    bool split = false;
    vk::Buffer receivedIndirect, sumsIndirect, gatheredIndirect;
    // Glossy transfer with point/spot lights: (texel, first record) per glossy texel and the
    // lights' cached light at their samples (AtlasLightRecord).
    vk::Buffer glossyTexels, lightCache;
    std::uint32_t glossyTexelCount = 0;
    // Glossy materials (interleaved transfer only): the glossy transfer atlas rides in `received`;
    // the final gather's per-pixel sums and the view sample's point-light highlight per pixel.
    bool glossy = false, glossyTransfer = false, shuffleDirections = false;
    vk::Buffer materials, gathered, highlight;
    // The compute passes (shaders/modes/atlas/*.comp.glsl); direct, gather and highlight only where
    // the scene needs them (empty otherwise).
    vk::ComputePass<shader::AtlasExchangePush> exchangePass;
    vk::ComputePass<shader::AtlasUpdatePush> updatePass;
    vk::ComputePass<shader::AtlasShadePush> shadePass;
    vk::ComputePass<shader::AtlasDirectPush> directPass;
    vk::ComputePass<shader::AtlasGatherPush> gatherPass;
    vk::ComputePass<shader::AtlasHighlightPush> highlightPass;
    vk::DescriptorSetLayout viewSetLayout, directSetLayout;
    vk::DescriptorPool descriptorPool;
    VkDescriptorSet viewSet = VK_NULL_HANDLE, directSet = VK_NULL_HANDLE;
    // first_shot: the emitter points, the point/spot lights' part of the direct atlas kept apart
    // and the running sum of the shots (vec4 per texel side each).
    bool firstShot = false;
    std::unique_ptr<gpu::EmitterPointPass> emitterPoints;
    vk::Buffer pointDirect, shotSum;
    vk::DescriptorSetLayout firstShotSetLayout;
    VkDescriptorSet firstShotSet = VK_NULL_HANDLE;
    vk::ComputePass<shader::AtlasFirstShotPush> firstShotPass;
    atlas::AtlasLink link;
    vk::GpuTimer timer;
    Bounds bounds;
    std::uint32_t texelCount = 0;
    // Host wall clock of each direction's two submissions, beside the GPU timestamps: build + sort,
    // exchange + update (the bench's ms per direction include host submission and waits).
    PassTime wallBuild{"build + sort (wall)"}, wallExchange{"exchange + update (wall)"};
    std::uint64_t nodesLast = 0;
    std::uint64_t rebuilds = 0;
};

} // namespace bl
