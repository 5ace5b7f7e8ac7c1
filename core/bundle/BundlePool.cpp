#include "bundle/BundlePool.h"

#include "base/Error.h"
#include "vk/Check.h"
#include "bundle/BundleFrame.h"
#include "vk/Commands.h"

#include <algorithm>
#include <bundle/pool_count.frag.spv.h>
#include <bundle/pool_count_subgroup.frag.spv.h>
#include <bundle/pool_sort.comp.spv.h>
#include <bundle/pool_splats.frag.spv.h>
#include <bundle/pool_splats.vert.spv.h>
#include <bundle/pool_splats_subgroup.frag.spv.h>
#include <bundle/pool_stats.comp.spv.h>
#include <bundle/pool_triangles.frag.spv.h>
#include <bundle/pool_triangles.vert.spv.h>
#include <bundle/pool_triangles_exact.frag.spv.h>
#include <bundle/pool_triangles_exact_subgroup.frag.spv.h>
#include <bundle/pool_triangles_subgroup.frag.spv.h>
#include <cmath>

namespace bl {

namespace {
// Default pool before the first build has said what it needs: nodes per head entry.
constexpr std::uint64_t kInitialNodesPerPixel = 4;
// Growth after an overflow: what was asked for, plus headroom for the next directions.
constexpr double kGrowthFactor = 1.25;
// Without an explicit cap, the pool may take this fraction of the largest device-local heap: the
// rest stays for the G-buffer, textures, the scene and other processes sharing the device.
constexpr double kDefaultHeapFraction = 0.5;

constexpr VkBufferUsageFlags kAddressable =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
constexpr VkBufferUsageFlags kFilled = kAddressable | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
constexpr VkShaderStageFlags kDrawStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

bool fragmentSubgroups(const vk::Context& ctx) {
    VkPhysicalDeviceSubgroupProperties sub{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &sub};
    vkGetPhysicalDeviceProperties2(ctx.physicalDevice(), &props);
    const VkSubgroupFeatureFlags need = VK_SUBGROUP_FEATURE_BALLOT_BIT | VK_SUBGROUP_FEATURE_SHUFFLE_BIT;
    return (sub.supportedStages & VK_SHADER_STAGE_FRAGMENT_BIT) && (sub.supportedOperations & need) == need;
}

std::uint32_t payloadBytes(BundlePayload payload) {
    return payload == BundlePayload::Hit ? sizeof(shader::BundleHit) : 0u;
}

std::span<const std::uint32_t> spv(std::span<const std::uint32_t> s) { return s; }
} // namespace

vk::BoundSet makeTriangleBufferSet(VkDevice device, const gpu::GpuScene& scene, VkShaderStageFlags stages) {
    return vk::BoundSet(device,
                        {vk::Bound::storageBuffer(0, scene.planeBuffer()), vk::Bound::storageBuffer(1, scene.vertexBuffer()),
                         vk::Bound::storageBuffer(2, scene.indexBuffer())},
                        stages);
}

VkDeviceAddress deviceAddress(const vk::Context& ctx, const vk::Buffer& buffer) {
    if (!buffer.get()) return 0;
    VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    info.buffer = buffer.get();
    return vkGetBufferDeviceAddress(ctx.device(), &info);
}

glm::uvec2 splitAddress(VkDeviceAddress a) {
    return {static_cast<std::uint32_t>(a & 0xffffffffu), static_cast<std::uint32_t>(a >> 32)};
}

std::uint64_t BundlePool::bytesPerNode() const {
    return sizeof(shader::BundleNode) + payloadBytes(mOptions.payload) + (mOptions.sortable ? sizeof(std::uint32_t) : 0);
}

BundlePool::BundlePool(const vk::Context& ctx, const gpu::GpuScene& scene, const BundlePoolOptions& options)
    : mContext(&ctx), mScene(&scene), mOptions(options) {
    if (!ctx.bufferDeviceAddress()) {
        throw Error("bundles need bufferDeviceAddress (a Vulkan 1.3 feature) on '" + ctx.info().name + "'");
    }
    if (options.slots == 0 || options.slotPixels == 0) {
        throw Error("bundle pool: " + std::to_string(options.slots) + " slots of " +
                    std::to_string(options.slotPixels) + " pixels hold nothing");
    }
    mSubgroups = options.subgroupAllocation && fragmentSubgroups(ctx);
    // With gl_PrimitiveID (the geometryShader feature) depths are exact ray-plane intersections;
    // without it they are interpolated, within ~pixelSize / 512 * tan(incidence) of exact.
    mExactDepth = ctx.geometryShader();
    if (options.payload == BundlePayload::Hit && options.rasterized && !mExactDepth) {
        throw Error("the bundle hit payload needs the geometryShader feature (gl_PrimitiveID), which '" +
                    ctx.info().name + "' lacks");
    }

    // Limits, all from the device unless capped: one allocation, one buffer, and the sum of all.
    const std::uint64_t heads = std::uint64_t(options.slots) * options.slotPixels;
    const VkDeviceSize perBuffer = std::min(ctx.maxAllocationBytes(), ctx.maxBufferBytes());
    if (heads * sizeof(std::uint32_t) > perBuffer || heads > 0xffffffffull) {
        throw Error("bundle pool: " + std::to_string(options.slots) + " slots of " + std::to_string(options.slotPixels) +
                    " pixels need " + std::to_string(heads * 4) + " bytes of heads, more than one buffer of '" +
                    ctx.info().name + "' holds (" + std::to_string(perBuffer) + ")");
    }
    const std::uint64_t fixedBytes = heads * sizeof(std::uint32_t) + options.slots * sizeof(shader::BundleFrame);
    const auto heapShare = static_cast<std::uint64_t>(kDefaultHeapFraction * double(ctx.deviceLocalHeapBytes()));
    const std::uint64_t nodeBudget =
        options.memoryCapBytes ? options.memoryCapBytes : (heapShare > fixedBytes ? heapShare - fixedBytes : 0);
    const std::uint64_t widest = std::max<std::uint64_t>(sizeof(shader::BundleNode), payloadBytes(options.payload));
    mMaxNodes = nodeBudget / bytesPerNode();
    mMaxNodes = std::min<std::uint64_t>(mMaxNodes, perBuffer / widest);
    mMaxNodes = std::min<std::uint64_t>(mMaxNodes, shader::kBundleNil - 1);
    if (mMaxNodes < 1) {
        throw Error("bundle pool: a node budget of " + std::to_string(nodeBudget) + " bytes holds no node of " +
                    std::to_string(bytesPerNode()) + " bytes");
    }
    mFixedBytes = fixedBytes;
    ctx.requireDeviceMemory(fixedBytes, "bundle pool heads");
    mHeads = vk::Buffer(ctx, heads * sizeof(std::uint32_t), kFilled, vk::MemoryUse::Device);
    mFrames = vk::Buffer(ctx, options.slots * sizeof(shader::BundleFrame), kFilled, vk::MemoryUse::Device);
    mCounters = vk::Buffer(ctx, sizeof(shader::BundleCounters), kFilled, vk::MemoryUse::Device);
    mStatusCopy = vk::Buffer(ctx, sizeof(shader::BundleCounters), VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    allocateNodes(options.initialNodes ? options.initialNodes : kInitialNodesPerPixel * heads);

    VkDevice device = ctx.device();
    // Exact variants read the triangle's plane and corners (hit payload) by primitive id.
    mTriangles = makeTriangleBufferSet(device, scene, kDrawStages);
    VkDescriptorSetLayout layouts[] = {mTriangles.layout()};
    mDrawLayout = vk::makePipelineLayout(device, layouts, sizeof(shader::BundleDrawPush), kDrawStages);

    vk::GraphicsPipelineDesc desc; // no attachments, no depth test, no culling
    desc.layout = mDrawLayout.get();
    desc.specialization.assign(shader::kBundleSpecCount, 0u);
    desc.specialization[shader::kBundleSpecHitPayload] = options.payload == BundlePayload::Hit ? 1u : 0u;
    desc.vertexShader = kSpv_bundle_pool_triangles_vert;
    desc.vertexBindings = gpu::GpuScene::vertexBindings();
    desc.vertexAttributes = gpu::GpuScene::vertexAttributes();
    if (mExactDepth) {
        desc.fragmentShader = mSubgroups ? spv(kSpv_bundle_pool_triangles_exact_subgroup_frag)
                                         : spv(kSpv_bundle_pool_triangles_exact_frag);
    } else {
        desc.fragmentShader = mSubgroups ? spv(kSpv_bundle_pool_triangles_subgroup_frag)
                                         : spv(kSpv_bundle_pool_triangles_frag);
    }
    mTrianglePipeline = vk::makeGraphicsPipeline(device, desc);
    desc.vertexShader = kSpv_bundle_pool_splats_vert;
    desc.vertexBindings.clear();
    desc.vertexAttributes.clear();
    desc.fragmentShader = mSubgroups ? spv(kSpv_bundle_pool_splats_subgroup_frag) : spv(kSpv_bundle_pool_splats_frag);
    mSplatPipeline = vk::makeGraphicsPipeline(device, desc);
    desc.vertexShader = kSpv_bundle_pool_triangles_vert;
    desc.vertexBindings = gpu::GpuScene::vertexBindings();
    desc.vertexAttributes = gpu::GpuScene::vertexAttributes();
    desc.fragmentShader = mSubgroups ? spv(kSpv_bundle_pool_count_subgroup_frag) : spv(kSpv_bundle_pool_count_frag);
    mCountPipeline = vk::makeGraphicsPipeline(device, desc);
    mSort = vk::ComputePass<shader::BundlePoolPush>(device, kSpv_bundle_pool_sort_comp);
    mStats = vk::ComputePass<shader::BundlePoolPush>(device, kSpv_bundle_pool_stats_comp);
}

void BundlePool::allocateNodes(std::uint64_t nodes) {
    nodes = std::clamp<std::uint64_t>(nodes, 1, mMaxNodes);
    if (nodes == mCapacity) return;
    // Free before allocating: the old pool's contents are never needed again.
    mNodes = {};
    mPayload = {};
    mPrevious = {};
    // Everything the pool holds at once, not each buffer alone.
    mContext->requireDeviceMemory(mFixedBytes + nodes * bytesPerNode(),
                                  "bundle pool of " + std::to_string(nodes) + " nodes");
    mNodes = vk::Buffer(*mContext, nodes * sizeof(shader::BundleNode), kFilled, vk::MemoryUse::Device);
    if (const std::uint32_t bytes = payloadBytes(mOptions.payload)) {
        mPayload = vk::Buffer(*mContext, nodes * bytes, kFilled, vk::MemoryUse::Device);
    }
    if (mOptions.sortable) {
        mPrevious = vk::Buffer(*mContext, nodes * sizeof(std::uint32_t), kFilled, vk::MemoryUse::Device);
    }
    mCapacity = nodes;
}

bool BundlePool::grow(const BundlePoolStatus& status) {
    if (mCapacity >= mMaxNodes) return false;
    const auto wanted = static_cast<std::uint64_t>(std::ceil(double(status.requested) * kGrowthFactor));
    allocateNodes(std::max(wanted, mCapacity + 1));
    return true;
}

void BundlePool::checkSlot(std::uint32_t slot, const shader::BundleFrame& frame) const {
    if (slot >= mOptions.slots) {
        throw Error("bundle pool: slot " + std::to_string(slot) + " of " + std::to_string(mOptions.slots));
    }
    if (std::uint64_t(frame.width) * frame.height > mOptions.slotPixels || frame.width == 0 || frame.height == 0) {
        throw Error("bundle pool: a " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                    " frame does not fit a slot of " + std::to_string(mOptions.slotPixels) + " pixels");
    }
    const VkViewport v = bundleViewport(frame);
    const std::uint32_t* maxViewport = mContext->limits().maxViewportDimensions;
    if (frame.tileX + frame.width > frame.gridWidth || frame.tileY + frame.height > frame.gridHeight ||
        v.width > float(maxViewport[0]) || v.height > float(maxViewport[1])) {
        throw Error("bundle pool: a " + std::to_string(frame.width) + "x" + std::to_string(frame.height) + " tile at " +
                    std::to_string(frame.tileX) + "," + std::to_string(frame.tileY) + " of a " +
                    std::to_string(frame.gridWidth) + "x" + std::to_string(frame.gridHeight) +
                    " grid: outside the grid, or a grid beyond the device's viewport (" +
                    std::to_string(maxViewport[0]) + "x" + std::to_string(maxViewport[1]) + ")");
    }
}

void BundlePool::recordReset(VkCommandBuffer cmd) const {
    const shader::BundleCounters counters{0, static_cast<std::uint32_t>(mCapacity), 0, 0};
    vkCmdUpdateBuffer(cmd, mCounters.get(), 0, sizeof(counters), &counters);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                               VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    recordStatusCopy(cmd); // a reset with no build after it reads as empty
}

void BundlePool::recordBuild(VkCommandBuffer cmd, std::uint32_t slot, const shader::BundleFrame& frame,
                             const BundleGeometry& geometry, vk::GpuTimer* timer) const {
    const SlotBuild build{slot, frame, geometry};
    recordBuilds(cmd, std::span<const SlotBuild>(&build, 1), timer);
}

void BundlePool::recordBuilds(VkCommandBuffer cmd, std::span<const SlotBuild> builds, vk::GpuTimer* timer) const {
    if (mOptions.payload == BundlePayload::Hit && !mExactDepth) {
        throw Error("the bundle hit payload needs the geometryShader feature (gl_PrimitiveID) to be rasterized, which '" +
                    mContext->info().name + "' lacks: build with bundle_backend = compute");
    }
    // A slot twice would have its heads cleared after its first build's barrier had passed.
    std::vector<bool> seen(mOptions.slots, false);
    for (const SlotBuild& b : builds) {
        if (b.slot < seen.size() && seen[b.slot]) {
            throw Error("bundle pool: slot " + std::to_string(b.slot) + " twice in one batch of builds");
        }
        if (b.slot < seen.size()) seen[b.slot] = true;
    }
    for (const SlotBuild& b : builds) {
        recordSlotStart(cmd, b.slot, b.frame);
    }
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                      VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    for (const SlotBuild& b : builds) {
        const bool triangles = b.geometry.kind == shader::kBundleGeometryTriangles;
        recordRasterization(cmd, b.slot, b.frame, triangles ? b.geometry.time : 0.0,
                            triangles ? mTrianglePipeline.get() : VK_NULL_HANDLE, "bundle build", timer,
                            triangles ? nullptr : &b.geometry);
    }
    recordBatchEnd(cmd);
}

void BundlePool::recordCount(VkCommandBuffer cmd, const shader::BundleFrame& frame, double time,
                             vk::GpuTimer* timer) const {
    recordSlotStart(cmd, 0, frame);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                      VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    recordRasterization(cmd, 0, frame, time, mCountPipeline.get(), "rasterization floor", timer, nullptr);
    recordBatchEnd(cmd);
}

void BundlePool::recordSlotStart(VkCommandBuffer cmd, std::uint32_t slot, const shader::BundleFrame& frame) const {
    checkSlot(slot, frame);
    const VkDeviceSize headOffset = VkDeviceSize(slot) * mOptions.slotPixels * sizeof(std::uint32_t);
    const VkDeviceSize frameOffset = VkDeviceSize(slot) * sizeof(shader::BundleFrame);
    // The frame goes into the command stream, not a host-written buffer: every build recorded in
    // one command buffer sees its own.
    vkCmdUpdateBuffer(cmd, mFrames.get(), frameOffset, sizeof(frame), &frame);
    vkCmdFillBuffer(cmd, mHeads.get(), headOffset, VkDeviceSize(frame.width) * frame.height * sizeof(std::uint32_t),
                    shader::kBundleNil);
}

void BundlePool::recordRasterization(VkCommandBuffer cmd, std::uint32_t slot, const shader::BundleFrame& frame,
                                     double time, VkPipeline pipeline, const char* passName, vk::GpuTimer* timer,
                                     const BundleGeometry* splats) const {
    const VkDeviceSize headOffset = VkDeviceSize(slot) * mOptions.slotPixels * sizeof(std::uint32_t);
    const VkDeviceSize frameOffset = VkDeviceSize(slot) * sizeof(shader::BundleFrame);
    const std::uint32_t scope = timer ? timer->start(cmd, passName) : 0;
    vk::RenderTargets targets;
    targets.extent = {frame.width, frame.height};
    targets.viewport = bundleViewport(frame);
    vk::beginRendering(cmd, targets);
    shader::BundleDrawPush push{};
    push.frameAddress = splitAddress(deviceAddress(*mContext, mFrames) + frameOffset);
    push.headAddress = splitAddress(deviceAddress(*mContext, mHeads) + headOffset);
    push.nodeAddress = splitAddress(deviceAddress(*mContext, mNodes));
    push.payloadAddress = splitAddress(deviceAddress(*mContext, mPayload));
    push.counterAddress = splitAddress(deviceAddress(*mContext, mCounters));
    if (splats) {
        if (splats->splatCount > 0) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mSplatPipeline.get());
            push.splatAddress = splitAddress(splats->splats);
            push.model = glm::mat4(1.0f);
            vkCmdPushConstants(cmd, mDrawLayout.get(), kDrawStages, 0, sizeof(push), &push);
            vkCmdDraw(cmd, 3 * splats->splatCount, 1, 0, 0);
        }
    } else {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mDrawLayout.get(), 0, 1, mTriangles.sets().data(), 0, nullptr);
        mScene->bindGeometry(cmd);
        for (const gpu::GpuDraw& d : mScene->draws()) {
            push.model = mScene->modelMatrix(d.mesh, time);
            push.material = mScene->scene().meshes[d.mesh].material;
            push.firstPrimitive = d.firstIndex / 3;
            push.vertexOffset = static_cast<std::uint32_t>(d.vertexOffset);
            vkCmdPushConstants(cmd, mDrawLayout.get(), kDrawStages, 0, sizeof(push), &push);
            vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
        }
    }
    vkCmdEndRendering(cmd);
    if (timer) timer->stop(cmd, scope);
}

