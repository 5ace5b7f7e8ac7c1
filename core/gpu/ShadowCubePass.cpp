#include "gpu/ShadowCubePass.h"

#include "base/Error.h"
#include "vk/Commands.h"

#include <gpu/shadow_cube.frag.spv.h>
#include <gpu/shadow_cube.vert.spv.h>
#include <shared/CubeFaces.h>

#include <algorithm>
#include <cmath>

namespace bl::gpu {

namespace {
constexpr VkFormat kTexelFormat = VK_FORMAT_R16G16B16A16_UINT; // shaders/gpu/ShadowTexel.glsl
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
// ShadowTexel.glsl's texel for "nothing along this ray": +inf (0x7f800000 as two halves), no normal.
constexpr VkClearColorValue kNothing{.uint32 = {0x0000u, 0x7f80u, 0x8000u, 0x8000u}};
} // namespace

std::optional<VkRect2D> ShadowCubePass::frontTexels(std::uint32_t face, const glm::vec3& front,
                                                    std::uint32_t resolution) {
    const VkRect2D whole{{0, 0}, {resolution, resolution}};
    if (front == glm::vec3(0.0f)) {
        return whole;
    }
    // A ray through (x, y) of the face ([-1, 1]^2, CubeFaces.h) is f + x r + y u; its sign against
    // `front` is that of a + b x + c y, linear, so the front part is the square cut by a line: its
    // corners in front and the edges' crossings bound it.
    glm::vec3 r, u, f;
    shader::blCubeFaceBasis(face, r, u, f);
    const double a = glm::dot(f, front), b = glm::dot(r, front), c = glm::dot(u, front);
    const auto value = [&](double x, double y) { return a + b * x + c * y; };
    const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    double xMin = 2, xMax = -2, yMin = 2, yMax = -2;
    const auto include = [&](double x, double y) {
        xMin = std::min(xMin, x), xMax = std::max(xMax, x), yMin = std::min(yMin, y), yMax = std::max(yMax, y);
    };
    for (int i = 0; i < 4; ++i) {
        const double* p = corners[i];
        const double* q = corners[(i + 1) % 4];
        const double vp = value(p[0], p[1]), vq = value(q[0], q[1]);
        if (vp >= 0.0) {
            include(p[0], p[1]);
        }
        if ((vp < 0.0) != (vq < 0.0)) {
            const double t = vp / (vp - vq);
            include(p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]));
        }
    }
    if (xMin > xMax) {
        return std::nullopt;
    }
    // Column (x + 1) / 2 N, row (1 - y) / 2 N, widened by a texel (rounding, and the lookups'
    // nearest texel at the front part's edge).
    const double n = resolution;
    const auto clampTexel = [&](double t) { return static_cast<std::int64_t>(std::clamp(t, 0.0, n)); };
    const std::int64_t x0 = clampTexel(std::floor((xMin + 1.0) * 0.5 * n) - 1.0);
    const std::int64_t x1 = clampTexel(std::ceil((xMax + 1.0) * 0.5 * n) + 1.0);
    const std::int64_t y0 = clampTexel(std::floor((1.0 - yMax) * 0.5 * n) - 1.0);
    const std::int64_t y1 = clampTexel(std::ceil((1.0 - yMin) * 0.5 * n) + 1.0);
    if (x1 <= x0 || y1 <= y0) {
        return std::nullopt;
    }
    return VkRect2D{{static_cast<std::int32_t>(x0), static_cast<std::int32_t>(y0)},
                    {static_cast<std::uint32_t>(x1 - x0), static_cast<std::uint32_t>(y1 - y0)}};
}

bool ShadowCubePass::refreshFor(const vk::Context& ctx, GpuScene& scene, double time) {
    if (mLightCount == 0 || (mLightsTime && (!scene.features().animated || *mLightsTime == time))) {
        return false;
    }
    scene.setLightTime(ctx, time); // keyframed lights move with their shadows
    mLightsTime = time;
    return true;
}

ShadowCubePass::ShadowCubePass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t resolution)
    : ShadowCubePass(ctx, scene, resolution, static_cast<std::uint32_t>(scene.lights().size())) {}

ShadowCubePass::ShadowCubePass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t resolution,
                               std::uint32_t cubes)
    : ShadowCubePass(ctx, scene, resolution, cubes, static_cast<std::uint32_t>(scene.lights().size()), true) {}

ShadowCubePass ShadowCubePass::forPositions(const vk::Context& ctx, const GpuScene& scene, std::uint32_t resolution,
                                            std::uint32_t cubes, bool normals) {
    return ShadowCubePass(ctx, scene, resolution, cubes, 0u, normals);
}

