// Perfect global ray-bundles one at a time, with no overflow handling left to the caller: a
// grow-and-tile wrapper around a one-slot BundlePool (BundlePool.h), for modes like skylight that
// consume each bundle before building the next.
//
// Never loses a fragment: the build counts the nodes it needs; when they exceed the pool, the pool
// grows and the bundle is rebuilt; when they exceed the memory cap, the frame is split into tiles
// built (and consumed) one after another, a tile that still overflows splits again. Every
// overflow is reported in the stats.
#pragma once

#include "bundle/BundlePool.h"
#include "bundle/ComputeBundleRasterizer.h"

#include <functional>
#include <memory>

namespace bl {

// Who rasterizes the triangles: the graphics pipeline (BundlePool::recordBuild) or compute
// shaders (ComputeBundleRasterizer: triangles, the same nodes and hit payload).
enum class BundleBackend { Raster, Compute };

// The backend a setting names: "raster", "compute", or "auto": compute where it was measured
// faster (a CPU device, lavapipe, where it can run), raster on GPUs (experiments/gpu/README.md).
// One rule for the modes that choose (skylight) and for `bundlelab bench bundles`.
BundleBackend chooseBundleBackend(const vk::Context& ctx, const std::string& setting);

struct BundleBuilderOptions {
    BundlePayload payload = BundlePayload::None;
    std::uint64_t initialNodes = 0;          // pool size at start (0: 4 per pixel of the first frame)
    std::uint64_t memoryCapBytes = 1ull << 30; // pool (+ payload) never exceeds this
    bool subgroupAllocation = true;          // used when the device supports it
    BundleBackend backend = BundleBackend::Raster;
    bool listStatistics = false;             // longest list, non-empty pixels (one extra pass that
                                             // walks every list: also the traversal benchmark)
};

// A built bundle (or one tile of it), valid during the consumer callback.
struct BuiltBundle {
    shader::BundleFrame frame;
    VkDeviceAddress heads = 0;
    VkDeviceAddress nodes = 0;
    VkDeviceAddress payload = 0;
    VkDeviceAddress counters = 0; // the allocator's BundleCounters: blBundlePoolOverflowed
    std::uint64_t fragments = 0;  // 0 while recorded with the build (recordWithBuild)
};

// Work recorded into the build's own submission, after the build (one submit and wait for both).
// It runs for every attempt, an overflowed one too, so it must test blBundlePoolOverflowed on the
// device and then do nothing: the builder grows the pool or tiles the frame and records it again.
using BundleRecorder = std::function<void(VkCommandBuffer, const BuiltBundle&)>;

struct BundleStats {
    std::uint64_t fragments = 0;
    std::uint32_t nonEmptyPixels = 0; // with listStatistics
    std::uint32_t longestList = 0;    // with listStatistics
    std::uint32_t rebuilds = 0;       // builds repeated after the pool grew
    std::uint32_t tiles = 1;          // parts the frame was split into
    double buildMs = 0.0;             // GPU time of every build, rebuilds after an overflow included
    double traverseMs = 0.0;          // GPU time of the statistics pass: every list walked once
    double meanListLength() const { return nonEmptyPixels ? double(fragments) / nonEmptyPixels : 0.0; }
};

class BundleBuilder {
public:
    BundleBuilder(const vk::Context& ctx, const gpu::GpuScene& scene, const BundleBuilderOptions& options = {});

    // Builds the bundle for `frame` (scene at `time`) and hands each completed part to `consume`
    // (the whole frame, or its tiles in turn). Throws bl::Error if one pixel alone needs more than
    // the memory cap.
    // `recordWithBuild`, where given, is recorded after each build in its submission (above);
    // `consume` still follows each completed part on the host.
    BundleStats build(const shader::BundleFrame& frame, double time,
                      const std::function<void(const BuiltBundle&)>& consume,
                      const BundleRecorder& recordWithBuild = {});

    // The benchmark floor: rasterize the same triangles with a fragment shader that only counts.
    // Returns the fragment count; GPU milliseconds in *ms.
    std::uint64_t countFragments(const shader::BundleFrame& frame, double time, double* ms);

    // A host copy of a built bundle's lists (tests, debugging): heads per pixel, then the nodes,
    // and (`hits`, with the hit payload) each node's hit.
    void readLists(const BuiltBundle& bundle, std::vector<std::uint32_t>& heads, std::vector<shader::BundleNode>& nodes,
                   std::vector<shader::BundleHit>* hits = nullptr) const;

    std::uint64_t capacity() const { return mPool ? mPool->capacity() : 0; }
    bool usesSubgroups() const;
    bool exactDepths() const { return mContext->geometryShader(); }

private:
    struct Attempt {
        std::uint64_t requested;
        double ms;
    };
    Attempt buildOnce(const shader::BundleFrame& frame, double time, bool countOnly,
                      const BundleRecorder& recordWithBuild = {});
    BuiltBundle builtFor(const shader::BundleFrame& frame, std::uint64_t fragments) const;
    void ensurePool(std::uint32_t pixels);
    void readStatistics(BundleStats& stats);
    void buildTiles(const shader::BundleFrame& frame, double time, std::uint32_t depth, BundleStats& stats,
                    const std::function<void(const BuiltBundle&)>& consume, const BundleRecorder& recordWithBuild);

    const vk::Context* mContext;
    const gpu::GpuScene* mScene;
    BundleBuilderOptions mOptions;
    std::unique_ptr<BundlePool> mPool;
    std::unique_ptr<ComputeBundleRasterizer> mCompute; // backend = Compute
    vk::Buffer mStats;
    vk::GpuTimer mTimer;
};

} // namespace bl
