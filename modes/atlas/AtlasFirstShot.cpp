// Mode atlas's first shot (first_shot = auto | on): the area emitters' direct light by emitter points
// (gpu/EmitterPointPass.h) and the environment's by environment_shots directional depth maps drawn
// by its importance (bundle/EnvironmentShadowPass.h) into the direct atlas, new points and directions
// every direction, so the exchange carries reflected light only (shaders/modes/atlas/first_shot.comp.glsl:
// one pass over the texels' samples for both).
#include "modes/atlas/AtlasGpu.h"

#include "vk/Commands.h"

#include <modes/atlas/AtlasShared.h>
#include <modes/atlas/first_shot.comp.spv.h>
#include <shared/Random.h>

#include <array>

namespace bl {

using atlasmode::addressOf;
using atlasmode::kStorage;

AtlasMode::FirstShotChoice AtlasMode::firstShotChoice(const Scene& scene) const {
    const SceneFeatures f = scene.features();
    const AtlasModeOptions& o = mOptions;
    FirstShotChoice c;
    c.area = f.emissiveMeshes;
    c.environment = f.environment && o.environmentShots > 0;
    if (!c.area && !c.environment) {
        c.code = f.environment ? "environment-shots-0" : "no-area-emitters";
        c.why = f.environment ? "no area emitters, and environment_shots = 0: the exchange's list ends carry the environment"
                              : "no area emitters or environment";
        return c;
    }
    std::string conflictCode;
    if (o.bounce) {
        c.conflict = "transfer = bounce";
        conflictCode = "transfer-bounce";
    } else if (o.delayIndirect != 0) {
        c.conflict = "delay_indirect = " + std::to_string(o.delayIndirect);
        conflictCode = "delay-indirect";
    } else if (f.glossy && o.glossy != "off") {
        c.conflict = "glossy = " + o.glossy + " on glossy materials";
        conflictCode = "glossy-transport";
    }
    const std::string sources = c.area && c.environment ? "the emitters' and the environment's" : c.area ? "the emitters'" : "the environment's";
    if (o.firstShot == "off") {
        c.code = "first-shot-off";
        c.why = "first_shot = off: the exchange carries " + sources + " light";
    } else if (!c.conflict.empty()) {
        c.code = conflictCode;
        c.why = o.firstShot == "on"
                    ? "first_shot = on with " + c.conflict + ": refused at set-up (first_shot = auto leaves the shot out)"
                    : "first_shot = auto, " + c.conflict + ": the exchange carries " + sources + " light";
    } else {
        c.runs = true;
        c.code = c.area && c.environment ? "area-emitters-environment" : c.area ? "area-emitters" : "environment";
    }
    if (!c.runs) {
        c.area = c.environment = false;
    }
    return c;
}

void AtlasMode::setUpFirstShot(const Scene& scene) {
    Gpu& g = *mGpu;
    g.direct.firstShot = mPlan.runs(kPassFirstShot);
    if (!g.direct.firstShot) {
        return;
    }
    const FirstShotChoice choice = firstShotChoice(scene);
    // Without area emitters the points' pass is off (placeholders bound, no point adds light).
    const std::uint32_t points = choice.area ? mOptions.emitterPoints : 0;
    const std::uint32_t side = mOptions.emitterShadowResolution;
    const VkDeviceSize environmentBytes =
        choice.environment
            ? EnvironmentShadowPass::bytesFor(mOptions.environmentShots, mOptions.environmentShadowResolution)
            : 0;
    mContext->requireDeviceMemory(gpu::EmitterPointPass::bytesFor(points, side) + environmentBytes +
                                      VkDeviceSize(g.link.texelCount) * shader::kAtlasSides * 2 * sizeof(glm::vec4),
                                  "atlas first shot");
    g.direct.emitterPoints = std::make_unique<gpu::EmitterPointPass>(*mContext, *g.scene, scene, points, side);
    const std::vector<glm::vec4> zero(std::size_t(shader::kAtlasSides) * g.link.texelCount);
    g.direct.pointDirect = vk::makeBuffer(*mContext, std::span<const glm::vec4>(zero), kStorage);
    g.direct.shotSum = vk::makeBuffer(*mContext, std::span<const glm::vec4>(zero), kStorage);

    // Without the environment's part the pass is off and binds placeholders.
    g.direct.environmentShadows = std::make_unique<EnvironmentShadowPass>(
        *mContext, *g.scene, scene, choice.environment ? mOptions.environmentShots : 0u,
        mOptions.environmentShadowResolution);

    VkDevice device = mContext->device();
    g.direct.firstShotSet = vk::BoundSet(
        device,
        {vk::Bound::storageBuffer(shader::kAtlasFirstShotBindingPoints, g.direct.emitterPoints->buffer()),
         vk::Bound::storageImage(shader::kAtlasFirstShotBindingMaps, g.direct.emitterPoints->maps().view()),
         vk::Bound::storageImage(shader::kAtlasFirstShotBindingMaps2, g.direct.emitterPoints->maps().view()),
         vk::Bound::storageBuffer(shader::kAtlasFirstShotBindingEnvironment, g.direct.environmentShadows->buffer()),
         vk::Bound::storageImage(shader::kAtlasFirstShotBindingEnvironmentMaps, g.direct.environmentShadows->maps().view())});
    std::array<std::uint32_t, shader::kAtlasShotSpecCount> shotSpec{};
    shotSpec[shader::kAtlasShotSpecAllSamples] = mOptions.shotAllSamples ? 1u : 0u;
    g.direct.firstShotPass = vk::ComputePass<shader::AtlasFirstShotPush>(device, kSpv_modes_atlas_first_shot_comp,
                                                                         {g.direct.firstShotSet.layout()}, shotSpec);
}

void AtlasMode::recordFirstShot(VkCommandBuffer cmd, double time) {
    Gpu& g = *mGpu;
    g.direct.emitterPoints->record(cmd, time, &g.timer);
    g.direct.environmentShadows->record(cmd, time, &g.timer);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    shader::AtlasFirstShotPush push{};
    push.samples = addressOf(*mContext, g.direct.samples);
    push.first = addressOf(*mContext, g.direct.firstSample);
    push.texels = addressOf(*mContext, g.link.texels);
    push.direct = addressOf(*mContext, g.direct.directRadiance);
    push.pointDirect = addressOf(*mContext, g.direct.pointDirect);
    push.shotSum = addressOf(*mContext, g.direct.shotSum);
    push.senders = addressOf(*mContext, g.exchange.senders);
    push.texelCount = g.link.texelCount;
    push.inverseShots = 1.0f / float(mIterations + 1);
    push.shot = mIterations;
    push.seedHash = shader::blHash(static_cast<std::uint32_t>(mSeed ^ (mSeed >> 32)));
    const std::uint32_t scope = g.timer.start(cmd, "first shot");
    g.direct.firstShotPass.dispatch(cmd, push, vk::groupCount(g.link.texelCount, shader::kAtlasGroupSize), g.direct.firstShotSet.sets());
    g.timer.stop(cmd, scope);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
}

} // namespace bl
