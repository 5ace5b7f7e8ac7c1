#include "bundle/BundleBuilder.h"

#include "base/Error.h"
#include "base/Log.h"
#include "vk/Check.h"
#include "bundle/BundleFrame.h"
#include "vk/Commands.h"

#include <algorithm>
#include <bundle/build.frag.spv.h>
#include <bundle/build.vert.spv.h>
#include <bundle/build_subgroup.frag.spv.h>
#include <bundle/build_exact.frag.spv.h>
#include <bundle/build_exact_subgroup.frag.spv.h>
#include <bundle/count.frag.spv.h>
#include <bundle/count_subgroup.frag.spv.h>
#include <bundle/stats.comp.spv.h>
#include <cmath>
#include <cstring>

namespace bl {

namespace {
// Growth when a build overflows: what was asked for, plus headroom for the next directions.
constexpr double kGrowthFactor = 1.25;
constexpr std::uint32_t kStatsGroupSize = 64;
constexpr std::uint32_t kMaxTileDepth = 16;

VkDeviceAddress addressOf(const vk::Context& ctx, const vk::Buffer& b) {
    VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    info.buffer = b.get();
    return vkGetBufferDeviceAddress(ctx.device(), &info);
}

glm::uvec2 split(VkDeviceAddress a) {
    return {static_cast<std::uint32_t>(a & 0xffffffffu), static_cast<std::uint32_t>(a >> 32)};
}

bool fragmentSubgroups(const vk::Context& ctx) {
    VkPhysicalDeviceSubgroupProperties sub{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &sub};
    vkGetPhysicalDeviceProperties2(ctx.physicalDevice(), &props);
    const VkSubgroupFeatureFlags need = VK_SUBGROUP_FEATURE_BALLOT_BIT | VK_SUBGROUP_FEATURE_SHUFFLE_BIT;
    return (sub.supportedStages & VK_SHADER_STAGE_FRAGMENT_BIT) && (sub.supportedOperations & need) == need;
}

constexpr VkBufferUsageFlags kAddressable =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
} // namespace

std::uint32_t BundleBuilder::payloadBytes(BundlePayload payload) {
    switch (payload) {
    case BundlePayload::Shading: return sizeof(shader::BundleShading);
    case BundlePayload::Surface: return sizeof(shader::BundleSurface);
    default: return 0;
    }
}

BundleBuilder::BundleBuilder(const vk::Context& ctx, const gpu::GpuScene& scene, const BundleBuilderOptions& options)
    : mContext(&ctx), mScene(&scene), mOptions(options) {
    if (!ctx.bufferDeviceAddress()) {
        throw Error("bundles need bufferDeviceAddress (a Vulkan 1.3 feature) on '" + ctx.info().name + "'");
    }
    mSubgroups = options.subgroupAllocation && fragmentSubgroups(ctx);
    const std::uint64_t bytesPerNode = sizeof(shader::BundleNode) + payloadBytes(options.payload);
    // A single allocation is limited by the device too (2 GiB on lavapipe).
    const std::uint64_t allocationLimit = 0x7fffffffull;
    mCapNodes = std::min<std::uint64_t>(options.memoryCapBytes / bytesPerNode, allocationLimit / bytesPerNode);
    mCapNodes = std::min<std::uint64_t>(mCapNodes, shader::kBundleNil - 1);
    if (mCapNodes < 1) {
        throw Error("bundle memory cap of " + std::to_string(options.memoryCapBytes) + " bytes holds no node");
    }
    VkDevice device = ctx.device();
    mCounters = vk::Buffer(ctx, sizeof(shader::BundleCounters), kAddressable, vk::MemoryUse::Device);
    mFrame = vk::Buffer(ctx, sizeof(shader::BundleFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, vk::MemoryUse::Upload);
    mStats = vk::Buffer(ctx, 4 * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Device);
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT;
    // 0: frame, 1: materials, 2: list statistics, 3: triangle planes (exact depths).
    mSetLayout = vk::makeDescriptorSetLayout(device, {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, stages},
                                                      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, stages},
                                                      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, stages},
                                                      {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, stages}});
    mPool = vk::DescriptorPool(device, 2, 8);
    mSet = mPool.allocate(mSetLayout.get());
    vk::DescriptorWriter()
        .buffer(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, mFrame.get())
        .buffer(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene.materialBuffer())
        .buffer(2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, mStats.get())
        .buffer(3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, scene.planeBuffer())
        .update(device, mSet);
    VkDescriptorSetLayout layouts[] = {mSetLayout.get()};
    mPipelineLayout = vk::makePipelineLayout(device, layouts, sizeof(shader::BundleBuildPush), stages);

    vk::GraphicsPipelineDesc desc;
    desc.vertexShader = kSpv_bundle_build_vert;
    // With gl_PrimitiveID (the geometryShader feature) depths are exact ray-plane intersections;
    // without it they are interpolated, within ~pixelSize / 512 * tan(incidence) of exact.
    mExactDepth = ctx.geometryShader();
    if (options.payload == BundlePayload::Surface && !mExactDepth) {
        throw Error("the bundle surface payload needs the geometryShader feature (gl_PrimitiveID), which '" +
                    ctx.info().name + "' lacks");
    }
    if (mExactDepth) {
        desc.fragmentShader = mSubgroups ? std::span<const std::uint32_t>(kSpv_bundle_build_exact_subgroup_frag)
                                         : std::span<const std::uint32_t>(kSpv_bundle_build_exact_frag);
    } else {
        desc.fragmentShader = mSubgroups ? std::span<const std::uint32_t>(kSpv_bundle_build_subgroup_frag)
                                         : std::span<const std::uint32_t>(kSpv_bundle_build_frag);
    }
    desc.vertexBindings = gpu::GpuScene::vertexBindings();
    desc.vertexAttributes = gpu::GpuScene::vertexAttributes();
    desc.layout = mPipelineLayout.get(); // no attachments, no depth test, no culling
    mBuildPipeline = vk::makeGraphicsPipeline(device, desc);
    desc.fragmentShader = mSubgroups ? std::span<const std::uint32_t>(kSpv_bundle_count_subgroup_frag)
                                     : std::span<const std::uint32_t>(kSpv_bundle_count_frag);
    mCountPipeline = vk::makeGraphicsPipeline(device, desc);
    mStatsPipeline = vk::makeComputePipeline(device, kSpv_bundle_stats_comp, mPipelineLayout.get());
    mTimer = vk::GpuTimer(ctx);
}

