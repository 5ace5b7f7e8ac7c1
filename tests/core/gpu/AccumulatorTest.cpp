// The layered accumulator: sums that stay accurate over 10^5 samples, layers by path length,
// the variance of the mean, and NaN/Inf samples counted apart from dropped ones.
#include "gpu/Accumulator.h"
#include "reference/PathTracer.h"
#include "support/VulkanTest.h"
#include "vk/Commands.h"
#include "vk/Descriptors.h"
#include "vk/Pipeline.h"

#include <cmath>
#include <tests/AccumulateTest.h>
#include <tests/accumulate.comp.spv.h>

using namespace bl;

namespace {

constexpr std::uint32_t kSide = 16; // pixels: the sums are per pixel, a few hundred pixels suffice
// Samples per dispatch: llvmpipe (lavapipe) ends any shader loop after 65535 iterations
// (LP_MAX_TGSI_LOOP_ITERATIONS), so longer streams take several dispatches.
constexpr std::uint32_t kSamplesPerDispatch = 25000;

class AccumulatorTest : public test::VulkanTest {
protected:
    // Runs the test shader's `kind` stream of `iterations` samples per pixel into `accum` (kinds
    // whose samples depend on the sample index must fit in one dispatch).
    void feed(const gpu::Accumulator& accum, std::uint32_t kind, std::uint32_t iterations, float value = 0.0f) {
        VkDevice d = ctx().device();
        vk::DescriptorSetLayout layout = vk::makeDescriptorSetLayout(
            d, {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}});
        vk::DescriptorPool pool(d, 1, 1);
        VkDescriptorSet set = pool.allocate(layout.get());
        vk::DescriptorWriter()
            .image(0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, accum.view(), VK_IMAGE_LAYOUT_GENERAL)
            .update(d, set);
        VkDescriptorSetLayout layouts[] = {layout.get()};
        vk::PipelineLayout pipelineLayout =
            vk::makePipelineLayout(d, layouts, sizeof(shader::AccumTestPush), VK_SHADER_STAGE_COMPUTE_BIT);
        vk::Pipeline pipeline = vk::makeComputePipeline(d, kSpv_tests_accumulate_comp, pipelineLayout.get());
        shader::AccumTestPush push{};
        push.kind = kind;
        push.width = kSide;
        push.height = kSide;
        push.value = value;
        ctx().submitAndWait([&](VkCommandBuffer cmd) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout.get(), 0, 1, &set, 0, nullptr);
            const std::uint32_t groups = vk::groupCount(kSide, shader::kAccumTestGroupSize);
            for (std::uint32_t done = 0; done < iterations; done += push.iterations) {
                push.iterations = std::min(kSamplesPerDispatch, iterations - done);
                vkCmdPushConstants(cmd, pipelineLayout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
                vkCmdDispatch(cmd, groups, groups, 1);
                vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT);
            }
        });
    }
    gpu::Accumulator make() { return gpu::Accumulator(ctx(), kSide, kSide, shader::kAccumTestLayers); }
};

const Image& layerNamed(const gpu::AccumulatedImages& images, const std::string& name) {
    for (const auto& [n, image] : images.layers) {
        if (n == name) return image;
    }
    throw std::runtime_error("no layer " + name);
}

// Largest relative error of the mean's red channel against `expected`.
double worstRelativeError(const Image& mean, double expected) {
    double worst = 0.0;
    for (const glm::vec3& p : mean.pixels()) worst = std::max(worst, std::abs(p.x - expected) / expected);
    return worst;
}

} // namespace

TEST_F(AccumulatorTest, LayerNamesAreTheReferences) {
    for (std::uint32_t l = 0; l < shader::kPathLayerCount; ++l) {
        EXPECT_STREQ(gpu::kAccumLayerNames[l], kPathLayerNames[l]);
    }
}

