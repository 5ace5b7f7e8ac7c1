// The packed texture buffer (core/gpu/PackedTextures.h, shaders/gpu/PackedTextureLookup.glsl)
// against the reference's lookup (sRGB decode, then core/image/BilinearLookup.h with repeat wrap):
// two textures of odd sizes, coordinates inside, outside [0, 1], on texel centres and edges, and
// non-finite ones.
#include "gpu/PackedTextures.h"
#include "image/BilinearLookup.h"
#include "support/VulkanTest.h"
#include "vk/Commands.h"
#include "vk/Descriptors.h"
#include "vk/Pipeline.h"

#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <tests/packed_textures.comp.spv.h>

using namespace bl;

namespace {

Image decode(const Rgba8Image& t) {
    Image img(t.width, t.height);
    for (int i = 0; i < t.width * t.height; ++i) {
        for (int c = 0; c < 3; ++c) img.pixels()[std::size_t(i)][c] = srgbToLinear(t.texels[std::size_t(4 * i + c)] / 255.0f);
    }
    return img;
}

class PackedTexturesTest : public bl::test::VulkanTest {};

} // namespace

TEST_F(PackedTexturesTest, LookupsMatchTheReferencesBilinearLookup) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> byte(0, 255);
    Scene scene;
    for (glm::ivec2 size : {glm::ivec2(5, 3), glm::ivec2(7, 4)}) {
        Rgba8Image t{size.x, size.y, std::vector<unsigned char>(std::size_t(4 * size.x * size.y))};
        for (unsigned char& b : t.texels) b = static_cast<unsigned char>(byte(rng));
        scene.textures.push_back({"random", t});
    }
    gpu::PackedTextures packed(ctx(), scene);
    EXPECT_EQ(packed.bytes(), 4 * gpu::PackedTextures::words(scene));

    std::vector<glm::vec4> queries;
    std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
    for (std::uint32_t t = 0; t < 2; ++t) {
        const float index = std::bit_cast<float>(t);
        for (int i = 0; i < 500; ++i) queries.emplace_back(coordinate(rng), coordinate(rng), index, 0.0f);
        const glm::vec2 size(scene.textures[t].image.width, scene.textures[t].image.height);
        for (float x : {0.0f, 0.5f, 1.0f, 2.5f, -0.5f}) { // texel edges and centres, both axes
            queries.emplace_back(x / size.x, (x + 0.5f) / size.y, index, 0.0f);
            queries.emplace_back(1.0f, 0.0f, index, 0.0f);
        }
        queries.emplace_back(std::numeric_limits<float>::quiet_NaN(), 0.3f, index, 0.0f);
        queries.emplace_back(0.2f, std::numeric_limits<float>::infinity(), index, 0.0f);
    }
    const auto count = static_cast<std::uint32_t>(queries.size());
    vk::Buffer queryBuffer = vk::makeBuffer(ctx(), std::span<const glm::vec4>(queries), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    vk::Buffer results(ctx(), count * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Readback);

    VkDevice device = ctx().device();
    const VkDescriptorType sb = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    vk::DescriptorSetLayout setLayout = vk::makeDescriptorSetLayout(device, {{0, sb, cs}, {1, sb, cs}, {2, sb, cs}});
    vk::DescriptorPool pool(device, 1, 3);
    VkDescriptorSet set = pool.allocate(setLayout.get());
    vk::DescriptorWriter()
        .buffer(0, sb, packed.buffer())
        .buffer(1, sb, queryBuffer.get())
        .buffer(2, sb, results.get())
        .update(device, set);
    VkDescriptorSetLayout layouts[] = {setLayout.get()};
    vk::PipelineLayout layout = vk::makePipelineLayout(device, layouts, sizeof(std::uint32_t), cs);
    vk::Pipeline pipeline = vk::makeComputePipeline(device, kSpv_tests_packed_textures_comp, layout.get());
    ctx().submitAndWait([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout.get(), 0, 1, &set, 0, nullptr);
        vkCmdPushConstants(cmd, layout.get(), cs, 0, sizeof(count), &count);
        vkCmdDispatch(cmd, vk::groupCount(count, 64), 1, 1);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_HOST_BIT);
    });
    const auto* got = static_cast<const glm::vec4*>(results.data());
    const Image linear[] = {decode(scene.textures[0].image), decode(scene.textures[1].image)};
    double worst = 0.0;
    for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t t = std::bit_cast<std::uint32_t>(queries[i].z);
        const glm::vec3 expected = bilinearLookup(linear[t], {queries[i].x, queries[i].y}, Wrap::Repeat, Wrap::Repeat);
        for (int c = 0; c < 3; ++c) {
            const double error = std::abs(double(got[i][c]) - double(expected[c]));
            worst = std::max(worst, error);
            EXPECT_LT(error, 2e-5) << "query " << i << " (" << queries[i].x << ", " << queries[i].y << ") texture " << t
                                   << " channel " << c;
        }
    }
    std::printf("%u lookups, largest difference %.3g\n", count, worst);
}
