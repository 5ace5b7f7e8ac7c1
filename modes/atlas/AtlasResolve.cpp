// Mode atlas's camera view: per view sample the camera G-buffer and the atlas uv raster, then the
// shade pass looks each pixel's texel side up (bilinear inside its chart) and adds emission, the
// environment, the direct atlas and the glossy gather; the accumulator averages the samples.
#include "modes/atlas/AtlasGpu.h"
#include "base/Error.h"
#include "vk/Commands.h"

#include <modes/atlas/AtlasShared.h>

#include <algorithm>
#include <cstdint>
#include <utility>

namespace bl {

using atlasmode::addressOf;

ImageSet AtlasMode::resolve() {
    Gpu& g = sceneState(mGpu, name(), "resolve");
    const std::uint32_t samples = mOptions.viewSamples;
    const std::uint32_t width = g.view.camera->width(), height = g.view.camera->height();
    g.view.camera->accumulator().clear(*mContext);
    shader::AtlasShadePush push{};
    push.sums = addressOf(*mContext, g.exchange.sums);
    push.texels = addressOf(*mContext, g.link.texels);
    push.charts = addressOf(*mContext, g.link.charts);
    push.width = width;
    push.height = height;
    push.atlasWidth = static_cast<std::uint32_t>(g.link.atlas.maps.width);
    push.atlasHeight = static_cast<std::uint32_t>(g.link.atlas.maps.height);
    push.reflectedScale = mTotalWeight > 0.0 ? float(1.0 / mTotalWeight) : 0.0f;
    push.settled = addressOf(*mContext, g.exchange.settled);
    push.directScale = mOptions.directScale();
    push.bilinear = mOptions.bilinear ? 1u : 0u;
    push.environmentPresent = g.scene->environmentPresent() ? 1u : 0u;
    push.environmentRotation = g.scene->environmentRotation();
    push.direct = addressOf(*mContext, g.direct.directRadiance);
    push.gathered = g.glossy.gather ? addressOf(*mContext, g.glossy.gathered) : glm::uvec2(0u);
    push.highlight = g.glossy.highlightPass ? addressOf(*mContext, g.glossy.highlight) : glm::uvec2(0u);
    if (g.exchange.split) {
        push.split = 1u;
        push.sumsIndirect = addressOf(*mContext, g.exchange.sumsIndirect);
        push.gatheredIndirect = g.glossy.gather ? addressOf(*mContext, g.glossy.gatheredIndirect) : glm::uvec2(0u);
        push.indirectScale = mIndirectWeight > 0.0 ? float(1.0 / mIndirectWeight) : 0.0f;
    }
    // Several view samples per submission (the camera's uniform is written in the command stream,
    // RecordedUniform.h; the rest is push constants): on an H200 a 64^2 resolve of 16 samples, one
    // submit and wait each, took 50 ms; at 640x360 the same 16 samples are 17 ms of GPU work.
    for (std::uint32_t first = 0; first < samples; first += kViewSamplesPerSubmission) {
        const std::uint32_t last = std::min(samples, first + kViewSamplesPerSubmission);
        mContext->submitAndWait([&](VkCommandBuffer cmd) {
            g.timer.begin(cmd);
            for (std::uint32_t k = first; k < last; ++k) {
                const gpu::CameraSample sample = g.view.camera->sample(k, samples > 1, mTime, mSeed);
                push.samplePosition = sample.samplePosition;
                g.view.camera->record(cmd, sample, &g.timer);
                g.view.lookup->record(cmd, sample, &g.timer);
                if (g.glossy.highlightPass) {
                    recordHighlight(cmd);
                }
                const VkDescriptorSet sets[] = {g.view.camera->set(), g.view.bound.set()};
                g.timer.timed(cmd, "shade", [&] {
                    g.view.shadePass.dispatch(cmd, push, vk::groupCount(width, height, shader::kAtlasViewGroupSize), sets);
                });
                // The next sample's G-buffer and lookup overwrite what this shade read.
                vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
            }
            vk::computeToHost(cmd);
        });
        g.timer.collect();
    }
    ImageSet out;
    out.iterations = mIterations;
    gpu::AccumulatedImages estimate = g.view.camera->accumulator().resolve(*mContext, samples);
    out.layers = std::move(estimate.layers);
    addSampleLosses(out, estimate.nonFiniteSamples, estimate.droppedSamples, estimate.expectedSamples);
    out.counters.emplace_back("atlas_texels", double(g.link.texelCount));
    out.counters.emplace_back("atlas_charts", double(g.link.atlas.stats.charts));
    out.counters.emplace_back("atlas_degenerate_triangles", double(g.link.tables.degenerateTriangles));
    out.counters.emplace_back("bundle_nodes_last", double(g.exchange.nodesLast));
    out.counters.emplace_back("bundle_rebuilds", double(g.exchange.rebuilds));
    return out;
}

} // namespace bl