// 10^5 samples of 0.1: a plain float sum reaches ~10^4, where each addition rounds by up to half of
// 2^-10 and the mean drifts by ~1e-4 relative. The compensated sums must keep the mean of identical
// samples at the sample's own float value, to a few ulp.
TEST_F(AccumulatorTest, SumsStayAccurateOverManySamples) {
    constexpr std::uint32_t kSamples = 100000;
    constexpr float kValue = 0.1f;
    constexpr double kCompensatedTolerance = 1e-6; // relative: ~8 float ulp
    constexpr double kPlainDriftAtLeast = 1e-5;    // relative: what the test must be able to see

    gpu::Accumulator plain = make();
    feed(plain, shader::kAccumTestPlain, kSamples, kValue);
    const gpu::AccumulatedImages plainOut = plain.resolve(ctx(), kSamples);
    ASSERT_EQ(plainOut.droppedSamples, 0u) << "every sample must arrive for the comparison to be fair";
    const double plainError = worstRelativeError(plainOut.layers[0].second, kValue);
    EXPECT_GT(plainError, kPlainDriftAtLeast) << "a plain float sum should drift here, or the test proves nothing";

    gpu::Accumulator compensated = make();
    feed(compensated, shader::kAccumTestConstant, kSamples, kValue);
    gpu::AccumulatedImages out = compensated.resolve(ctx(), kSamples);
    EXPECT_LT(worstRelativeError(out.layers[0].second, kValue), kCompensatedTolerance) << "plain sum: " << plainError;
    EXPECT_LT(worstRelativeError(layerNamed(out, "direct"), kValue), kCompensatedTolerance);
    EXPECT_EQ(out.nonFiniteSamples, 0u);
    EXPECT_EQ(out.droppedSamples, 0u);
}

TEST_F(AccumulatorTest, WritesTheModesLayersAndTheirSum) {
    gpu::Accumulator accum = make();
    feed(accum, shader::kAccumTestLayered, 3);
    gpu::AccumulatedImages out = accum.resolve(ctx(), 3);
    std::vector<std::string> names;
    for (const auto& [n, image] : out.layers) names.push_back(n);
    EXPECT_EQ(names, (std::vector<std::string>{"", "emitted", "direct", "indirect2", "variance"}));
    // The shader offers 0.25 (l + 1) to every layer; only the mask's layers count, in the sum too.
    EXPECT_EQ(layerNamed(out, "emitted").at(3, 5), glm::vec3(0.25f));
    EXPECT_EQ(layerNamed(out, "direct").at(3, 5), glm::vec3(0.5f));
    EXPECT_EQ(layerNamed(out, "indirect2").at(3, 5), glm::vec3(1.0f));
    EXPECT_EQ(out.layers[0].second.at(3, 5), glm::vec3(1.75f));
    EXPECT_EQ(layerNamed(out, "variance").at(3, 5), glm::vec3(0.0f)); // identical samples
}

// Uniform samples on [0, 1): the variance of the mean of N is 1 / (12 N).
TEST_F(AccumulatorTest, VarianceOfTheMeanMatchesAUniformDistribution) {
    constexpr std::uint32_t kSamples = 512;
    gpu::Accumulator accum = make();
    feed(accum, shader::kAccumTestUniform, kSamples);
    gpu::AccumulatedImages out = accum.resolve(ctx(), kSamples);
    const double expected = 1.0 / (12.0 * kSamples);
    double ratioSum = 0.0, meanSum = 0.0;
    const Image& variance = layerNamed(out, "variance");
    for (std::size_t i = 0; i < variance.pixelCount(); ++i) {
        ratioSum += variance.pixels()[i].x / expected;
        meanSum += out.layers[0].second.pixels()[i].x;
    }
    const double pixels = double(variance.pixelCount());
    // Each pixel's estimate has a relative standard deviation of sqrt(0.8 / N) ~ 4%; over 256
    // pixels the average's is ~0.25%: 2% is many standard deviations, and a wrong formula (n instead
    // of n - 1, a missing / n, the wrong moment) is off by far more.
    EXPECT_NEAR(ratioSum / pixels, 1.0, 0.02);
    EXPECT_NEAR(meanSum / pixels, 0.5, 0.01);
}

// Per pixel column x and sample i, (x + i) mod 5 = 0 gives NaN, 1 gives nothing: of every five
// samples one is non-finite, one dropped, three added.
TEST_F(AccumulatorTest, CountsNonFiniteAndDroppedSamplesApart) {
    constexpr std::uint32_t kSamples = 10;
    gpu::Accumulator accum = make();
    feed(accum, shader::kAccumTestShortfall, kSamples);
    gpu::AccumulatedImages out = accum.resolve(ctx(), kSamples);
    const std::uint64_t pixels = kSide * kSide;
    EXPECT_EQ(out.nonFiniteSamples, pixels * kSamples / 5);
    EXPECT_EQ(out.droppedSamples, pixels * kSamples / 5);
    EXPECT_EQ(out.layers[0].second.at(7, 2), glm::vec3(1.0f)); // the refused samples never averaged in
    EXPECT_EQ(out.layers[0].second.countNonFinite(), 0u);
}
