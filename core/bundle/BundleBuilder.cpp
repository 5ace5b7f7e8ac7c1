#include "bundle/BundleBuilder.h"

#include "base/Error.h"
#include "base/Log.h"
#include "bundle/BundleFrame.h"
#include "bundle/ComputeBundleRasterizer.h"
#include "vk/Commands.h"

#include <algorithm>
#include <cmath>

namespace bl {

BundleBackend chooseBundleBackend(const vk::Context& ctx, const std::string& setting) {
    if (setting == "compute") return BundleBackend::Compute;
    if (setting == "raster") return BundleBackend::Raster;
    if (setting != "auto") throw Error("bundle backend '" + setting + "': raster, compute or auto");
    return ctx.info().type == "CPU" && ComputeBundleRasterizer::supported(ctx) ? BundleBackend::Compute
                                                                               : BundleBackend::Raster;
}

namespace {
// Headroom when splitting into tiles: each tile's predicted need is the whole frame's share, but
// fragments are not spread evenly.
constexpr double kTileHeadroom = 1.25;
constexpr std::uint32_t kMaxTileDepth = 16;
// Nodes per pixel before the first build has said what it needs.
constexpr std::uint64_t kInitialNodesPerPixel = 4;
} // namespace

BundleBuilder::BundleBuilder(const vk::Context& ctx, const gpu::GpuScene& scene, const BundleBuilderOptions& options)
    : mContext(&ctx), mScene(&scene), mOptions(options) {
    if (!ctx.bufferDeviceAddress()) {
        throw Error("bundles need bufferDeviceAddress (a Vulkan 1.3 feature) on '" + ctx.info().name + "'");
    }
    mStats = vk::Buffer(ctx, sizeof(shader::BundleListStats),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                            VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                        vk::MemoryUse::Device);
    mTimer = vk::GpuTimer(ctx);
    if (options.backend == BundleBackend::Compute) {
        mCompute = std::make_unique<ComputeBundleRasterizer>(ctx, scene);
    }
}

bool BundleBuilder::usesSubgroups() const { return mPool && mPool->usesSubgroups(); }

void BundleBuilder::ensurePool(std::uint32_t pixels) {
    if (mPool && mPool->slotPixels() >= pixels) return;
    BundlePoolOptions options;
    options.slots = 1;
    options.slotPixels = std::max(pixels, 1u);
    options.payload = mOptions.payload;
    options.memoryCapBytes = mOptions.memoryCapBytes;
    options.subgroupAllocation = mOptions.subgroupAllocation;
    options.rasterized = mOptions.backend == BundleBackend::Raster;
    // A pool replaced for a larger frame starts from what the old one had learnt it needs.
    options.initialNodes = mPool ? mPool->capacity()
                                 : (mOptions.initialNodes ? mOptions.initialNodes : kInitialNodesPerPixel * pixels);
    mPool.reset();
    mPool = std::make_unique<BundlePool>(*mContext, *mScene, options);
}

BuiltBundle BundleBuilder::builtFor(const shader::BundleFrame& frame, std::uint64_t fragments) const {
    const shader::BundlePoolView view = mPool->view();
    auto join = [](glm::uvec2 v) { return VkDeviceAddress(v.x) | VkDeviceAddress(v.y) << 32; };
    BuiltBundle built;
    built.frame = frame;
    built.heads = join(view.heads);
    built.nodes = join(view.nodes);
    built.payload = join(view.payload);
    built.counters = join(view.counters);
    built.fragments = fragments;
    return built;
}

BundleBuilder::Attempt BundleBuilder::buildOnce(const shader::BundleFrame& frame, double time, bool countOnly,
                                                const BundleRecorder& recordWithBuild) {
    mContext->submitAndWait([&](VkCommandBuffer cmd) {
        mTimer.begin(cmd);
        mPool->recordReset(cmd);
        if (countOnly) {
            mPool->recordCount(cmd, frame, time, &mTimer);
        } else if (mCompute) {
            mCompute->record(cmd, *mPool, 0, frame, time, &mTimer);
        } else {
            mPool->recordBuild(cmd, 0, frame, BundleGeometry::triangles(time), &mTimer);
        }
        if (recordWithBuild && !countOnly) {
            recordWithBuild(cmd, builtFor(frame, 0)); // the builds end with a barrier to every later stage
        }
    });
    mTimer.collect();
    double ms = 0.0;
    for (const PassTime& p : mTimer.totals()) ms += p.totalMs;
    mTimer.clearTotals();
    return {mPool->status().requested, ms};
}

void BundleBuilder::readStatistics(BundleStats& stats) {
    mContext->submitAndWait([&](VkCommandBuffer cmd) {
        mTimer.begin(cmd);
        vkCmdFillBuffer(cmd, mStats.get(), 0, sizeof(shader::BundleListStats), 0);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        mPool->recordStatistics(cmd, 0, deviceAddress(*mContext, mStats), &mTimer);
    });
    mTimer.collect();
    for (const PassTime& p : mTimer.totals()) stats.traverseMs += p.totalMs;
    mTimer.clearTotals();
    shader::BundleListStats out{};
    mStats.download(*mContext, &out, sizeof(out));
    stats.nonEmptyPixels += out.nonEmptyPixels;
    stats.longestList = std::max(stats.longestList, out.longestList);
}

void BundleBuilder::buildTiles(const shader::BundleFrame& frame, double time, std::uint32_t depth, BundleStats& stats,
                               const std::function<void(const BuiltBundle&)>& consume,
                               const BundleRecorder& recordWithBuild) {
    const std::uint32_t pixels = frame.width * frame.height;
    ensurePool(pixels);
    Attempt a = buildOnce(frame, time, false, recordWithBuild);
    stats.buildMs += a.ms;
    if (a.requested > mPool->capacity() && mPool->grow({a.requested, mPool->capacity()})) {
        // Grown to what this build needs (within the limits): build again.
        ++stats.rebuilds;
        log::debug("bundle: " + std::to_string(a.requested) + " nodes needed: pool grown to " +
                   std::to_string(mPool->capacity()) + ", rebuilding");
        a = buildOnce(frame, time, false, recordWithBuild);
        stats.buildMs += a.ms;
    }
    if (a.requested > mPool->capacity()) {
        // Beyond the memory limits: split into tiles whose predicted needs fit, and build them in turn.
        if (depth >= kMaxTileDepth || pixels == 1) {
            throw Error("bundle: one tile of " + std::to_string(pixels) + " pixel(s) needs " +
                        std::to_string(a.requested) + " nodes, more than the memory cap allows (" +
                        std::to_string(mPool->maxNodes()) + ")");
        }
        ++stats.rebuilds;
        const double parts = std::ceil(double(a.requested) / double(mPool->capacity()) * kTileHeadroom);
        const auto side = static_cast<std::uint32_t>(std::max(2.0, std::ceil(std::sqrt(parts))));
        const std::uint32_t tw = std::max(1u, (frame.width + side - 1) / side);
        const std::uint32_t th = std::max(1u, (frame.height + side - 1) / side);
        for (std::uint32_t y = 0; y < frame.height; y += th) {
            for (std::uint32_t x = 0; x < frame.width; x += tw) {
                if (x || y) ++stats.tiles;
                buildTiles(bundleTile(frame, x, y, std::min(tw, frame.width - x), std::min(th, frame.height - y)),
                           time, depth + 1, stats, consume, recordWithBuild);
            }
        }
        return;
    }
    stats.fragments += a.requested;
    if (mOptions.listStatistics) {
        readStatistics(stats);
    }
    consume(builtFor(frame, a.requested));
}

BundleStats BundleBuilder::build(const shader::BundleFrame& frame, double time,
                                 const std::function<void(const BuiltBundle&)>& consume,
                                 const BundleRecorder& recordWithBuild) {
    BundleStats stats;
    buildTiles(frame, time, 0, stats, consume, recordWithBuild);
    return stats;
}

void BundleBuilder::readLists(const BuiltBundle& bundle, std::vector<std::uint32_t>& heads,
                              std::vector<shader::BundleNode>& nodes, std::vector<shader::BundleHit>* hits) const {
    heads = mPool->readHeads(0);
    heads.resize(std::size_t(bundle.frame.width) * bundle.frame.height);
    nodes = mPool->readNodes(bundle.fragments);
    if (hits) *hits = mPool->readHits(bundle.fragments);
}

std::uint64_t BundleBuilder::countFragments(const shader::BundleFrame& frame, double time, double* ms) {
    ensurePool(frame.width * frame.height);
    Attempt a = buildOnce(frame, time, true);
    if (ms) *ms = a.ms;
    return a.requested;
}

} // namespace bl