void BundleBuilder::ensureCapacity(std::uint64_t nodes, std::uint32_t pixels) {
    const std::uint64_t headBytes = std::uint64_t(std::max(pixels, 1u)) * sizeof(std::uint32_t);
    if (!mHeads.get() || mHeads.size() < headBytes) {
        mHeads = vk::Buffer(*mContext, headBytes, kAddressable, vk::MemoryUse::Device);
    }
    nodes = std::min(std::max<std::uint64_t>(nodes, 1), mCapNodes);
    if (nodes <= mCapacity) {
        return;
    }
    const std::uint32_t payload = payloadBytes(mOptions.payload);
    mContext->requireDeviceMemory(nodes * (sizeof(shader::BundleNode) + payload) + headBytes, "bundle node pool");
    mNodes = vk::Buffer(*mContext, nodes * sizeof(shader::BundleNode), kAddressable, vk::MemoryUse::Device);
    mPayload = payload ? vk::Buffer(*mContext, nodes * payload, kAddressable, vk::MemoryUse::Device) : vk::Buffer();
    mCapacity = nodes;
}

BundleBuilder::Attempt BundleBuilder::buildOnce(const shader::BundleFrame& frame, double time, VkPipeline pipeline) {
    std::memcpy(mFrame.data(), &frame, sizeof(frame));
    const shader::BundleCounters counters{0, static_cast<std::uint32_t>(mCapacity), 0, 0};
    const std::uint32_t pixels = frame.width * frame.height;
    mContext->submitAndWait([&](VkCommandBuffer cmd) {
        mTimer.begin(cmd);
        vkCmdFillBuffer(cmd, mHeads.get(), 0, VkDeviceSize(pixels) * sizeof(std::uint32_t), shader::kBundleNil);
        vkCmdUpdateBuffer(cmd, mCounters.get(), 0, sizeof(counters), &counters);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
        std::uint32_t scope = mTimer.start(cmd, "bundle build");
        vk::RenderTargets targets;
        targets.extent = {frame.width, frame.height};
        vk::beginRendering(cmd, targets);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipelineLayout.get(), 0, 1, &mSet, 0, nullptr);
        mScene->bindGeometry(cmd);
        shader::BundleBuildPush push{};
        push.headAddress = split(addressOf(*mContext, mHeads));
        push.nodeAddress = split(addressOf(*mContext, mNodes));
        push.payloadAddress = mPayload.get() ? split(addressOf(*mContext, mPayload)) : glm::uvec2(0);
        push.counterAddress = split(addressOf(*mContext, mCounters));
        push.payloadKind = static_cast<std::uint32_t>(mOptions.payload);
        for (const gpu::GpuDraw& d : mScene->draws()) {
            push.model = mScene->modelMatrix(d.mesh, time);
            push.material = mScene->scene().meshes[d.mesh].material;
            push.firstTriangle = d.firstIndex / 3;
            push.vertexOffset = static_cast<std::uint32_t>(d.vertexOffset);
            vkCmdPushConstants(cmd, mPipelineLayout.get(),
                               VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT,
                               0, sizeof(push), &push);
            vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
        }
        vkCmdEndRendering(cmd);
        mTimer.stop(cmd, scope);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT |
                              VK_PIPELINE_STAGE_2_HOST_BIT);
    });
    mTimer.collect();
    double ms = 0.0;
    for (const PassTime& p : mTimer.totals()) ms += p.totalMs;
    mTimer.clearTotals();
    shader::BundleCounters result{};
    mCounters.download(*mContext, &result, sizeof(result));
    return {result.requested, ms};
}

