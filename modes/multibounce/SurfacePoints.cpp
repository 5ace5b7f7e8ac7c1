#include "modes/multibounce/SurfacePoints.h"

#include "base/Error.h"
#include "bundle/BundlePool.h"
#include "vk/Commands.h"

#include <cmath>
#include <glm/gtc/constants.hpp>
#include <modes/multibounce/MultibounceShared.h>
#include <modes/multibounce/points.comp.spv.h>
#include <numeric>

namespace bl {

namespace {
constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
// Groups per row of the 2D dispatch (maxComputeWorkGroupCount is at least 65535 per axis).
constexpr std::uint32_t kGroupsPerRow = 4096;
} // namespace

SurfacePoints::SurfacePoints(const vk::Context& ctx, const gpu::GpuScene& scene, std::uint32_t directions,
                             std::uint32_t perDirection, double splatScale)
    : mContext(&ctx), mScene(&scene), mDirections(directions), mPerDirection(perDirection) {
    if (directions == 0 || perDirection == 0 || !(splatScale > 0.0) || !std::isfinite(splatScale)) {
        throw Error("imperfect bundles: " + std::to_string(directions) + " directions of " +
                    std::to_string(perDirection) + " points with splat scale " + std::to_string(splatScale) +
                    " (need at least one of each and a scale > 0)");
    }
    // Areas in the order GpuScene numbers triangles (draw by draw), in double.
    const Scene& s = scene.scene();
    std::vector<double> cumulative;
    cumulative.reserve(scene.triangleCount());
    std::vector<shader::MultibounceDraw> draws;
    for (const gpu::GpuDraw& d : scene.draws()) {
        const Mesh& m = s.meshes[d.mesh];
        draws.push_back({glm::mat4(1.0f), d.firstIndex / 3, m.material, static_cast<std::uint32_t>(d.vertexOffset), 0});
        for (const glm::uvec3& t : m.triangles) {
            const glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
            const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
            mArea += std::isfinite(area) ? area : 0.0;
            cumulative.push_back(mArea);
        }
    }
    mTriangles = static_cast<std::uint32_t>(cumulative.size());
    if (mTriangles == 0 || !(mArea > 0.0)) {
        throw Error("imperfect bundles: the scene has no surface area to sample points on");
    }
    std::vector<float> cdf(cumulative.size());
    for (std::size_t i = 0; i < cdf.size(); ++i) cdf[i] = static_cast<float>(cumulative[i] / mArea);
    cdf.back() = 1.0f;
    mRadius = static_cast<float>(splatScale * std::sqrt(mArea / (glm::pi<double>() * perDirection)));

    const std::uint64_t count = std::uint64_t(directions) * perDirection;
    if (count > 0xffffffffull / 2) {
        throw Error("imperfect bundles: " + std::to_string(count) + " points per iteration are too many");
    }
    // The point pass binds both arrays whole as storage buffers.
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(ctx.physicalDevice(), &properties);
    const std::uint64_t range = properties.limits.maxStorageBufferRange;
    if (count * sizeof(shader::BundleSplat) > range) {
        throw Error("imperfect bundles: " + std::to_string(directions) + " directions x " + std::to_string(perDirection) +
                    " points need " + std::to_string(count * sizeof(shader::BundleSplat)) +
                    " bytes of splats, more than one storage buffer binding of '" + ctx.info().name + "' holds (" +
                    std::to_string(range) + "); at most " + std::to_string(range / sizeof(shader::BundleSplat) / perDirection) +
                    " directions fit at this number of points (lower bundle_count or points)");
    }
    ctx.requireDeviceMemory(count * (sizeof(shader::BundleSplat) + sizeof(shader::MultibouncePoint)),
                            "imperfect bundles: " + std::to_string(directions) + " x " + std::to_string(perDirection) +
                                " points");
    mCdf = vk::makeBuffer(ctx, std::span<const float>(cdf), kStorage);
    mDraws = vk::Buffer(ctx, draws.size() * sizeof(shader::MultibounceDraw), kStorage, vk::MemoryUse::Upload);
    mDraws.upload(ctx, draws.data(), draws.size() * sizeof(shader::MultibounceDraw));
    mSplats = vk::Buffer(ctx, count * sizeof(shader::BundleSplat), kStorage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                         vk::MemoryUse::Device);
    mPoints = vk::Buffer(ctx, count * sizeof(shader::MultibouncePoint), kStorage, vk::MemoryUse::Device);

    VkDevice device = ctx.device();
    mBound = vk::BoundSet(device, {vk::Bound::storageBuffer(shader::kMultibouncePointsBindingCdf, mCdf.get()),
                                   vk::Bound::storageBuffer(shader::kMultibouncePointsBindingDraws, mDraws.get()),
                                   vk::Bound::storageBuffer(shader::kMultibouncePointsBindingVertices, scene.vertexBuffer()),
                                   vk::Bound::storageBuffer(shader::kMultibouncePointsBindingIndices, scene.indexBuffer()),
                                   vk::Bound::storageBuffer(shader::kMultibouncePointsBindingPlanes, scene.planeBuffer()),
                                   vk::Bound::storageBuffer(shader::kMultibouncePointsBindingSplats, mSplats.get()),
                                   vk::Bound::storageBuffer(shader::kMultibouncePointsBindingPoints, mPoints.get())});
    mSample = vk::ComputePass<shader::MultibouncePointsPush>(device, kSpv_modes_multibounce_points_comp, {mBound.layout()});
}

void SurfacePoints::record(VkCommandBuffer cmd, std::uint32_t seed, std::uint32_t iteration, double time,
                           vk::GpuTimer* timer) {
    if (mScene->features().animated) {
        auto* draws = static_cast<shader::MultibounceDraw*>(mDraws.data());
        for (std::size_t i = 0; i < mScene->draws().size(); ++i) {
            draws[i].model = mScene->modelMatrix(mScene->draws()[i].mesh, time);
        }
    }
    const std::uint32_t scope = timer ? timer->start(cmd, "surface points") : 0;
    shader::MultibouncePointsPush push{};
    push.seed = seed;
    push.iteration = iteration;
    push.count = mDirections * mPerDirection;
    push.pointsPerDirection = mPerDirection;
    push.triangleCount = mTriangles;
    push.drawCount = static_cast<std::uint32_t>(mScene->draws().size());
    push.radius = mRadius;
    push.textured = mScene->features().textured ? 1u : 0u;
    const std::uint32_t groups = vk::groupCount(push.count, shader::kMultibouncePointsGroupSize);
    const std::uint32_t rowGroups = std::min(groups, kGroupsPerRow);
    mSample.dispatch(cmd, push, {rowGroups, vk::groupCount(groups, rowGroups), 1}, mBound.sets());
    if (timer) timer->stop(cmd, scope);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT);
}

VkDeviceAddress SurfacePoints::splats(std::uint32_t direction) const {
    return deviceAddress(*mContext, mSplats) + VkDeviceAddress(direction) * mPerDirection * sizeof(shader::BundleSplat);
}

} // namespace bl
