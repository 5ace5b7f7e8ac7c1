#include "bundle/ComputeBundleRasterizer.h"

#include "base/Error.h"
#include "vk/Commands.h"

#include <algorithm>

#include <bundle/ComputeBuildShared.h>
#include <bundle/compute_clear.comp.spv.h>
#include <bundle/compute_triangles.comp.spv.h>

namespace bl {

namespace {
VkDeviceAddress join(glm::uvec2 v) { return VkDeviceAddress(v.x) | VkDeviceAddress(v.y) << 32; }
} // namespace

bool ComputeBundleRasterizer::supported(const vk::Context& ctx) {
    VkPhysicalDeviceFeatures features{};
    vkGetPhysicalDeviceFeatures(ctx.physicalDevice(), &features);
    return features.shaderInt64 == VK_TRUE;
}

ComputeBundleRasterizer::ComputeBundleRasterizer(const vk::Context& ctx, const gpu::GpuScene& scene)
    : mContext(&ctx), mScene(&scene) {
    if (!supported(ctx)) {
        throw Error("bundle_backend = compute needs shaderInt64, which '" + ctx.info().name + "' lacks");
    }
    VkDevice device = ctx.device();
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    mTriangleSet = makeTriangleBufferSet(device, scene, cs);
    std::uint32_t largestDraw = 1;
    for (const gpu::GpuDraw& d : scene.draws()) largestDraw = std::max(largestDraw, std::min(d.indexCount / 3, 65535u));
    mBig = vk::Buffer(ctx, sizeof(shader::BundleComputeBigHeader) + VkDeviceSize(largestDraw) * sizeof(std::uint32_t),
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                          VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      vk::MemoryUse::Device);
    mClear = vk::ComputePass<shader::BundleComputeClearPush>(device, kSpv_bundle_compute_clear_comp, {mTriangleSet.layout()});
    mTriangles = vk::ComputePass<shader::BundleComputePush>(device, kSpv_bundle_compute_triangles_comp,
                                                            {mTriangleSet.layout()});
}

void ComputeBundleRasterizer::record(VkCommandBuffer cmd, const BundlePool& pool, std::uint32_t slot,
                                     const shader::BundleFrame& frame, double time, vk::GpuTimer* timer) const {
    const std::uint32_t pixels = frame.width * frame.height;
    if (slot >= pool.slots() || pixels > pool.slotPixels() || pixels == 0) {
        throw Error("compute bundle build: slot " + std::to_string(slot) + " of " + std::to_string(pool.slots()) +
                    ", frame of " + std::to_string(pixels) + " pixels for slots of " +
                    std::to_string(pool.slotPixels()));
    }
    const shader::BundlePoolView view = pool.view();
    const VkDeviceAddress heads = join(view.heads) + VkDeviceAddress(slot) * pool.slotPixels() * sizeof(std::uint32_t);
    const VkDeviceAddress frames = join(view.frames) + VkDeviceAddress(slot) * sizeof(shader::BundleFrame);
    const std::uint32_t scope = timer ? timer->start(cmd, "bundle build (compute)") : 0;

    shader::BundleComputeClearPush clear{};
    clear.frame = frame;
    clear.frameAddress = splitAddress(frames);
    clear.headAddress = splitAddress(heads);
    clear.pixels = pixels;
    mClear.dispatch(cmd, clear, vk::groupCount(pixels, shader::kBundleComputeGroupSize));
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);

    shader::BundleComputePush push{};
    push.frameAddress = splitAddress(frames);
    push.headAddress = splitAddress(heads);
    push.nodeAddress = view.nodes;
    push.counterAddress = view.counters;
    push.payloadAddress = view.payload; // 0 without payload
    push.rowsPerBand = std::max(1u, shader::kBundleComputeBandPixels / frame.width);
    push.bands = (frame.height + push.rowsPerBand - 1) / push.rowsPerBand;
    push.bigAddress = splitAddress(deviceAddress(*mContext, mBig));
    const shader::BundleComputeBigHeader empty{vk::groupCount(push.bands, shader::kBundleComputeGroupSize), 0, 1, 0};
    // Draws in chunks of at most kChunk triangles: the big pass's indirect y count (the listed
    // triangles) stays within every device's maxComputeWorkGroupCount (65535).
    constexpr std::uint32_t kChunk = 65535;
    for (const gpu::GpuDraw& d : mScene->draws()) {
      push.modelRows = glm::mat3x4(glm::transpose(mScene->modelMatrix(d.mesh, time)));
      push.material = mScene->scene().meshes[d.mesh].material;
      push.vertexOffset = static_cast<std::uint32_t>(d.vertexOffset);
      for (std::uint32_t first = 0; first < d.indexCount / 3; first += kChunk) {
        push.firstPrimitive = d.firstIndex / 3 + first;
        push.triangleCount = std::min(kChunk, d.indexCount / 3 - first);
        // The previous draw's big pass read the list and its dispatch: reset them after it.
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                          VK_PIPELINE_STAGE_2_TRANSFER_BIT);
        vkCmdUpdateBuffer(cmd, mBig.get(), 0, sizeof(empty), &empty);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        push.pass = shader::kBundleComputeSmallPass;
        mTriangles.dispatch(cmd, push, vk::groupCount(push.triangleCount, shader::kBundleComputeGroupSize),
                            mTriangleSet.sets());
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT);
        push.pass = shader::kBundleComputeBigPass;
        mTriangles.dispatchIndirect(cmd, push, mBig.get(), 0, mTriangleSet.sets());
      }
    }
    if (timer) timer->stop(cmd, scope);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                          VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT);
    pool.recordStatusCopy(cmd);
}

} // namespace bl
