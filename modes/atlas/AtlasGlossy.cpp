// Mode atlas's glossy passes ([HHGM10] 5.3-5.4): point/spot lights into the glossy transfer atlas,
// the final glossy gather toward the eye, and the lights' own highlight per view sample.
#include "modes/atlas/AtlasGpu.h"
#include "vk/Commands.h"

#include <modes/atlas/AtlasShared.h>

namespace bl {

// Point/spot lights into the glossy transfer atlas for the next direction (direct.comp.glsl's
// glossy pass), after the exchange's atomics.
void AtlasMode::recordGlossyLights(VkCommandBuffer cmd) {
    Gpu& g = *mGpu;
    shader::AtlasDirectPush push = glossyPush();
    push.next = g.exchange.directions->sample(directionIndex(mIterations + 1)).omega;
    push.glossy = shader::kAtlasDirectGlossy;
    recordDirect(cmd, push, "glossy lights", g.glossy.texelCount);
}

shader::AtlasDirectPush AtlasMode::glossyPush() const {
    const Gpu& g = *mGpu;
    shader::AtlasDirectPush push = directPush();
    push.received = atlasmode::addressOf(*mContext, g.exchange.received);
    push.materials = atlasmode::addressOf(*mContext, g.glossy.materials);
    push.touched = atlasmode::addressOf(*mContext, g.exchange.touched);
    push.glossyTexels = atlasmode::addressOf(*mContext, g.glossy.texels);
    push.lightCache = atlasmode::addressOf(*mContext, g.glossy.lightCache);
    push.glossyCount = g.glossy.texelCount;
    return push;
}

// The final glossy gather of the direction just exchanged (its sender still unchanged): the
// G-buffer of a jittered camera sample (a new sub-pixel position per direction), then one
// invocation per pixel.
void AtlasMode::recordGather(VkCommandBuffer cmd, double weight) {
    Gpu& g = *mGpu;
    const gpu::CameraSample sample = g.view.camera->sample(mIterations, true, mTime, mSeed);
    g.view.camera->record(cmd, sample, &g.timer);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    shader::AtlasGatherPush push{};
    push.pool = g.exchange.pool->view();
    push.gatheredIndirect = g.exchange.split ? atlasmode::addressOf(*mContext, g.glossy.gatheredIndirect) : glm::uvec2(0u);
    push.triangles = atlasmode::addressOf(*mContext, g.link.triangles);
    push.gathered = atlasmode::addressOf(*mContext, g.glossy.gathered);
    push.direction = atlasmode::addressOf(*mContext, g.exchange.direction);
    push.width = g.view.camera->width();
    push.height = g.view.camera->height();
    push.atlasWidth = static_cast<std::uint32_t>(g.link.atlas.maps.width);
    push.atlasHeight = static_cast<std::uint32_t>(g.link.atlas.maps.height);
    push.weight = float(weight);
    push.clear = mTotalWeight == 0.0 ? 1u : 0u;
    const std::uint32_t scope = g.timer.start(cmd, "glossy gather");
    const VkDescriptorSet set = g.view.camera->set();
    g.glossy.gatherPass.dispatch(cmd, push,
                          {vk::groupCount(push.width, shader::kAtlasViewGroupSize),
                           vk::groupCount(push.height, shader::kAtlasViewGroupSize), 1},
                          {&set, 1});
    g.timer.stop(cmd, scope);
}

// Point/spot lights' glossy highlight toward the eye for the view sample whose G-buffer was just
// recorded.
void AtlasMode::recordHighlight(VkCommandBuffer cmd) {
    Gpu& g = *mGpu;
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    shader::AtlasHighlightPush push{};
    push.highlight = atlasmode::addressOf(*mContext, g.glossy.highlight);
    push.width = g.view.camera->width();
    push.height = g.view.camera->height();
    push.lightCount = g.direct.shadows->lightCount();
    push.shadowResolution = g.direct.shadows->resolution();
    const std::uint32_t scope = g.timer.start(cmd, "glossy highlight");
    const VkDescriptorSet sets[] = {g.view.camera->set(), g.direct.directSet.set()};
    g.glossy.highlightPass.dispatch(cmd, push,
                             {vk::groupCount(push.width, shader::kAtlasViewGroupSize),
                              vk::groupCount(push.height, shader::kAtlasViewGroupSize), 1},
                             sets);
    g.timer.stop(cmd, scope);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
}

} // namespace bl