void BundlePool::recordBatchEnd(VkCommandBuffer cmd) const {
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                          VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT);
    recordStatusCopy(cmd);
}

void BundlePool::recordStatusCopy(VkCommandBuffer cmd) const {
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                               VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                      VK_PIPELINE_STAGE_2_TRANSFER_BIT);
    const VkBufferCopy region{0, 0, sizeof(shader::BundleCounters)};
    vkCmdCopyBuffer(cmd, mCounters.get(), mStatusCopy.get(), 1, &region);
    // The fence alone does not make device writes visible to host reads.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_HOST_BIT);
}

void BundlePool::recordSorts(VkCommandBuffer cmd, std::uint32_t first, std::uint32_t count, vk::GpuTimer* timer) const {
    if (count == 0 || first + count > slots()) {
        throw Error("bundle sort: slots " + std::to_string(first) + " + " + std::to_string(count) + " of a pool of " +
                    std::to_string(slots()));
    }
    const std::uint32_t scope = timer ? timer->start(cmd, "bundle sort") : 0;
    shader::BundlePoolPush push{};
    push.pool = view();
    push.slot = first; // the shader adds the workgroup's y
    mSort.dispatch(cmd, push, glm::uvec3(vk::groupCount(mOptions.slotPixels, shader::kBundleSortGroupSize), count, 1));
    if (timer) timer->stop(cmd, scope);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                          VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT);
}