void BundleBuilder::readStatistics(const shader::BundleFrame& frame, BundleStats& stats) {
    const std::uint32_t zero[4] = {0, 0, 0, 0};
    const std::uint32_t pixels = frame.width * frame.height;
    std::memcpy(mFrame.data(), &frame, sizeof(frame));
    mContext->submitAndWait([&](VkCommandBuffer cmd) {
        mTimer.begin(cmd);
        vkCmdUpdateBuffer(cmd, mStats.get(), 0, sizeof(zero), zero);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        std::uint32_t scope = mTimer.start(cmd, "traverse all lists");
        shader::BundleBuildPush push{};
        push.headAddress = split(addressOf(*mContext, mHeads));
        push.nodeAddress = split(addressOf(*mContext, mNodes));
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mStatsPipeline.get());
        VkDescriptorSet sets[] = {mSet};
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, mPipelineLayout.get(), 0, 1, sets, 0, nullptr);
        vkCmdPushConstants(cmd, mPipelineLayout.get(),
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT, 0,
                           sizeof(push), &push);
        vkCmdDispatch(cmd, vk::groupCount(pixels, kStatsGroupSize), 1, 1);
        mTimer.stop(cmd, scope);
    });
    mTimer.collect();
    for (const PassTime& p : mTimer.totals()) stats.traverseMs += p.totalMs;
    mTimer.clearTotals();
    std::uint32_t out[4];
    mStats.download(*mContext, out, sizeof(out));
    stats.nonEmptyPixels += out[0];
    stats.longestList = std::max(stats.longestList, out[1]);
}