ShadowCubePass::ShadowCubePass(const vk::Context& ctx, const GpuScene& scene, std::uint32_t resolution,
                               std::uint32_t cubes, std::uint32_t lights, bool normals)
    : mScene(&scene), mResolution(resolution), mLightCount(lights), mCubes(cubes) {
    if (mCubes < mLightCount) {
        throw Error("shadow cubes: " + std::to_string(mCubes) + " cube(s) cannot hold the scene's " +
                    std::to_string(mLightCount) + " light(s)");
    }
    VkDevice device = ctx.device();
    // Without cubes a 1x1 placeholder keeps the shading pass's descriptors valid.
    const std::uint32_t side = mCubes ? resolution : 1;
    mMaps = vk::GpuImage(ctx, {side, side, kFaces * std::max(mCubes, 1u), kTexelFormat,
                               VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT, true});
    mDepth = vk::GpuImage(ctx, {side, side, 1, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});
    mPipelineLayout = vk::makePipelineLayout(device, {}, sizeof(shader::ShadowPush),
                                             VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
    vk::GraphicsPipelineDesc desc;
    desc.vertexShader = kSpv_gpu_shadow_cube_vert;
    desc.fragmentShader = kSpv_gpu_shadow_cube_frag;
    desc.vertexBindings = GpuScene::vertexBindings();
    desc.vertexAttributes = GpuScene::vertexAttributes(); // positions and normals
    desc.colorFormats = {kTexelFormat};
    desc.depthFormat = kDepthFormat;
    desc.layout = mPipelineLayout.get();
    desc.specialization.assign(shader::kShadowSpecNormals + 1, 0u);
    desc.specialization[shader::kShadowSpecNormals] = normals ? 1u : 0u;
    mPipeline = vk::makeGraphicsPipeline(device, desc);

    // Every cube starts as "nothing in the way" (+inf, no normal) in GENERAL, so a cube never rendered reads
    // as unshadowed, and each record changes the layout of its own layers only.
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        vk::transitionImage(cmd, mMaps.get(), vk::ImageTransition{});
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
        vkCmdClearColorImage(cmd, mMaps.get(), VK_IMAGE_LAYOUT_GENERAL, &kNothing, 1, &all);
    });
}

void ShadowCubePass::record(VkCommandBuffer cmd, double time, vk::GpuTimer* timer) {
    if (mLightCount == 0) {
        return; // the cleared placeholder stays valid
    }
    std::uint32_t scope = timer ? timer->start(cmd, "shadow maps") : 0;
    for (std::uint32_t light = 0; light < mLightCount; ++light) {
        recordCube(cmd, mScene->lights()[light].position, light, time);
    }
    if (timer) {
        timer->stop(cmd, scope);
    }
}

void ShadowCubePass::record(VkCommandBuffer cmd, const glm::vec3& position, std::uint32_t cube, double time,
                            vk::GpuTimer* timer, const glm::vec3& front) {
    if (cube >= mCubes) {
        throw Error("shadow cubes: cube " + std::to_string(cube) + " requested, the image holds " +
                    std::to_string(mCubes));
    }
    std::uint32_t scope = timer ? timer->start(cmd, "shadow cube") : 0;
    recordCube(cmd, position, cube, time, front);
    if (timer) {
        timer->stop(cmd, scope);
    }
}

void ShadowCubePass::recordCube(VkCommandBuffer cmd, const glm::vec3& position, std::uint32_t cube, double time,
                                const glm::vec3& front) {
    // Only this cube's layers change layout (its old maps are discarded); the others keep theirs.
    vk::ImageTransition toAttachment = vk::toColorAttachment();
    toAttachment.baseLayer = kFaces * cube;
    toAttachment.layerCount = kFaces;
    vk::transitionImage(cmd, mMaps.get(), toAttachment);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, mPipeline.get());
    mScene->bindGeometry(cmd);
    for (std::uint32_t face = 0; face < kFaces; ++face) {
        vk::transitionImage(cmd, mDepth.get(), vk::toDepthAttachment());
        vk::RenderTargets targets;
        targets.colors = {mMaps.layerView(kFaces * cube + face)};
        targets.clearColor = kNothing;
        targets.depth = mDepth.view();
        targets.extent = {mResolution, mResolution};
        vk::beginRendering(cmd, targets); // clears the whole face
        const std::optional<VkRect2D> part = frontTexels(face, front, mResolution);
        if (!part) {
            vkCmdEndRendering(cmd);
            continue; // nothing it lights lies behind this face: "nothing in the way"
        }
        vkCmdSetScissor(cmd, 0, 1, &*part);
        for (const GpuDraw& d : mScene->draws()) {
            shader::ShadowPush push{};
            push.model = mScene->modelMatrix(d.mesh, time);
            push.lightPosition = position;
            push.nearPlane = mScene->shadowNear();
            push.face = face;
            vkCmdPushConstants(cmd, mPipelineLayout.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                               sizeof(push), &push);
            vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
        }
        vkCmdEndRendering(cmd);
    }
    vk::ImageTransition toGeneral = vk::colorAttachmentToGeneral();
    toGeneral.baseLayer = kFaces * cube;
    toGeneral.layerCount = kFaces;
    vk::transitionImage(cmd, mMaps.get(), toGeneral);
}

} // namespace bl::gpu
