// Mode atlas's direct light from point and spot lights ([HHGM10] 6.5, the hybrid): cube shadow
// maps light sample points inside every texel's surface into the direct atlas, and, with the
// glossy transfer atlas, each glossy sample's shadowed light is cached once for the glossy pass.
#include "modes/atlas/AtlasGpu.h"
#include "base/Error.h"
#include "modes/atlas/TexelSamples.h"
#include "scene/ShaderConversions.h"
#include "vk/Commands.h"

#include <modes/atlas/AtlasShared.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace bl {

using atlasmode::addressOf;
using atlasmode::kStorage;

// What both uses of the direct pass share: the texels' sample points and the lights.
shader::AtlasDirectPush AtlasMode::directPush() const {
    const Gpu& g = *mGpu;
    shader::AtlasDirectPush push{};
    push.samples = addressOf(*mContext, g.direct.samples);
    push.first = addressOf(*mContext, g.direct.firstSample);
    push.texels = addressOf(*mContext, g.link.texels);
    push.texelCount = g.link.texelCount;
    push.lightCount = g.direct.shadows->lightCount();
    push.shadowResolution = g.direct.shadows->resolution();
    return push;
}

void AtlasMode::lightDirect(double time) {
    Gpu& g = *mGpu;
    if (!g.direct.shadows && !g.direct.firstShot) {
        return;
    }
    // The texels' sample points: the point/spot lights' and the first shot's.
    const auto grid = static_cast<int>(mOptions.lightSamples);
    const atlasmode::TexelSamples samples = atlasmode::buildTexelSamples(*mScene, g.link.atlas, g.link.link, grid, time);
    g.direct.samples = vk::makeBuffer(*mContext, std::span<const shader::AtlasSample>(samples.samples), kStorage);
    g.direct.firstSample = vk::makeBuffer(*mContext, std::span<const std::uint32_t>(samples.first), kStorage);
    if (!g.direct.shadows) {
        return; // first shot only: the point/spot part of the direct atlas stays zero
    }
    g.scene->setLightTime(*mContext, time); // keyframed lights where they are at this time
    shader::AtlasDirectPush push = directPush();
    push.direct = addressOf(*mContext, g.direct.directRadiance);
    push.sender = mOptions.bounce ? addressOf(*mContext, g.exchange.sender) : glm::uvec2(0u); // interleaved: sender records
    push.directIntoSender = mOptions.bounce ? 0u : 1u;
    if (g.glossy.transfer) {
        // The glossy texels (their lobes take the lights' light toward each next direction) and
        // the first cache record of each: one per sample and light.
        std::vector<glm::uvec2> glossyTexels;
        VkDeviceSize records = 0; // the shader indexes them by 32 bits: refused beyond that below
        for (std::uint32_t t = 0; t < g.link.texelCount; ++t) {
            const shader::AtlasTexel& texel = g.link.tables.texels[t];
            const std::uint32_t m = texel.material;
            const bool glossy = m < mScene->materials.size() && toGpuMaterial(mScene->materials[m]).specular != glm::vec3(0.0f);
            if (!(texel.inverseArea > 0.0f) || !glossy) continue;
            glossyTexels.emplace_back(t, static_cast<std::uint32_t>(records));
            records += (samples.first[t + 1] - samples.first[t]) * g.direct.shadows->lightCount();
        }
        if (records > VkDeviceSize(UINT32_MAX)) {
            throw Error("atlas: the glossy light cache needs " + std::to_string(records) +
                        " records (glossy texel samples x lights), more than 2^32; lower light_samples or "
                        "atlas_resolution");
        }
        g.glossy.texelCount = static_cast<std::uint32_t>(glossyTexels.size());
        g.glossy.texels = vk::makeBuffer(*mContext, std::span<const glm::uvec2>(glossyTexels), kStorage);
        g.glossy.lightCache = vk::Buffer(*mContext, std::max<VkDeviceSize>(records, 1) * sizeof(shader::AtlasLightRecord),
                                  kStorage, vk::MemoryUse::Device);
    }
    mContext->submitAndWait([&](VkCommandBuffer cmd) {
        g.timer.begin(cmd);
        g.direct.shadows->record(cmd, time, &g.timer);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        recordDirect(cmd, push, "direct", g.link.texelCount);
        if (g.glossy.transfer && g.glossy.texelCount > 0) {
            shader::AtlasDirectPush cache = glossyPush();
            cache.glossy = shader::kAtlasDirectGlossyCache;
            recordDirect(cmd, cache, "glossy light cache", g.glossy.texelCount);
        }
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        if (g.direct.firstShot) { // the shots add to the point/spot part, kept apart
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT);
            const VkBufferCopy all{0, 0, g.direct.directRadiance.size()};
            vkCmdCopyBuffer(cmd, g.direct.directRadiance.get(), g.direct.pointDirect.get(), 1, &all);
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
        }
    });
    g.timer.collect();
}

// One dispatch of direct.comp.glsl over `count` invocations (every texel for the direct atlas, the
// glossy texels for the lights' share of the glossy transfer atlas), timed as `name`.
void AtlasMode::recordDirect(VkCommandBuffer cmd, const shader::AtlasDirectPush& push, const char* name,
                             std::uint32_t count) {
    Gpu& g = *mGpu;
    const std::uint32_t scope = g.timer.start(cmd, name);
    g.direct.directPass.dispatch(cmd, push, vk::groupCount(count, shader::kAtlasGroupSize), g.direct.directSet.sets());
    g.timer.stop(cmd, scope);
}

} // namespace bl