void BundleBuilder::buildTiles(const shader::BundleFrame& frame, double time, std::uint32_t depth, BundleStats& stats,
                               const std::function<void(const BuiltBundle&)>& consume) {
    const std::uint32_t pixels = frame.width * frame.height;
    if (mCapacity == 0) {
        ensureCapacity(mOptions.initialNodes ? mOptions.initialNodes : 4ull * pixels, pixels);
    } else {
        ensureCapacity(mCapacity, pixels);
    }
    Attempt a = buildOnce(frame, time, mBuildPipeline.get());
    if (a.requested > mCapacity && mCapacity < mCapNodes) {
        // Grow to what this build needs (capped) and rebuild.
        ++stats.rebuilds;
        log::debug("bundle: " + std::to_string(a.requested) + " nodes needed, pool of " + std::to_string(mCapacity) +
                   ": growing and rebuilding");
        ensureCapacity(static_cast<std::uint64_t>(std::ceil(a.requested * kGrowthFactor)), pixels);
        a = buildOnce(frame, time, mBuildPipeline.get());
    }
    if (a.requested > mCapacity) {
        // Beyond the memory cap: split into tiles whose predicted needs fit, and build them in turn.
        if (depth >= kMaxTileDepth || pixels == 1) {
            throw Error("bundle: one tile of " + std::to_string(pixels) + " pixel(s) needs " +
                        std::to_string(a.requested) + " nodes, more than the memory cap allows (" +
                        std::to_string(mCapNodes) + ")");
        }
        ++stats.rebuilds;
        const double parts = std::ceil(double(a.requested) / double(mCapacity) * kGrowthFactor);
        const auto side = static_cast<std::uint32_t>(std::max(2.0, std::ceil(std::sqrt(parts))));
        const std::uint32_t tw = std::max(1u, (frame.width + side - 1) / side);
        const std::uint32_t th = std::max(1u, (frame.height + side - 1) / side);
        stats.tiles += side * side - 1;
        for (std::uint32_t y = 0; y < frame.height; y += th) {
            for (std::uint32_t x = 0; x < frame.width; x += tw) {
                buildTiles(bundleTile(frame, x, y, std::min(tw, frame.width - x), std::min(th, frame.height - y)),
                           time, depth + 1, stats, consume);
            }
        }
        return;
    }
    stats.fragments += a.requested;
    stats.buildMs += a.ms;
    if (mOptions.listStatistics) {
        readStatistics(frame, stats);
    }
    BuiltBundle built;
    built.frame = frame;
    built.heads = addressOf(*mContext, mHeads);
    built.nodes = addressOf(*mContext, mNodes);
    built.payload = mPayload.get() ? addressOf(*mContext, mPayload) : 0;
    built.fragments = a.requested;
    consume(built);
}

BundleStats BundleBuilder::build(const shader::BundleFrame& frame, double time,
                                 const std::function<void(const BuiltBundle&)>& consume) {
    BundleStats stats;
    buildTiles(frame, time, 0, stats, consume);
    return stats;
}

void BundleBuilder::readLists(const BuiltBundle& bundle, std::vector<std::uint32_t>& heads,
                              std::vector<shader::BundleNode>& nodes) const {
    heads.resize(std::size_t(bundle.frame.width) * bundle.frame.height);
    mHeads.download(*mContext, heads.data(), heads.size() * sizeof(std::uint32_t));
    nodes.resize(std::min<std::uint64_t>(bundle.fragments, mCapacity));
    if (!nodes.empty()) {
        mNodes.download(*mContext, nodes.data(), nodes.size() * sizeof(shader::BundleNode));
    }
}

std::uint64_t BundleBuilder::countFragments(const shader::BundleFrame& frame, double time, double* ms) {
    ensureCapacity(std::max<std::uint64_t>(mCapacity, 1), frame.width * frame.height);
    Attempt a = buildOnce(frame, time, mCountPipeline.get());
    if (ms) *ms = a.ms;
    return a.requested;
}

} // namespace bl