void BundlePool::recordStatistics(VkCommandBuffer cmd, std::uint32_t slot, VkDeviceAddress stats,
                                  vk::GpuTimer* timer) const {
    const std::uint32_t scope = timer ? timer->start(cmd, "traverse all lists") : 0;
    shader::BundlePoolPush push{};
    push.pool = view();
    push.slot = slot;
    push.statsAddress = splitAddress(stats);
    mStats.dispatch(cmd, push, vk::groupCount(mOptions.slotPixels, shader::kBundleSortGroupSize));
    if (timer) timer->stop(cmd, scope);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT);
}

BundlePoolStatus BundlePool::status() const {
    shader::BundleCounters c{};
    mStatusCopy.download(*mContext, &c, sizeof(c)); // mapped: a plain copy
    BundlePoolStatus s;
    s.capacity = mCapacity;
    s.requested = std::uint64_t(c.allocated) + (std::uint64_t(c.excessHigh) << 32 | c.excessLow);
    return s;
}

shader::BundlePoolView BundlePool::view() const {
    shader::BundlePoolView v{};
    v.heads = splitAddress(deviceAddress(*mContext, mHeads));
    v.nodes = splitAddress(deviceAddress(*mContext, mNodes));
    v.payload = splitAddress(deviceAddress(*mContext, mPayload));
    v.frames = splitAddress(deviceAddress(*mContext, mFrames));
    v.counters = splitAddress(deviceAddress(*mContext, mCounters));
    v.previous = splitAddress(deviceAddress(*mContext, mPrevious));
    v.slotPixels = mOptions.slotPixels;
    v.slots = mOptions.slots;
    v.payloadKind = mOptions.payload == BundlePayload::Hit ? shader::kBundlePayloadHit : shader::kBundlePayloadNone;
    v.sorted = 0;
    return v;
}

