// A pool of K resident global ray-bundles ([RB 1], papers/EQUATIONS.md), recorded by the mode into its
// own command buffers: one node pool, one allocator and K head slices, so a mode can build many
// bundles in one submission and keep all of them for later passes (multibounce reuses K
// omnidirectional bundles per frame; bidir builds one per VPL pair; atlas one per direction).
//
// Usage, per command buffer:
//   pool.recordReset(cmd);                       // the allocator starts empty
//   pool.recordBuild(cmd, slot, frame, geometry); // for any slots, triangles or point splats
//                                                 // (recordBuilds: several slots, one set of barriers)
//   pool.recordSort(cmd, slot);                  // optional: depth order + O(1) neighbours
//                                                 // (recordSorts: consecutive slots, one dispatch)
//   ... consumer passes read pool.view() and skip their work if blBundlePoolOverflowed() ...
// then, after the fence: status() says whether the builds fit; if not, grow() and redo the
// iteration (nothing partial may be kept). BundleBuilder wraps this into grow-and-tile for modes
// that want one bundle at a time with no overflow handling of their own.
//
// Memory: every limit comes from the device (largest device-local heap, maxMemoryAllocationSize,
// maxBufferSize) or from an explicit cap; the sum of heads, nodes, payload and links is checked
// before anything is allocated.
#pragma once

#include "gpu/GpuScene.h"
#include "vk/Buffer.h"
#include "vk/BoundSet.h"
#include "vk/GpuTimer.h"
#include "vk/ComputePass.h"
#include "vk/Pipeline.h"

#include <shared/BundleTypes.h>
#include <span>
#include <vector>

namespace bl {

enum class BundlePayload {
    None, // depth + face only (visibility)
    Hit,  // + normal, material, texture UV, triangle or point id, barycentrics, facet plane (BundleHit)
};

// What a bundle is built from: the scene's triangles at a time, or point splats in a device buffer
// (imperfect bundles).
struct BundleGeometry {
    std::uint32_t kind = shader::kBundleGeometryTriangles;
    double time = 0.0;                // triangles: scene time
    VkDeviceAddress splats = 0;       // splats: BundleSplat array
    std::uint32_t splatCount = 0;

    static BundleGeometry triangles(double time) { return {shader::kBundleGeometryTriangles, time, 0, 0}; }
    static BundleGeometry pointSplats(VkDeviceAddress splats, std::uint32_t count) {
        return {shader::kBundleGeometrySplats, 0.0, splats, count};
    }
};

struct BundlePoolOptions {
    std::uint32_t slots = 1;          // bundles resident at once
    std::uint32_t slotPixels = 0;     // head entries per slot: the largest frame's width * height
    std::uint64_t initialNodes = 0;   // 0: 4 per slot pixel per slot
    BundlePayload payload = BundlePayload::None;
    bool sortable = false;            // keep a predecessor per node for O(1) backward steps
    std::uint64_t memoryCapBytes = 0; // cap on node storage (nodes + payload + links); 0: half the
                                      // largest device-local heap, less the heads
    bool subgroupAllocation = true;   // one atomic per subgroup where the device allows it
    bool rasterized = true;           // built by recordBuild (a hit payload needs gl_PrimitiveID
                                      // there); false: by ComputeBundleRasterizer, which needs none
};

// The allocator's state after the builds of one command buffer completed.
struct BundlePoolStatus {
    std::uint64_t requested = 0; // nodes every build since recordReset asked for (exact, 64-bit)
    std::uint64_t capacity = 0;
    bool overflowed() const { return requested > capacity; }
};

// The scene's triangles as the exact builds read them by primitive id: storage buffers at binding
// 0 (planes), 1 (vertices) and 2 (indices) of one descriptor set (BundlePool, ComputeBundleRasterizer).
vk::BoundSet makeTriangleBufferSet(VkDevice device, const gpu::GpuScene& scene, VkShaderStageFlags stages);

class BundlePool {
public:
    // `scene` provides the triangles (and the planes for exact depths); it must outlive the pool.
    BundlePool(const vk::Context& ctx, const gpu::GpuScene& scene, const BundlePoolOptions& options);