std::vector<std::uint32_t> BundlePool::readHeads(std::uint32_t slot) const {
    std::vector<std::uint32_t> heads(mOptions.slotPixels);
    mHeads.download(*mContext, heads.data(), heads.size() * sizeof(std::uint32_t),
                    VkDeviceSize(slot) * mOptions.slotPixels * sizeof(std::uint32_t));
    return heads;
}

shader::BundleFrame BundlePool::readFrame(std::uint32_t slot) const {
    shader::BundleFrame f{};
    mFrames.download(*mContext, &f, sizeof(f), VkDeviceSize(slot) * sizeof(f));
    return f;
}

std::vector<shader::BundleNode> BundlePool::readNodes(std::uint64_t count) const {
    std::vector<shader::BundleNode> nodes(std::min(count, mCapacity));
    if (!nodes.empty()) mNodes.download(*mContext, nodes.data(), nodes.size() * sizeof(shader::BundleNode));
    return nodes;
}

std::vector<shader::BundleHit> BundlePool::readHits(std::uint64_t count) const {
    std::vector<shader::BundleHit> hits(mPayload.get() ? std::min(count, mCapacity) : 0);
    if (!hits.empty()) mPayload.download(*mContext, hits.data(), hits.size() * sizeof(shader::BundleHit));
    return hits;
}

std::vector<std::uint32_t> BundlePool::readPrevious(std::uint64_t count) const {
    std::vector<std::uint32_t> previous(mPrevious.get() ? std::min(count, mCapacity) : 0);
    if (!previous.empty()) mPrevious.download(*mContext, previous.data(), previous.size() * sizeof(std::uint32_t));
    return previous;
}

} // namespace bl