    void recordReset(VkCommandBuffer cmd) const;
    void recordBuild(VkCommandBuffer cmd, std::uint32_t slot, const shader::BundleFrame& frame,
                     const BundleGeometry& geometry, vk::GpuTimer* timer = nullptr) const;
    // One slot's build of a batch.
    struct SlotBuild {
        std::uint32_t slot = 0;
        shader::BundleFrame frame{};
        BundleGeometry geometry;
    };
    // The builds of several slots (distinct), as recordBuild each, but with one barrier before
    // their rasterizations and one after, and one status copy: builds of different slots share
    // only the node allocator, whose atomics need no barrier between them. A timer scope per slot.
    void recordBuilds(VkCommandBuffer cmd, std::span<const SlotBuild> builds, vk::GpuTimer* timer = nullptr) const;
    // The benchmark floor: the same rasterization of the scene's triangles, counting fragments
    // (into the allocator: status().requested) and storing nothing.
    void recordCount(VkCommandBuffer cmd, const shader::BundleFrame& frame, double time,
                     vk::GpuTimer* timer = nullptr) const;
    // Sorts slots first .. first + count - 1 in one dispatch (one timer scope and barrier for all:
    // a mode that sorts its K bundles pays the per-dispatch cost once, not K times).
    void recordSorts(VkCommandBuffer cmd, std::uint32_t first, std::uint32_t count, vk::GpuTimer* timer = nullptr) const;
    void recordSort(VkCommandBuffer cmd, std::uint32_t slot, vk::GpuTimer* timer = nullptr) const {
        recordSorts(cmd, slot, 1, timer);
    }
    // Walks every list of the slot once, adding into the BundleListStats at `stats` (the buffer
    // must be zeroed before).
    void recordStatistics(VkCommandBuffer cmd, std::uint32_t slot, VkDeviceAddress stats,
                          vk::GpuTimer* timer = nullptr) const;

    // After the fence of the command buffer with the builds: read from a host-visible copy that
    // every reset and build records at its end (no submit of its own: on a GPU, a download per build
    // (staging allocation, submit, wait) cost more than the build).
    BundlePoolStatus status() const;
    // Records the copy of the allocator's counters that status() reads (recordReset, recordBuild and
    // the compute backend's builds call it; callable after any other pass that allocates nodes).
    void recordStatusCopy(VkCommandBuffer cmd) const;
    // Grows the node pool to what `status` asked for plus headroom, within the limits. False when
    // the limits do not allow it (the caller must split its work, e.g. into tiles). Contents are lost.
    bool grow(const BundlePoolStatus& status);

    shader::BundlePoolView view() const;
    std::uint32_t slots() const { return mOptions.slots; }
    std::uint32_t slotPixels() const { return mOptions.slotPixels; }
    std::uint64_t capacity() const { return mCapacity; }
    std::uint64_t maxNodes() const { return mMaxNodes; }
    BundlePayload payload() const { return mOptions.payload; }
    bool exactDepths() const { return mExactDepth; }
    bool usesSubgroups() const { return mSubgroups; }
    std::uint64_t bytesPerNode() const;

    // Host copies (tests, debugging): a slot's heads and frame, the node pool, the payload, links.
    std::vector<std::uint32_t> readHeads(std::uint32_t slot) const;
    shader::BundleFrame readFrame(std::uint32_t slot) const;
    std::vector<shader::BundleNode> readNodes(std::uint64_t count) const;
    std::vector<shader::BundleHit> readHits(std::uint64_t count) const;
    std::vector<std::uint32_t> readPrevious(std::uint64_t count) const;

private:
    void allocateNodes(std::uint64_t nodes);
    void checkSlot(std::uint32_t slot, const shader::BundleFrame& frame) const;
    // The slot's frame into the frame buffer and its heads cleared (before the batch's barrier).
    void recordSlotStart(VkCommandBuffer cmd, std::uint32_t slot, const shader::BundleFrame& frame) const;
    // The slot's rasterization: the scene's triangles at `time` with `pipeline`, or `splats`.
    void recordRasterization(VkCommandBuffer cmd, std::uint32_t slot, const shader::BundleFrame& frame, double time,
                             VkPipeline pipeline, const char* passName, vk::GpuTimer* timer,
                             const BundleGeometry* splats) const;
    // After a batch: its writes visible to every later stage, and the status copy.
    void recordBatchEnd(VkCommandBuffer cmd) const;

    const vk::Context* mContext;
    const gpu::GpuScene* mScene;
    BundlePoolOptions mOptions;
    bool mSubgroups = false;
    bool mExactDepth = false;
    std::uint64_t mMaxNodes = 0;
    std::uint64_t mFixedBytes = 0; // heads + frames
    std::uint64_t mCapacity = 0;
    vk::Buffer mHeads;
    vk::Buffer mFrames;
    vk::Buffer mCounters;
    vk::Buffer mStatusCopy; // host-visible: the counters as of the last recorded reset or build
    vk::Buffer mNodes;
    vk::Buffer mPayload;
    vk::Buffer mPrevious;
    vk::BoundSet mTriangles;
    vk::PipelineLayout mDrawLayout;
    vk::Pipeline mTrianglePipeline;
    vk::Pipeline mSplatPipeline;
    vk::Pipeline mCountPipeline;
    vk::ComputePass<shader::BundlePoolPush> mSort;
    vk::ComputePass<shader::BundlePoolPush> mStats;
};

// Device address of a buffer created with VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT.
VkDeviceAddress deviceAddress(const vk::Context& ctx, const vk::Buffer& buffer);
// A 64-bit address as the two words shaders take (no 64-bit integer types needed there).
glm::uvec2 splitAddress(VkDeviceAddress address);

} // namespace bl
